#include "sutura/engine/sim/dynamics.hpp"

#include <cmath>
#include <memory>
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

// The backward Euler steps of one simulate_dynamics call: the state they advance, and what
// the steps share.
//
// Modified Newton: the step matrix A = M (1/h^2 + alpha/h) + (beta/h) K_d + K is factorised
// once and reused across iterations and steps while it still contracts the residual by at
// least half per iteration; otherwise it is rebuilt from the current tangent. K_d, the
// stiffness in the damping term, is the tangent of the last rebuild at the start of a step,
// turned with the nodes' rotations since (corotated_damping.hpp; the turn is held for the
// step, so the damping force stays linear in the step's increment). Reuse is what makes a
// step cost about one gradient evaluation and one back-substitution instead of a full
// assembly and factorisation. DynamicsScheme::Linearized ends a step at its first iteration
// that halves the residual without raising the energy.
class Integrator {
 public:
  Integrator(const ShellSystem& sys, DynamicsState& state, const DynamicsParams& params,
             DynamicsResult& result)
      : sys_(sys),
        state_(state),
        params_(params),
        result_(result),
        map_(sys),
        d_(sys.dofs_per_node()),
        mass_(map_.restrict(lumped_mass(sys))),
        solver_(make_linear_solver(params.linear_solver, params.pcg)),
        damping_(sys, map_),
        single_precision_(params.single_precision_solves &&
                          params.linear_solver == LinearSolverKind::Cholmod),
        linearized_(params.scheme == DynamicsScheme::Linearized) {}

  // A step of size h, retried as two steps of h/2 (recursively) when it fails. Why: a step
  // through a sharp change (a fold snapping through, a contact) may need a smaller step only
  // there; a fixed dt would have to be small for the whole run. Returns why it failed ("" if
  // it did not), the state rolled back to the step's start.
  std::string advance(double h, int depth) {
    const DynamicsState start = state_;
    const Evaluation ev_start = ev_;
    std::string failure = step_once(h, false);
    if (failure.empty()) return {};
    state_ = start;
    ev_ = ev_start;
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
    if (!linearized_ && state_.velocity.squaredNorm() > 0.0) {
      have_factor_ = false;
      const std::string retry = step_once(h, true, step_ref_);
      if (retry.empty()) {
        ++result_.restarts;
        return {};
      }
      failure += "; from zero increment: " + retry;
      state_ = start;
      ev_ = ev_start;
    }
    if (depth == params_.max_step_cuts) return failure;
    ++result_.step_cuts;
    for (int half = 0; half < 2; ++half) {
      failure = advance(0.5 * h, depth + 1);
      if (!failure.empty()) {
        state_ = start;
        ev_ = ev_start;
        return failure;
      }
    }
    return {};
  }

 private:
  // What one attempt at a step of size h holds fixed, and its increment du = h v1.
  struct Step {
    double h = 0.0;
    double damp_m = 0.0, damp_k = 0.0;  // A's factors on M and on K_d
    double area_floor = 0.0;            // the smallest area ratio an accepted step may leave
    Eigen::VectorXd v0;
    ShellState start_shell;  // the linearized scheme's energy guard only
    double start_kinetic = 0.0, start_internal = 0.0;
    Eigen::VectorXd du;
    bool du_zero = true;             // the damping force of a zero increment is zero
    Eigen::VectorXd damping_force;   // Q K_d Q^T du
  };

  // One backward Euler step of size h from the current state; returns why it failed ("" if
  // it did not). The caller restores the state after a failure. `from_zero_increment`: Newton
  // starts from zero increment instead of the predictor, its tolerance relative to
  // `retry_ref` (see advance).
  std::string step_once(double h, bool from_zero_increment, double retry_ref = -1.0) {
    step_ref_ = retry_ref;
    Step step = begin(h, from_zero_increment);
    if (std::string failure = iterate(step, retry_ref); !failure.empty()) return failure;
    return finish(step);
  }

