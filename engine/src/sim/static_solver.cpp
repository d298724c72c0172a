#include "sutura/engine/sim/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "static_iterate.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

using detail::characteristic_length;
using detail::kStopped;

void check(const StaticSolverParams& p) {
  if (!std::isfinite(p.lambda_start) || !std::isfinite(p.lambda_end))
    throw InvalidArgument("load factors must be finite");
  if (p.load_steps < 1) throw InvalidArgument("load_steps must be at least 1");
  if (!(p.energy_reference >= 0.0)) throw InvalidArgument("energy_reference must be >= 0");
  if (!(p.force_reference >= 0.0)) throw InvalidArgument("force_reference must be >= 0");
  if (!(p.tolerance > 0.0 && p.tolerance < 1.0)) throw InvalidArgument("tolerance must be in (0, 1)");
  if (p.max_iterations < 1) throw InvalidArgument("max_iterations must be at least 1");
  if (p.max_step_cuts < 0) throw InvalidArgument("max_step_cuts must be >= 0");
  if (!(p.min_area_ratio >= 0.0 && p.min_area_ratio < 1.0))
    throw InvalidArgument("min_area_ratio must be in [0, 1)");
  if (!(p.energy_blowup > 1.0)) throw InvalidArgument("energy_blowup must be > 1");
  if (p.quasi_newton_steps < 0) throw InvalidArgument("quasi_newton_steps must be >= 0");
}

StaticResult linear_solve(const ShellSystem& sys, const DofMap& map, ShellState& state,
                          const StaticSolverParams& params, LinearSolver& solver,
                          TangentAssembler& assembler) {
  StaticResult result;
  const Evaluation ev = evaluate(sys, map, state, params.lambda_end, true, false, &assembler);
  result.history.push_back(
      {params.lambda_end, 0, ev.residual.norm(), ev.internal_energy, 1.0, ev.internal_energy});
  Eigen::VectorXd du;
  if (!solver.factorize(ev.tangent)) {
    result.message = "linear solve: the stiffness matrix is singular (is the structure constrained?)";
    return result;
  }
  if (!solver.solve(-ev.residual, du) || !du.allFinite()) {
    result.message = "linear solve failed: " + solver.last_note();
    return result;
  }
  const ShellState start = state;
  apply_increment(state, map.expand(du), sys.dofs_per_node());
  const Evaluation after = evaluate(sys, map, state, params.lambda_end, false);
  result.converged = true;
  result.iterations = 1;
  result.lambda_reached = params.lambda_end;
  result.residual = after.residual.norm();  // non-zero: the nonlinear residual of the linear answer
  result.energy = after.internal_energy;
  result.history.push_back({params.lambda_end, 1, result.residual, result.energy, 1.0,
                            result.energy - external_work(sys, start, state, params.lambda_end)});
  return result;
}

}  // namespace

void SolverWorkspace::keep_factor(Eigen::Index num_free) {
  reusable_factor_ = solver_ ? solver_->definite_factor_id() : 0;
  reusable_size_ = num_free;
}

bool SolverWorkspace::holds_reusable_factor(Eigen::Index num_free) const {
  return solver_ && reusable_factor_ != 0 && reusable_factor_ == solver_->definite_factor_id() &&
         reusable_size_ == num_free;
}

LinearSolver& SolverWorkspace::solver(LinearSolverKind kind, const PcgParams& pcg) {
  const bool same_pcg =
      pcg.tolerance == pcg_.tolerance && pcg.max_iterations == pcg_.max_iterations;
  if (!solver_ || kind != kind_ || (kind == LinearSolverKind::Pcg && !same_pcg)) {
    solver_ = make_linear_solver(kind, pcg);
    kind_ = kind;
    pcg_ = pcg;
  }
  return *solver_;
}

bool factorize_for_quasi_newton(const ShellSystem& sys, const ShellState& state, double lambda,
                                SolverWorkspace& workspace) {
  const DofMap map(sys);
  LinearSolver& solver = workspace.solver(LinearSolverKind::Cholmod, {});
  const Evaluation ev = evaluate(sys, map, state, lambda, true, true, &workspace.assembler());
  if (!solver.factorize_definite(ev.tangent)) return false;
  workspace.keep_factor(static_cast<Eigen::Index>(map.num_free()));
  return true;
}

