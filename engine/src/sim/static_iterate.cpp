#include "static_iterate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sutura::engine::detail {

// Only follower pressure adds a load stiffness (external_forces).
bool has_load_stiffness(const ShellSystem& sys) {
  return !sys.loads.pressures.empty() || !sys.fixed_loads.pressures.empty();
}

double characteristic_length(const ShellState& s) {
  if (s.x.empty()) return 1.0;
  Eigen::AlignedBox3d box;
  for (const auto& p : s.x) box.extend(p);
  return std::max(box.diagonal().norm(), 1e-12);
}

// The residual that coordinate round-off alone leaves (N): 1e-13 E t L with the stiffest
// material's E t and the state's size L (about ten times the floor measured: 1e-14 E t L).
// A state already at equilibrium with no loads (a solve without loads, a slit re-joined with
// no gap) has a round-off first residual and no load, so a tolerance relative to those alone
// could never be met; below this floor the residual is zero to the arithmetic.
double roundoff_residual(const ShellSystem& sys, const ShellState& state) {
  double et = 0.0;
  if (sys.problem.materials)
    for (const ShellMaterial& m : *sys.problem.materials) et = std::max(et, m.youngs_modulus * m.thickness);
  return 1e-13 * et * characteristic_length(state);
}

// A trial state that collapses a triangle further than the current state has (below
// min_area_ratio of its rest area) counts as non-finite, so the line search backs off: the
// floor for trials from `state` (0 = no test).
double collapse_floor(const ShellSystem& sys, const ShellState& state,
                      const StaticSolverParams& params) {
  return params.min_area_ratio > 0.0
             ? std::min(params.min_area_ratio, min_area_ratio(sys.problem, state))
             : 0.0;
}

// The evaluation at `trial` = state + a du_full (with the tangent if asked); a trial below the
// collapse floor gets a NaN energy and residual and sets `collapsed`.
Evaluation evaluate_trial(const ShellSystem& sys, const DofMap& map, const ShellState& state,
                          const Eigen::VectorXd& du_full, double a, double lambda,
                          double area_floor, bool with_tangent, TangentAssembler* assembler,
                          ShellState& trial, bool& collapsed) {
  trial = state;
  apply_increment(trial, a * du_full, sys.dofs_per_node());
  Evaluation e = evaluate(sys, map, trial, lambda, with_tangent, true, assembler);
  if (area_floor > 0.0 && min_area_ratio(sys.problem, trial) < area_floor) {
    collapsed = true;
    e.internal_energy = std::numeric_limits<double>::quiet_NaN();
    e.residual.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return e;
}

// The checks and bookkeeping of every iterate of newton() and minimize(): a non-finite state
// or an exploded energy fails (the message says why), otherwise the iterate goes into the
// history and the result. `work_done` is the loads' work since the start of the load step.
std::string record_iterate(const Evaluation& ev, double lambda, int it, double step_length,
                           double work_done, double energy_scale, bool collapsed_trial,
                           const StaticSolverParams& params, StaticResult& result) {
  const double rnorm = ev.residual.norm();
  if (!std::isfinite(rnorm) || !std::isfinite(ev.internal_energy))
    return collapsed_trial ? "every trial step collapsed a triangle (area below " +
                                 std::to_string(params.min_area_ratio) + " of its rest area)"
                           : "the state became non-finite (NaN/inf)";
  if (ev.internal_energy > params.energy_blowup * energy_scale)
    return "the strain energy exploded (" + std::to_string(ev.internal_energy) + " N*mm)";
  result.history.push_back(
      {lambda, it, rnorm, ev.internal_energy, step_length, ev.internal_energy - work_done});
  result.residual = rnorm;
  result.energy = ev.internal_energy;
  return {};
}

}  // namespace sutura::engine::detail
