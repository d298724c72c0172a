#pragma once
// Unloaded (zero-pressure) reference geometry by the backward-displacement method (Bols et al.,
// J. Comput. Appl. Math. 2013): a vessel segmented from CT or MRI was imaged under blood
// pressure, so its imaged shape x* is an equilibrium under that pressure, not a stress-free
// body. unload finds the rest shape X whose equilibrium under the loads is x*:
//
//   X_0 = x*;  x_k = equilibrium with rest X_k (a static solve);  X_{k+1} = X_k + a (x* - x_k)
//
// until max_i |x*_i - x_k,i| <= tolerance. The rest of every element is congruent with the
// vertex field X (rest_from_state with identity triads), so the object's earlier rest shape is
// replaced: unload applies to a body whose rest is one vertex field (a vessel before any
// edit), not to one carrying a suture's 1:n rest mapping.
//
// The plain fixed point converges linearly, and slowly where the wall is soft in bending
// (measured in docs/validation.md). Each update is therefore
// Anderson-accelerated (Walker & Ni 2011, type II, the last `acceleration_depth` steps): the
// least-squares combination of the last steps whose deviations best cancel the current one.
// When the largest deviation grows, the history restarts and the step a is halved for the
// updates after it (down to 1/16); a forward solve that fails is retried from the last
// equilibrium with half the step, unaccelerated. Deterministic: the same inputs give
// bit-identical results (column-pivoting QR, no threads of its own).
#include <string>
#include <vector>

#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/sim/shell_system.hpp"
#include "sutura/engine/sim/static_solver.hpp"

namespace sutura::engine {

struct UnloadParams {
  /// Forward solves at most (the first ramps the loads in from zero, each later one starts at
  /// the previous equilibrium with the updated rest shape), >= 1.
  int max_iterations = 20;
  /// mm, >= 0: converged when every vertex of the equilibrium is this close to its target.
  /// 0 = 1 % of the target's mean edge length.
  double tolerance = 0.0;
  /// Anderson acceleration's depth: how many earlier steps each update combines, >= 0
  /// (0 = the plain backward-displacement update).
  int acceleration_depth = 5;
  /// Every forward solve's settings. lambda_start and lambda_end are set by unload; keep_going
  /// is asked by each solve (a time limit).
  StaticSolverParams solver;
};

struct UnloadIteration {
  double max_deviation = 0.0;  ///< mm: max over vertices of |x* - x_k|
  double rms_deviation = 0.0;  ///< mm
  int solver_iterations = 0;   ///< of this forward solve (Newton + quasi-Newton)
  double step = 1.0;           ///< a of the update that produced this iteration's rest shape
  bool solved = true;          ///< false: the forward solve failed and was retried
  bool accelerated = false;    ///< its rest shape came from an Anderson update
};

struct UnloadResult {
  bool converged = false;
  bool stopped = false;   ///< a forward solve's keep_going said no
  std::string message;    ///< empty when converged
  double tolerance = 0.0; ///< mm, the one used
  /// The unloaded shape X (per vertex), the rest state congruent with it (identity rest
  /// triads), and the equilibrium under the loads with that rest (within `tolerance` of the
  /// target when converged). Filled only when converged.
  std::vector<Vec3> rest_positions;
  RestState rest;
  ShellState state;
  double max_deviation = 0.0;  ///< mm: of the last equilibrium from the target
  double rms_deviation = 0.0;
  double max_unloading = 0.0;  ///< mm: max |x* - X|, how far the loads move the unloaded shape
  int solver_iterations = 0;   ///< summed over every forward solve
  std::vector<UnloadIteration> history;
};

/// Finds the rest shape of `sys`'s faces (its problem.rest is ignored) whose equilibrium under
/// the system's loads, every one at full value (sys.loads ramped from zero in the first
/// solve's load steps, sys.fixed_loads with them), is `target` (one position per node). Fixed
/// DOFs keep their target values. `workspace` (optional) is shared by every forward solve.
/// Throws InvalidArgument for a target of the wrong size or invalid parameters. Cost: about
/// one loaded solve plus a few corrections (docs/performance.md).
UnloadResult unload(const ShellSystem& sys, const std::vector<Vec3>& target,
                    const UnloadParams& params, SolverWorkspace* workspace = nullptr);

}  // namespace sutura::engine