  Step begin(double h, bool from_zero_increment) {
    Step st;
    st.h = h;
    st.damp_m = 1.0 / (h * h) + params_.mass_damping / h;
    st.damp_k = params_.stiffness_damping / h;
    if (h != factor_h_) have_factor_ = false;
    st.area_floor = params_.min_area_ratio > 0.0
                        ? std::min(params_.min_area_ratio, min_area_ratio(sys_.problem, state_.shell))
                        : 0.0;
    st.v0 = map_.restrict(state_.velocity);
    // The linearized scheme starts from the evaluation at the end of the last step (its
    // gradient and, for the energy guard, its internal energy; DynamicsScheme::Linearized).
    if (linearized_ && ev_.residual.size() == 0) ev_ = evaluate(sys_, map_, state_.shell, 1.0, false);
    if (linearized_) st.start_shell = state_.shell;
    st.start_kinetic = 0.5 * st.v0.dot(mass_.cwiseProduct(st.v0));
    st.start_internal = ev_.internal_energy;
    // Bent past kRetakeBend since K_d was taken: the step matrix and K_d are taken anew at
    // this step's start. Without corotated_damping nothing turns (Q = I throughout).
    if (params_.corotated_damping &&
        damping_.turn_to(state_.shell.x) > detail::CorotatedDamping::kRetakeBend)
      have_factor_ = false;
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
    if (linearized_) {
      st.du = Eigen::VectorXd::Zero(st.v0.size());
    } else if (from_zero_increment) {
      st.du = Eigen::VectorXd::Zero(st.v0.size());
      ev_ = evaluate(sys_, map_, state_.shell, 1.0, false);  // a hook may have changed the system
    } else {
      st.du = h * st.v0;
      apply_increment(state_.shell, map_.expand(st.du), d_);
      ev_ = evaluate(sys_, map_, state_.shell, 1.0, false);
    }
    st.du_zero = st.du.squaredNorm() == 0.0;
    return st;
  }

  Eigen::VectorXd residual(Step& st) {
    Eigen::VectorXd R = mass_.cwiseProduct(st.du * st.damp_m - st.v0 / st.h) + ev_.residual;
    if (st.damp_k != 0.0 && !damping_.empty() && !st.du_zero) {
      damping_.apply(st.du, st.damping_force);
      R += st.damp_k * st.damping_force;
    }
    return R;
  }

  // K_d may only change at the start of a step: changing it mid-step would move the root of
  // R while Newton chases it. Within a step the step matrix takes the step's turned K_d.
  bool rebuild(const Step& st, bool new_damping) {
    const Evaluation full = evaluate(sys_, map_, state_.shell, 1.0, true, true, &assembler_);
    if (new_damping || damping_.empty()) damping_.reset(full.tangent, state_.shell.x);
    Eigen::SparseMatrix<double> A = full.tangent + st.damp_k * damping_.matrix();
    A.diagonal() += mass_ * st.damp_m;
    have_factor_ = solver_->factorize(A);
    factor_h_ = st.h;
    ++result_.factorizations;
    return have_factor_;
  }

