#include "static_iterate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace sutura::engine::detail {

// Newton iterations at a fixed load factor. Returns an empty string on convergence, else why
// it failed (the caller restores the state).
//
// Convergence: |r| <= max(tol * max(|f_ext|, |r_0|), roundoff_residual), or the energy norm of the Newton increment
// |du . r| <= tol^2 * |du_0 . r_0| (the usual FE energy criterion). The second is needed
// because coordinate round-off puts a floor of about 1e-14 E t L under the residual, which a
// purely relative residual test at small loads cannot pass.
//
// Line search, as a safeguard: the full Newton step is kept whenever it is finite and does not
// raise |r| by more than kGrowthLimit. Thin shells need that leniency: the first Newton step
// of a load increment stretches the membrane (the linear predictor), so |r| jumps up by two
// orders of magnitude although the step is good, and a strict merit test (residual norm, or
// Crisfield's slope test) turns quadratic convergence into hundreds of tiny steps (measured
// on the Sze cantilever: 158 iterations with the strict test, 43 without). Only a step
// beyond the limit is refined by secant steps on the slope s(a) = du . r(u + a du), which is
// negative at a = 0 (Crisfield 1991), keeping the trial with the smallest |s|.
std::string newton(const ShellSystem& sys, const DofMap& map, ShellState& state, double lambda,
                   const StaticSolverParams& params, LinearSolver& solver, double energy_scale,
                   StaticResult& result, TangentAssembler& assembler,
                   TangentAssembler& internal_assembler) {
  Evaluation ev = evaluate(sys, map, state, lambda, true, true, &assembler);
  const double ref =
      std::max({ev.external_norm, ev.residual.norm(), params.force_reference, 1e-300});
  const double roundoff = roundoff_residual(sys, state);
  double step_length = 1.0;
  double first_work = -1.0;
  int internal_steps = 0;  // consecutive steps with the internal-force tangent (below)
  bool collapsed_trial = false;  // a line-search trial was rejected for a collapsed triangle
  double work_done = 0.0;  // by the loads since the start of this load step (external_work)
  for (int it = 0;; ++it) {
    const double rnorm = ev.residual.norm();
    if (std::string failed = record_iterate(ev, lambda, it, step_length, work_done, energy_scale,
                                            collapsed_trial, params, result);
        !failed.empty())
      return failed;
    if (rnorm <= std::max(params.tolerance * ref, roundoff)) return {};
    if (params.keep_going && !params.keep_going()) return kStopped;
    if (it == params.max_iterations) {
      std::ostringstream m;
      m << "no convergence in " << params.max_iterations << " Newton iterations (residual "
        << rnorm << ", needed " << std::max(params.tolerance * ref, roundoff) << ")";
      return m.str();
    }
    ++result.iterations;
    bool factored;
    if (params.linear_solver == LinearSolverKind::Cholmod) {
      // A follower pressure on a still unstressed shell (the first iteration of an inflation)
      // makes the tangent indefinite through its load stiffness alone, until the hoop stress
      // builds up. The Newton step on it (LDL^T) heads for a saddle first; the step with the
      // tangent of the internal forces, positive definite there, is a descent direction of
      // the potential (for a conservative pressure: closed surface or held rims) and lands
      // close to the equilibrium. Measured on the fine arch's inflation (80 mmHg in two load
      // steps): 12 -> 9 iterations, 13.2 -> 7.9 s, the same equilibrium (lumen to 11 digits).
      // Such steps converge only linearly, and near an instability driven by the pressure
      // itself they would push away from the equilibrium that LDL^T reaches, so after
      // kInternalSteps of them in a row (or where the internal tangent is indefinite too)
      // the step is LDL^T on the true tangent, as before.
      constexpr int kInternalSteps = 3;
      factored = solver.factorize_definite(ev.tangent);
      if (!factored) ++result.indefinite_iterations;
      if (factored) {
        internal_steps = 0;
      } else if (has_load_stiffness(sys) && internal_steps < kInternalSteps) {
        const Evaluation internal =
            evaluate(sys, map, state, lambda, true, false, &internal_assembler);
        factored = solver.factorize_definite(internal.tangent);
        if (factored) ++internal_steps;
      }
      if (!factored) factored = solver.factorize_indefinite(ev.tangent);
    } else {
      factored = solver.factorize(ev.tangent);
    }
    if (!factored) return "the tangent stiffness is singular (is the structure constrained?)";
    Eigen::VectorXd du;
    if (!solver.solve(-ev.residual, du)) return "the linear solve failed: " + solver.last_note();
    const double s0 = du.dot(ev.residual);
    if (first_work < 0.0) first_work = std::abs(s0);
    const bool energy_converged =
        std::abs(s0) <= params.tolerance * params.tolerance * first_work && it > 0;
    const Eigen::VectorXd du_full = map.expand(du);

    const double area_floor = collapse_floor(sys, state, params);
    const auto trial_at = [&](double a, ShellState& trial) {
      return evaluate_trial(sys, map, state, du_full, a, lambda, area_floor, true, &assembler,
                            trial, collapsed_trial);
    };
    ShellState trial;
    Evaluation ev_trial = trial_at(1.0, trial);
    step_length = 1.0;
    constexpr double kGrowthLimit = 1e3;
    const double r1 = ev_trial.residual.norm();
    const bool full_step_ok = std::isfinite(r1) && r1 <= kGrowthLimit * rnorm;
    double trial_work = external_work(sys, state, trial, lambda);
    if (params.line_search && !energy_converged && s0 < 0.0 && !full_step_ok) {
      double a = 1.0, s_a = du.dot(ev_trial.residual);
      double best_a = a, best_s = std::isfinite(s_a) ? std::abs(s_a) : HUGE_VAL;
      ShellState best_state = trial;
      Evaluation best_ev = ev_trial;
      for (int search = 0; search < 5 && !(std::abs(s_a) <= 0.8 * std::abs(s0)); ++search) {
        // Secant on s between 0 and a; a non-finite trial halves the step instead.
        double next = std::isfinite(s_a) && s_a != s0 ? a * s0 / (s0 - s_a) : 0.5 * a;
        if (!(next > 0.0)) next = 0.5 * a;
        a = std::clamp(next, 0.1 * a, 2.0 * a);
        ev_trial = trial_at(a, trial);
        s_a = du.dot(ev_trial.residual);
        if (std::isfinite(s_a) && std::abs(s_a) < best_s) {
          best_a = a, best_s = std::abs(s_a);
          best_state = trial;
          best_ev = ev_trial;
        }
      }
      if (!(std::abs(s_a) <= 0.8 * std::abs(s0))) {
        a = best_a;
        trial = std::move(best_state);
        ev_trial = std::move(best_ev);
      }
      step_length = a;
      trial_work = external_work(sys, state, trial, lambda);
    }
    work_done += trial_work;
    state = std::move(trial);
    ev = std::move(ev_trial);
    if (energy_converged) {
      result.history.push_back({lambda, it + 1, ev.residual.norm(), ev.internal_energy, 1.0,
                                ev.internal_energy - work_done});
      result.residual = ev.residual.norm();
      result.energy = ev.internal_energy;
      return {};
    }
  }
}

}  // namespace sutura::engine::detail
