#include "sutura/engine/sim/dynamics.hpp"

#include <cmath>
#include <sstream>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

void check(const DynamicsParams& p) {
  if (!(p.dt > 0.0)) throw InvalidArgument("dt must be > 0");
  if (p.steps < 1) throw InvalidArgument("steps must be at least 1");
  if (p.mass_damping < 0.0) throw InvalidArgument("mass_damping must be >= 0");
  if (p.stiffness_damping < 0.0) throw InvalidArgument("stiffness_damping must be >= 0");
  if (!(p.tolerance > 0.0 && p.tolerance < 1.0)) throw InvalidArgument("tolerance must be in (0, 1)");
  if (p.max_iterations < 1) throw InvalidArgument("max_iterations must be at least 1");
}

}  // namespace

DynamicsResult simulate_dynamics(const ShellSystem& sys, DynamicsState& state,
                                 const DynamicsParams& params, const StepHook& hook) {
  check(params);
  DynamicsResult result;
  const DofMap map(sys);
  const int d = sys.dofs_per_node();
  const double h = params.dt;
  const Eigen::VectorXd mass = map.restrict(lumped_mass(sys));
  auto solver = make_linear_solver(params.linear_solver, params.pcg);
  if (state.velocity.size() != static_cast<Eigen::Index>(sys.num_dofs()))
    state.velocity = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sys.num_dofs()));

  double energy_scale = 0.0;
  for (int step = 0; step < params.steps; ++step) {
    if (hook && !hook(step)) break;
    const DynamicsState start = state;
    const Eigen::VectorXd v0 = map.restrict(state.velocity);
    Eigen::VectorXd du = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(map.num_free()));
    // Backward Euler for the increment du = h v1:
    //   R(du) = M (du/h - v0)/h + C du/h + g(x0 + du) - f_ext = 0,  C = alpha M + beta K0,
    //   dR/du = M/h^2 + C/h + K(x0 + du).
    // K0, the tangent at the start of the step, freezes the stiffness-proportional damping so
    // the damping force stays linear in the velocity.
    Evaluation ev = evaluate(sys, map, state.shell, 1.0, true);
    const Eigen::SparseMatrix<double> K0 = ev.tangent;
    const double damp_m = 1.0 / (h * h) + params.mass_damping / h;
    const double damp_k = params.stiffness_damping / h;
    std::string failure;
    double ref = -1.0;
    for (int it = 0;; ++it) {
      Eigen::VectorXd R = mass.cwiseProduct(du * damp_m - v0 / h) + damp_k * (K0 * du) + ev.residual;
      const double rnorm = R.norm();
      if (!std::isfinite(rnorm) || !std::isfinite(ev.internal_energy)) {
        failure = "the state became non-finite (NaN/inf)";
        break;
      }
      if (ref < 0.0) ref = std::max({rnorm, ev.external_norm, 1e-300});
      if (rnorm <= params.tolerance * ref) break;
      if (it == params.max_iterations) {
        std::ostringstream m;
        m << "Newton did not converge in " << params.max_iterations << " iterations (residual "
          << rnorm << ")";
        failure = m.str();
        break;
      }
      Eigen::SparseMatrix<double> A = ev.tangent + damp_k * K0;
      A.diagonal() += mass * damp_m;
      if (!solver->factorize(A)) {
        failure = "the step matrix is singular";
        break;
      }
      Eigen::VectorXd delta;
      if (!solver->solve(-R, delta)) {
        failure = "the linear solve failed: " + solver->last_note();
        break;
      }
      du += delta;
      apply_increment(state.shell, map.expand(delta), d);
      ev = evaluate(sys, map, state.shell, 1.0, true);
      ++result.newton_iterations;
    }
    if (failure.empty()) {
      state.velocity = map.expand(du / h);
      const double kinetic = 0.5 * du.dot(mass.cwiseProduct(du)) / (h * h);
      const double total = kinetic + ev.internal_energy;
      if (energy_scale > 0.0 && total > 1e12 * energy_scale)
        failure = "the energy exploded (" + std::to_string(total) + " N*mm)";
      energy_scale = std::max(energy_scale, total);
      result.kinetic_energy = kinetic;
      result.strain_energy = ev.internal_energy;
      result.residual = ev.residual.norm();
    }
    if (!failure.empty()) {
      state = start;
      result.ok = false;
      std::ostringstream m;
      m << "dynamics step " << step + 1 << " of " << params.steps << " failed: " << failure
        << "; rolled back to the state after step " << step;
      result.message = m.str();
      return result;
    }
    ++result.steps_done;
  }
  return result;
}

}  // namespace sutura::engine