StaticResult solve_static(const ShellSystem& sys, ShellState& state, const StaticSolverParams& params,
                          SolverWorkspace* workspace) {
  check(params);
  const DofMap map(sys);
  SolverWorkspace local;
  SolverWorkspace& ws = workspace != nullptr ? *workspace : local;
  LinearSolver& solver = ws.solver(params.linear_solver, params.pcg);
  TangentAssembler& assembler = ws.assembler();
  if (params.linear) return linear_solve(sys, map, state, params, solver, assembler);
  StaticResult result;
  ShellState good = state;
  // t runs from 0 to 1; the load factor is lambda_start + t * (lambda_end - lambda_start).
  const auto lambda_at = [&](double t) {
    return params.lambda_start + t * (params.lambda_end - params.lambda_start);
  };
  double t_done = 0.0;
  double dt = 1.0 / params.load_steps;
  int cuts = 0;
  // Energies are compared against the largest converged energy, floored by the work scale of
  // the full load over the structure's size so the first step has a meaningful reference.
  // Loads already at full value count too: a solve after an edit ramps no new load but
  // starts out of equilibrium under the old ones (an incision releasing the hoop stress of an
  // inflated vessel), and without them the reference would be zero.
  Eigen::VectorXd f;
  external_forces(sys.problem, state, sys.loads,
                  std::max(std::abs(params.lambda_start), std::abs(params.lambda_end)),
                  sys.dofs_per_node(), f, nullptr);
  double force = f.norm();
  if (!sys.fixed_loads.empty()) {
    external_forces(sys.problem, state, sys.fixed_loads, 1.0, sys.dofs_per_node(), f, nullptr);
    force += f.norm();
  }
  double energy_scale =
      std::max({force * characteristic_length(state), params.energy_reference, 1e-30});
  // The start state's own strain energy floors the reference too: a solve without loads from a
  // stressed shape (a sutured vessel settling after a remesh, not quite in equilibrium) starts
  // with it, and without it the first iterate's energy would read as an explosion. It only
  // loosens the check (a start whose energy is already huge makes it weak for that solve; the
  // non-finite and collapse tests still hold). One evaluation, O(F).
  const double start_energy = evaluate(sys, map, state, params.lambda_start, false).internal_energy;
  if (std::isfinite(start_energy)) energy_scale = std::max(energy_scale, start_energy);
  // A load-stepped energy minimisation starts its quasi-Newton steps from the tangent at the
  // start, where `state` is in equilibrium at lambda_start (positive definite if that is
  // stable: for an unloaded start the small-displacement stiffness, and the load stiffness of
  // pressure is zero there). Without it the first tangent is the one at the first load
  // step's level, indefinite where pressure acts on a still unstressed shell.
  const bool quasi_newton = params.shift_indefinite &&
                            params.linear_solver == LinearSolverKind::Cholmod &&
                            params.quasi_newton_steps > 0;
  if (quasi_newton && params.lambda_start != params.lambda_end &&
      !ws.holds_reusable_factor(static_cast<Eigen::Index>(map.num_free())))
    factorize_for_quasi_newton(sys, state, params.lambda_start, ws);
  while (t_done < 1.0 - 1e-12) {
    const double t = std::min(1.0, t_done + dt);
    const double lambda = lambda_at(t);
    const std::string why =
        params.shift_indefinite
            ? detail::minimize(sys, map, state, lambda, params, solver, energy_scale, result, ws)
            : detail::newton(sys, map, state, lambda, params, solver, energy_scale, result, assembler,
                     ws.internal_assembler());
    if (why.empty()) {
      t_done = t;
      good = state;
      energy_scale = std::max(energy_scale, result.energy);
      continue;
    }
    state = good;  // roll back to the last converged load step
    result.stopped = why == kStopped;
    if (result.stopped || cuts == params.max_step_cuts) {
      std::ostringstream m;
      m << "static solve failed at load factor " << lambda << ": " << why
        << "; rolled back to the last converged load factor " << lambda_at(t_done);
      result.message = m.str();
      result.lambda_reached = lambda_at(t_done);
      return result;
    }
    ++cuts;
    dt *= 0.5;
  }
  result.converged = true;
  result.lambda_reached = params.lambda_end;
  return result;
}

}  // namespace sutura::engine

