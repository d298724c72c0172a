#include "sutura/engine/sim/dynamics.hpp"

#include <cmath>
#include <functional>
#include <sstream>

#include "corotated_damping.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

// A step's failure when DynamicsParams::keep_going said no.
const std::string kStopped = "stopped by the caller";

void check(const DynamicsParams& p) {
  if (!(p.dt > 0.0)) throw InvalidArgument("dt must be > 0");
  if (p.steps < 1) throw InvalidArgument("steps must be at least 1");
  if (p.mass_damping < 0.0) throw InvalidArgument("mass_damping must be >= 0");
  if (p.stiffness_damping < 0.0) throw InvalidArgument("stiffness_damping must be >= 0");
  if (!(p.force_reference >= 0.0)) throw InvalidArgument("force_reference must be >= 0");
  if (!(p.tolerance > 0.0 && p.tolerance < 1.0)) throw InvalidArgument("tolerance must be in (0, 1)");
  if (p.max_iterations < 1) throw InvalidArgument("max_iterations must be at least 1");
  if (p.max_step_cuts < 0 || p.max_step_cuts > 10)
    throw InvalidArgument("max_step_cuts must be in [0, 10]");
  if (!(p.min_area_ratio >= 0.0 && p.min_area_ratio < 1.0))
    throw InvalidArgument("min_area_ratio must be in [0, 1)");
}

}  // namespace