  // Newton on R(du) = 0, from st.du, to params.tolerance of `ref` (< 0: of the first
  // residual, the external force and force_reference).
  std::string iterate(Step& st, double ref) {
    double previous = -1.0;
    for (int it = 0;; ++it) {
      if (params_.keep_going && !params_.keep_going()) return kStopped;
      Eigen::VectorXd R = residual(st);
      double rnorm = R.norm();
      if (!std::isfinite(rnorm) || !std::isfinite(ev_.internal_energy))
        return "the state became non-finite (NaN/inf)";
      if (ref < 0.0) ref = std::max({rnorm, ev_.external_norm, params_.force_reference, 1e-300});
      step_ref_ = ref;
      if (rnorm <= params_.tolerance * ref) return {};
      if (linearized_ && it > 0 && rnorm <= 0.5 * previous) {
        const double kinetic = 0.5 * st.du.dot(mass_.cwiseProduct(st.du)) / (st.h * st.h);
        const double gain = kinetic - st.start_kinetic + ev_.internal_energy - st.start_internal -
                            external_work(sys_, st.start_shell, state_.shell, 1.0);
        if (gain <= 1e-12 * energy_scale_) return {};  // round-off at rest may not stop a step
      }
      if (it == params_.max_iterations) {
        std::ostringstream m;
        m << "Newton did not converge in " << params_.max_iterations << " iterations (residual "
          << rnorm << ")";
        return m.str();
      }
      // A matrix that no longer halves the residual is stale: rebuild it here, before it is
      // used, from the tangent at the current iterate (then this is a full Newton step).
      bool fresh = false;
      if (!have_factor_ || (previous > 0.0 && rnorm > 0.5 * previous)) {
        if (!rebuild(st, it == 0)) return "the step matrix is singular";
        R = residual(st);  // the damping term changed with K_d
        rnorm = R.norm();
        fresh = true;
      }
      previous = rnorm;
      Eigen::VectorXd delta;
      const bool exact = fresh || !approximate_ok_;
      // The reused matrix, factorised at the damping's reference, turned with the nodes'
      // rotations since (CorotatedDamping::turn).
      const bool turn = damping_.turned();
      Eigen::VectorXd rhs = -R;
      if (turn) damping_.turn(true, rhs);
      if (!(exact ? solver_->solve(rhs, delta) : solver_->solve_approximately(rhs, delta)))
        return "the linear solve failed: " + solver_->last_note();
      if (turn) damping_.turn(false, delta);
      if (fresh) approximate_ok_ = single_precision_ && approximate_solve_agrees(*solver_, -R, delta);
      st.du += delta;
      st.du_zero = false;
      apply_increment(state_.shell, map_.expand(delta), d_);
      ev_ = evaluate(sys_, map_, state_.shell, 1.0, false);
      ++result_.newton_iterations;
    }
  }

  // Accepts a converged increment: the area floor, the new velocity, the energy guard.
  std::string finish(const Step& st) {
    if (st.area_floor > 0.0 && min_area_ratio(sys_.problem, state_.shell) < st.area_floor)
      return "a triangle collapsed (area below " + std::to_string(params_.min_area_ratio) +
             " of its rest area)";
    state_.velocity = map_.expand(st.du / st.h);
    const double kinetic = 0.5 * st.du.dot(mass_.cwiseProduct(st.du)) / (st.h * st.h);
    const double total = kinetic + ev_.internal_energy;
    if (energy_scale_ > 0.0 && total > 1e12 * energy_scale_)
      return "the energy exploded (" + std::to_string(total) + " N*mm)";
    energy_scale_ = std::max(energy_scale_, total);
    result_.kinetic_energy = kinetic;
    result_.strain_energy = ev_.internal_energy;
    result_.residual = ev_.residual.norm();
    return {};
  }

  const ShellSystem& sys_;
  DynamicsState& state_;
  const DynamicsParams& params_;
  DynamicsResult& result_;
  const DofMap map_;
  const int d_;
  const Eigen::VectorXd mass_;
  std::unique_ptr<LinearSolver> solver_;
  TangentAssembler assembler_;
  detail::CorotatedDamping damping_;
  bool have_factor_ = false;
  // Iterations on a reused matrix solve in single precision (DynamicsParams::
  // single_precision_solves; Cholmod only, the others solve exactly anyway) when the current
  // factorisation's single-precision solve agreed with its first, exact one
  // (approximate_solve_agrees).
  const bool single_precision_;
  bool approximate_ok_ = false;
  const bool linearized_;
  double factor_h_ = 0.0;  // the step size the factorised matrix was built for
  double energy_scale_ = 0.0;
  Evaluation ev_;
  double step_ref_ = 0.0;  // the reference of the last step_once's tolerance
};

}  // namespace

DynamicsResult simulate_dynamics(const ShellSystem& sys, DynamicsState& state,
                                 const DynamicsParams& params, const StepHook& hook) {
  check(params);
  DynamicsResult result;
  if (state.velocity.size() != static_cast<Eigen::Index>(sys.num_dofs()))
    state.velocity = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sys.num_dofs()));
  Integrator integrator(sys, state, params, result);
  for (int step = 0; step < params.steps; ++step) {
    if (hook && !hook(step)) break;
    const std::string failure = integrator.advance(params.dt, 0);
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
