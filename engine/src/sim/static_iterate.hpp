#pragma once
// The iterations of the static solver at one load factor, shared by its driver
// (static_solver.cpp): Newton with a lenient line search (static_newton.cpp) and energy
// minimisation with shifted factorisations and quasi-Newton steps (static_minimize.cpp), and
// the checks and bookkeeping they have in common (static_iterate.cpp). Private to the engine.
#include <string>

#include "sutura/engine/sim/static_solver.hpp"

namespace sutura::engine::detail {

/// A load step's failure when StaticSolverParams::keep_going said no.
inline const std::string kStopped = "stopped by the caller";

/// Whether the loads add a load stiffness (only follower pressure does: external_forces).
bool has_load_stiffness(const ShellSystem& sys);

/// The diagonal of the bounding box of the state's nodes, mm (1 for no node). O(nodes).
double characteristic_length(const ShellState& s);

/// The residual that coordinate round-off alone leaves, N (static_iterate.cpp says why).
double roundoff_residual(const ShellSystem& sys, const ShellState& state);

/// The area floor (fraction of rest area) below which a trial from `state` counts as collapsed:
/// min(min_area_ratio, the state's own smallest ratio), 0 = no test.
double collapse_floor(const ShellSystem& sys, const ShellState& state, const StaticSolverParams& params);

/// The evaluation at `trial` = state + a du_full (with the tangent if asked); a trial below
/// the collapse floor gets a NaN energy and residual and sets `collapsed`.
Evaluation evaluate_trial(const ShellSystem& sys, const DofMap& map, const ShellState& state,
                          const Eigen::VectorXd& du_full, double a, double lambda,
                          double area_floor, bool with_tangent, TangentAssembler* assembler,
                          ShellState& trial, bool& collapsed);

/// Records an iterate in `result` (history, residual, energy); returns why it fails instead
/// (non-finite, collapsed, exploded), empty when it does not.
std::string record_iterate(const Evaluation& ev, double lambda, int it, double step_length,
                           double work_done, double energy_scale, bool collapsed_trial,
                           const StaticSolverParams& params, StaticResult& result);

/// Newton iterations at the load factor `lambda`: empty on convergence, else why not (the
/// caller restores the state). Convergence and line search: static_newton.cpp.
std::string newton(const ShellSystem& sys, const DofMap& map, ShellState& state, double lambda,
                   const StaticSolverParams& params, LinearSolver& solver, double energy_scale,
                   StaticResult& result, TangentAssembler& assembler,
                   TangentAssembler& internal_assembler);

/// Energy minimisation at the load factor `lambda` (shift_indefinite): empty on convergence
/// (the factorisation then left in `ws`), else why not. static_minimize.cpp.
std::string minimize(const ShellSystem& sys, const DofMap& map, ShellState& state, double lambda,
                     const StaticSolverParams& params, LinearSolver& solver, double energy_scale,
                     StaticResult& result, SolverWorkspace& ws);

}  // namespace sutura::engine::detail
