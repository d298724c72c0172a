#pragma once
// Rest-shape relaxation (paper, Sec. 2.3). After a suture the joined shape x starts far from
// the split rest shape x0; a second rest shape y0, congruent with x but with split edges, makes
// the start stress-free, and the solver then runs while the rest shape moves linearly from y0
// to x0: rest(s) = lerp(y0, x0, s), s from 0 to 1 (rest_at below). The shell model is never modified.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/sim/dynamics.hpp"
#include "sutura/engine/sim/stability.hpp"
#include "sutura/engine/sim/static_solver.hpp"

namespace sutura::engine {

/// y0 after an edit: for every face with `congruent[f]` set, the rest element congruent with
/// the current state (rest_from_state); every other face keeps `base` (its current rest).
/// `congruent` has one entry per face; faces touching a sutured vertex and newly added patch
/// faces are the ones to set. Throws InvalidArgument on size mismatches.
RestState congruent_rest(const std::vector<FaceIndices>& faces, const ShellState& state,
                         const RestState& base, const std::vector<bool>& congruent);

/// The rest shape at relaxation parameter s in [0, 1]: per element, x0's triangle is first
/// moved rigidly onto y0's (same centroid, same element frame) and then the corners are
/// interpolated linearly and the triads by slerp. Elements only see their intrinsic rest shape,
/// so the rigid move changes nothing physical, but it keeps every interpolated triangle
/// non-degenerate: two triangles with the same frame have their third corner on the same side
/// of the first edge, while a plain lerp between a patch cut flat somewhere else and its place
/// on the vessel can pass through a zero-area triangle. s = 0 gives y0 and s = 1 gives x0,
/// exactly. Throws InvalidArgument on an element-count mismatch. Cost O(F).
RestState rest_at(const RestState& y0, const RestState& x0, double s);

enum class RelaxationSolver {
  Static,   ///< a quasi-static Newton solve at each s (fast; needs a constrained structure)
  Dynamic,  ///< implicit Euler steps while s advances (the paper's choice; works unconstrained)
};

/// Parses "static" | "dynamic"; throws InvalidArgument otherwise.
RelaxationSolver parse_relaxation_solver(const std::string& name);

struct RelaxationParams {
  RelaxationSolver solver = RelaxationSolver::Static;
  int steps = 10;          ///< >= 1: increments of s from s_start to s_end (static) or dynamics steps over which s advances
  double s_start = 0.0;    ///< where the rest shape is now, in [0, 1]
  double s_end = 1.0;      ///< where to stop, in [s_start, 1]; < 1 leaves the relaxation part-way
  /// After s_end = 1 is reached: Dynamic runs `settle_steps` more steps; then (both solvers) a
  /// static solve brings the shape to a tight equilibrium, its residual measured against the
  /// support reactions (skipped for a structure without supports, which would be singular).
  bool settle = true;
  int settle_steps = 20;   ///< >= 0, Dynamic only
  int max_cuts = 6;        ///< a failed static increment is retried with half the increment, down to 2^-max_cuts of the planned one (two good increments double it again)
  /// Relative Newton tolerance of the intermediate static increments, in (0, 1): they only
  /// carry the shape along the path; the last increment and the settling solve use
  /// statics.tolerance.
  double increment_tolerance = 1e-6;
  /// Static only: start each increment (from the third on) at the state extrapolated from the
  /// last two converged ones (secant predictor of path following), when that has the lower total
  /// potential energy at the new rest shape and collapses no triangle; otherwise at the last
  /// converged state. Costs two energy evaluations per increment.
  bool predictor = true;
  /// After the settling solve: test whether the final shape is a stable equilibrium
  /// (check_stability: one more tangent and Cholesky factorisation, and an LDL^T count of the
  /// unstable modes if it is not). Needs supports (the settling solve runs only then).
  bool check_stability = true;
  /// With check_stability and the Cholmod solver, when the settled shape has unstable modes (a
  /// symmetric configuration held on an unstable branch, e.g. a wall compressed but perfectly
  /// flat, which nothing in the energy pushes sideways): perturb it along a direction of
  /// negative curvature (unstable_mode; by at most a fifth of the mean rest edge length and
  /// 0.1 rad, the sign that lowers the potential) and settle again, at most this often, >= 0.
  /// The result is the shape the tissue would buckle into (of mirror-image shapes, the one the
  /// perturbation picks). Each escape is reported to the hook as phase "escape". A static
  /// increment that fails from an unstable start (converging onto the saddle only linearly) is
  /// likewise retried from the pushed shape before it is halved; those pushes count too. 0:
  /// only report.
  int max_escapes = 3;
  /// Dynamic only, t/mm^3, > 0 when set: the density of the relaxation's dynamics in place of
  /// every material's own. The dynamics only carry the rest shape through s; their mass sets
  /// the pace of that path (inertia against buckling at a given dt), not the equilibrium, so a
  /// plan can choose it without a fictitious density in the material. Unset: the materials'.
  std::optional<double> density;
  StaticSolverParams statics;   ///< per increment (lambda fixed at 1: loads stay applied)
  DynamicsParams dynamics;      ///< dt, damping, tolerances (steps is ignored)
};

struct RelaxationProgress {
  double s = 0.0;          ///< current rest-shape parameter
  int step = 0;            ///< increments or dynamics steps done
  int steps = 0;           ///< planned (static: done + what the current increment size needs)
  double residual = 0.0;   ///< |r| over free DOFs (static residual)
  double energy = 0.0;     ///< strain energy, N*mm
  std::string phase;       ///< "relax", "settle", "escape" or "retry" (a failed increment, halved)
  int newton_iterations = 0;  ///< Newton iterations of this increment or step (retries included)
  int quasi_newton_iterations = 0;  ///< static: quasi-Newton steps of this increment (StaticResult)
};
/// Called after every increment/step and failed increment; return false to cancel (the state is
/// kept as it is: the last converged one).
using RelaxationHook = std::function<bool(const RelaxationProgress&)>;

struct RelaxationResult {
  bool ok = false;
  /// The hook returned false, or statics.keep_going / dynamics.keep_going did (asked before
  /// every Newton iteration, escape and stability check): the state is the last converged one.
  bool cancelled = false;
  double s_reached = 0.0;
  int newton_iterations = 0;
  /// Static: steps that reused a factorisation (StaticSolverParams::quasi_newton_steps), in
  /// the increments, the settling and the escapes; newton_iterations counts the others.
  int quasi_newton_iterations = 0;
  /// Newton iterations of the static increments and the settling whose tangent was not
  /// positive definite (StaticResult::indefinite_iterations: a diagnostic of the solve, e.g.
  /// iterates with compressed elements; it does not mean an equilibrium on the way was
  /// unstable). The dynamic phase of a Dynamic relaxation is not counted (its matrix, mass
  /// over dt^2 plus K, stays definite).
  int indefinite_iterations = 0;
  double residual = 0.0;
  double energy = 0.0;
  /// The final shape's stability (check_stability), when checked: after a settling solve.
  std::optional<Stability> stability;
  /// How often an unstable shape was pushed along an unstable mode (max_escapes: a failed
  /// increment's start, or the settled shape), and the stability the final check found before
  /// the first push of the settled shape (unset when that was stable at once).
  int escapes = 0;
  std::optional<Stability> stability_before_escapes;
  std::vector<RelaxationProgress> history;
  std::string message;  ///< why it stopped early (the state is the last good one)
};

/// Runs the relaxation on `sys`, whose problem.rest must point at `rest` (overwritten with
/// rest_at(y0, x0, s) as s advances; on return it holds the rest shape at s_reached). `state`
/// is updated in place; on failure it is the last converged state. Throws InvalidArgument for
/// invalid parameters or mismatched sizes.
RelaxationResult relax(const ShellSystem& sys, RestState& rest, const RestState& y0,
                       const RestState& x0, ShellState& state, const RelaxationParams& params,
                       const RelaxationHook& hook = {});

}  // namespace sutura::engine