DynamicsResult simulate_dynamics(const ShellSystem& sys, DynamicsState& state,
                                 const DynamicsParams& params, const StepHook& hook) {
  check(params);
  DynamicsResult result;
  const DofMap map(sys);
  const int d = sys.dofs_per_node();
  const Eigen::VectorXd mass = map.restrict(lumped_mass(sys));
  auto solver = make_linear_solver(params.linear_solver, params.pcg);
  if (state.velocity.size() != static_cast<Eigen::Index>(sys.num_dofs()))
    state.velocity = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sys.num_dofs()));

  // Modified Newton: the step matrix A = M (1/h^2 + alpha/h) + (beta/h) K_d + K is factorised
  // once and reused across iterations and steps while it still contracts the residual by at
  // least half per iteration; otherwise it is rebuilt from the current tangent. K_d, the
  // stiffness in the damping term, is the tangent of the last rebuild at the start of a step,
  // turned with the nodes' rotations since (corotated_damping.hpp; the turn is held for the
  // step, so the damping force stays linear in the step's increment). Reuse is what makes a
  // step cost about one gradient evaluation and one back-substitution instead of a full
  // assembly and factorisation. DynamicsScheme::Linearized ends a step at its first iteration
  // that halves the residual without raising the energy.
  TangentAssembler assembler;
  detail::CorotatedDamping damping(sys, map);
  bool have_factor = false;
  // Iterations on a reused matrix solve in single precision (DynamicsParams::
  // single_precision_solves; Cholmod only, the others solve exactly anyway) when the current
  // factorisation's single-precision solve agreed with its first, exact one
  // (approximate_solve_agrees).
  const bool single_precision =
      params.single_precision_solves && params.linear_solver == LinearSolverKind::Cholmod;
  bool approximate_ok = false;
  const bool linearized = params.scheme == DynamicsScheme::Linearized;
  double factor_h = 0.0;  // the step size the factorised matrix was built for
  double energy_scale = 0.0;
  Evaluation ev;

  // One backward Euler step of size h from the current state; returns why it failed ("" if
  // it did not). The caller restores the state after a failure. `from_zero_increment`: Newton
  // starts from zero increment instead of the predictor, its tolerance relative to
  // `retry_ref` (see advance).
  double step_ref = 0.0;  // the reference of the last step_once's tolerance
  const auto step_once = [&](double h, bool from_zero_increment,
                             double retry_ref = -1.0) -> std::string {
    step_ref = retry_ref;
    const double damp_m = 1.0 / (h * h) + params.mass_damping / h;
    const double damp_k = params.stiffness_damping / h;
    if (h != factor_h) have_factor = false;
    const double area_floor =
        params.min_area_ratio > 0.0
            ? std::min(params.min_area_ratio, min_area_ratio(sys.problem, state.shell))
            : 0.0;
    const Eigen::VectorXd v0 = map.restrict(state.velocity);
    // The linearized scheme starts from the evaluation at the end of the last step (its
    // gradient and, for the energy guard, its internal energy; DynamicsScheme::Linearized).
    if (linearized && ev.residual.size() == 0) ev = evaluate(sys, map, state.shell, 1.0, false);
    const ShellState start_shell = linearized ? state.shell : ShellState{};
    const double start_kinetic = 0.5 * v0.dot(mass.cwiseProduct(v0));
    const double start_internal = ev.internal_energy;
    // Bent past kRetakeBend since K_d was taken: the step matrix and K_d are taken anew at
    // this step's start. Without corotated_damping nothing turns (Q = I throughout).
    if (params.corotated_damping &&
        damping.turn_to(state.shell.x) > detail::CorotatedDamping::kRetakeBend)
      have_factor = false;
    // Backward Euler for the increment du = h v1:
    //   R(du) = M (du/h - v0)/h + C du/h + g(x0 + du) - f_ext = 0,  C = alpha M + beta K_d.
    // Newton starts from the constant-velocity predictor du = h v0, which costs a gradient
    // evaluation and saves iterations (3.2 per step on the benchmark tube; 3.5 from du = 0,
    // with a second factorisation). The linearized scheme starts from du = 0, where the
    // gradient is the last step's: its one iteration is then the linearly implicit Euler
    // step of Baraff & Witkin, at one evaluation per step instead of two. It is less accurate
    // than an iteration from the predictor (the error of a reused matrix is a fraction of
    // the increment rather than of the predictor's error) but on the benchmark tube it is
    // 1e-3 of the tip's motion off Newton's, where halving dt moves Newton's by 6 %
    // (docs/performance.md).
    Eigen::VectorXd du;
    if (linearized) {
      du = Eigen::VectorXd::Zero(v0.size());
    } else if (from_zero_increment) {
      du = Eigen::VectorXd::Zero(v0.size());
      ev = evaluate(sys, map, state.shell, 1.0, false);  // a hook may have changed the system
    } else {
      du = h * v0;
      apply_increment(state.shell, map.expand(du), d);
      ev = evaluate(sys, map, state.shell, 1.0, false);
    }
    bool du_zero = du.squaredNorm() == 0.0;  // the damping force of a zero increment is zero
    Eigen::VectorXd damping_force;  // Q K_d Q^T du
    const auto residual = [&]() -> Eigen::VectorXd {
      Eigen::VectorXd R = mass.cwiseProduct(du * damp_m - v0 / h) + ev.residual;
      if (damp_k != 0.0 && !damping.empty() && !du_zero) {
        damping.apply(du, damping_force);
        R += damp_k * damping_force;
      }
      return R;
    };
    double ref = retry_ref, previous = -1.0;
    // K_d may only change at the start of a step: changing it mid-step would move the root of
    // R while Newton chases it. Within a step the step matrix takes the step's turned K_d.
    const auto rebuild = [&](bool new_damping) {
      const Evaluation full = evaluate(sys, map, state.shell, 1.0, true, true, &assembler);
      if (new_damping || damping.empty()) damping.reset(full.tangent, state.shell.x);
      Eigen::SparseMatrix<double> A = full.tangent + damp_k * damping.matrix();
      A.diagonal() += mass * damp_m;
      have_factor = solver->factorize(A);
      factor_h = h;
      ++result.factorizations;
      return have_factor;
    };
    for (int it = 0;; ++it) {
      if (params.keep_going && !params.keep_going()) return kStopped;
      Eigen::VectorXd R = residual();
      double rnorm = R.norm();
      if (!std::isfinite(rnorm) || !std::isfinite(ev.internal_energy))
        return "the state became non-finite (NaN/inf)";
      if (ref < 0.0) ref = std::max({rnorm, ev.external_norm, params.force_reference, 1e-300});
      step_ref = ref;
      if (rnorm <= params.tolerance * ref) break;
      if (linearized && it > 0 && rnorm <= 0.5 * previous) {
        const double kinetic = 0.5 * du.dot(mass.cwiseProduct(du)) / (h * h);
        const double gain = kinetic - start_kinetic + ev.internal_energy - start_internal -
                            external_work(sys, start_shell, state.shell, 1.0);
        if (gain <= 1e-12 * energy_scale) break;  // round-off at rest may not stop a step
      }
      if (it == params.max_iterations) {
        std::ostringstream m;
        m << "Newton did not converge in " << params.max_iterations << " iterations (residual "
          << rnorm << ")";
        return m.str();
      }
      // A matrix that no longer halves the residual is stale: rebuild it here, before it is
      // used, from the tangent at the current iterate (then this is a full Newton step).
      bool fresh = false;
      if (!have_factor || (previous > 0.0 && rnorm > 0.5 * previous)) {
        if (!rebuild(it == 0)) return "the step matrix is singular";
        R = residual();  // the damping term changed with K_d
        rnorm = R.norm();
        fresh = true;
      }
      previous = rnorm;
      Eigen::VectorXd delta;
      const bool exact = fresh || !approximate_ok;
      // The reused matrix, factorised at the damping's reference, turned with the nodes'
      // rotations since (CorotatedDamping::turn).
      const bool turn = damping.turned();
      Eigen::VectorXd rhs = -R;
      if (turn) damping.turn(true, rhs);
      if (!(exact ? solver->solve(rhs, delta) : solver->solve_approximately(rhs, delta)))
        return "the linear solve failed: " + solver->last_note();
      if (turn) damping.turn(false, delta);
      if (fresh) approximate_ok = single_precision && approximate_solve_agrees(*solver, -R, delta);
      du += delta;
      du_zero = false;
      apply_increment(state.shell, map.expand(delta), d);
      ev = evaluate(sys, map, state.shell, 1.0, false);
      ++result.newton_iterations;
    }
    if (area_floor > 0.0 && min_area_ratio(sys.problem, state.shell) < area_floor)
      return "a triangle collapsed (area below " + std::to_string(params.min_area_ratio) +
             " of its rest area)";
    state.velocity = map.expand(du / h);
    const double kinetic = 0.5 * du.dot(mass.cwiseProduct(du)) / (h * h);
    const double total = kinetic + ev.internal_energy;
    if (energy_scale > 0.0 && total > 1e12 * energy_scale)
      return "the energy exploded (" + std::to_string(total) + " N*mm)";
    energy_scale = std::max(energy_scale, total);
    result.kinetic_energy = kinetic;
    result.strain_energy = ev.internal_energy;
    result.residual = ev.residual.norm();
    return {};
  };

  // A step of size h, retried as two steps of h/2 (recursively) when it fails. Why: a step
  // through a sharp change (a fold snapping through, a contact) may need a smaller step only
  // there; a fixed dt would have to be small for the whole run.
  std::function<std::string(double, int)> advance = [&](double h, int depth) -> std::string {
    const DynamicsState start = state;
    const Evaluation ev_start = ev;
    std::string failure = step_once(h, false);
    if (failure.empty()) return {};
    state = start;
    ev = ev_start;
    // Newton that failed from the constant-velocity predictor is tried once more from zero
    // increment before the step is cut. Why: where the shell turns fast, the predictor moves
    // its nodes along straight lines and stretches it; on a heavy strip swinging up
    // (Dynamics.NewtonRetriesAFailedStepFromZeroIncrement) the stiff membrane's reaction to
    // that stretch sent Newton off, in one run even at dt/16, where from zero increment it
    // converged.
    if (failure == kStopped) return failure;  // rolled back above; no retry, no cut
    // The retry starts on a new step matrix (the failed attempt's was taken on its way off)
    // and keeps the attempt's tolerance: measured against the residual at zero increment,
    // which holds the inertia M v0 / h, it would be looser.
    if (!linearized && state.velocity.squaredNorm() > 0.0) {
      have_factor = false;
      const std::string retry = step_once(h, true, step_ref);
      if (retry.empty()) {
        ++result.restarts;
        return {};
      }
      failure += "; from zero increment: " + retry;
      state = start;
      ev = ev_start;
    }
    if (depth == params.max_step_cuts) return failure;
    ++result.step_cuts;
    for (int half = 0; half < 2; ++half) {
      failure = advance(0.5 * h, depth + 1);
      if (!failure.empty()) {
        state = start;
        ev = ev_start;
        return failure;
      }
    }
    return {};
  };

  for (int step = 0; step < params.steps; ++step) {
    if (hook && !hook(step)) break;
    const std::string failure = advance(params.dt, 0);
    if (!failure.empty()) {
      result.ok = false;
      result.stopped = failure == kStopped;
      std::ostringstream m;
      m << "dynamics step " << step + 1 << " of " << params.steps << " failed";
      if (params.max_step_cuts > 0) m << " (also in sub-steps down to dt/" << (1 << params.max_step_cuts) << ")";
      m << ": " << failure << "; rolled back to the state after step " << step;
      result.message = m.str();
      return result;
    }
    ++result.steps_done;
  }
  return result;
}

}  // namespace sutura::engine
