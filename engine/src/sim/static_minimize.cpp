#include "static_iterate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "lbfgs.hpp"

namespace sutura::engine::detail {

namespace {

// Factorises K, or where it is not positive definite K + mu diag|K| (Levenberg-Marquardt), mu
// grown tenfold from 1e-4 (or a decade below `lm_shift`, the last shift that worked) until
// the Cholesky factorisation succeeds: a descent direction of the energy where K is indefinite
// (an energy-driven run passing an instability), where plain Newton would head for a saddle.
// Consecutive iterations of one instability need similar shifts, and each trial is a full
// factorisation. `coarse` (with quasi-Newton steps): grown a hundredfold, from the last shift
// that worked itself; an over-shifted factorisation then costs only a few more cheap steps (the
// L-BFGS pairs correct it), a failed trial a whole factorisation. Returns false if no shift up
// to 1e4 works.
bool factorize_shifted(LinearSolver& solver, const Eigen::SparseMatrix<double>& K,
                       double& lm_shift, bool coarse, StaticResult& result) {
  if (solver.factorize_definite(K)) {
    lm_shift = 0.0;
    return true;
  }
  ++result.indefinite_iterations;
  const Eigen::VectorXd diag = K.diagonal().cwiseAbs().cwiseMax(1e-300);
  const double start = coarse ? std::max(1e-4, lm_shift) : std::max(1e-4, 0.1 * lm_shift);
  for (double mu = start; mu <= 1e4; mu *= coarse ? 100.0 : 10.0) {
    if (solver.factorize_definite(shift_diagonal(K, diag, mu))) {
      lm_shift = mu;
      return true;
    }
  }
  return false;
}

}  // namespace

// Energy minimisation at a fixed load factor (shift_indefinite: the rest-shape relaxation).
// With Cholmod, steps with a newly factorised tangent (factorize_shifted) alternate with
// quasi-Newton steps that reuse the last factorisation as L-BFGS's initial inverse Hessian
// (quasi_newton_steps; lbfgs.hpp); every step is a descent direction of the total potential
// energy P = E - W (external_work), backtracked until the Armijo condition holds. The other
// solvers, which cannot tell a definite matrix, take plain Newton steps. Returns an
// empty string on convergence (then the factorisation is left in `ws` for the next solve),
// else why it failed (the caller restores the state). Convergence as in newton().
std::string minimize(const ShellSystem& sys, const DofMap& map, ShellState& state, double lambda,
                     const StaticSolverParams& params, LinearSolver& solver, double energy_scale,
                     StaticResult& result, SolverWorkspace& ws) {
  // Measured on the patch aortoplasty, fine arch (docs/performance.md): 20 pairs (8: more
  // steps; 40: the same) and a window of 4 steps over which the residual must halve (3, 6, 8:
  // more tangents or more steps).
  constexpr int kDepth = 20;
  constexpr std::size_t kWindow = 4;
  const auto n = static_cast<Eigen::Index>(map.num_free());
  const bool cholmod = params.linear_solver == LinearSolverKind::Cholmod;
  const int qn_steps = cholmod ? params.quasi_newton_steps : 0;
  // Without quasi-Newton steps every iterate needs its tangent: evaluate trials with it.
  const bool trial_tangent = qn_steps == 0;
  Evaluation ev = evaluate(sys, map, state, lambda, trial_tangent, true, &ws.assembler());
  bool have_tangent = trial_tangent;
  const double ref =
      std::max({ev.external_norm, ev.residual.norm(), params.force_reference, 1e-300});
  const double roundoff = roundoff_residual(sys, state);
  detail::LbfgsHistory lbfgs(kDepth);
  // Residual norms since the factorisation in use (the first: where it was made); empty when
  // the factorisation came from the previous solve.
  std::vector<double> norms;
  bool need_tangent = qn_steps == 0 || !ws.holds_reusable_factor(n);
  int newton_steps = 0, since_factor = 0;
  double step_length = 1.0, first_work = -1.0, lm_shift = 0.0, work_done = 0.0;
  bool collapsed_trial = false;
  // L-BFGS's initial inverse Hessian is the factorised tangent, solved in single precision for
  // quasi-Newton steps (single_precision_solves; Cholmod only, the others solve exactly
  // anyway). The first step with each factorisation (a Newton step, or the first quasi-Newton
  // step with one carried in) has no pairs yet, du = -H0 r: it solves exactly, and is checked
  // against its single-precision solve (approximate_solve_agrees), which the later steps use
  // if it agrees.
  const bool single_precision = params.single_precision_solves && qn_steps > 0;
  bool checked = false, approximate_ok = false;
  const auto h0 = [&](const Eigen::VectorXd& q, Eigen::VectorXd& z) {
    return !checked || !approximate_ok ? solver.solve(q, z) : solver.solve_approximately(q, z);
  };
  for (int it = 0;; ++it) {
    const double rnorm = ev.residual.norm();
    if (std::string failed = record_iterate(ev, lambda, it, step_length, work_done, energy_scale,
                                            collapsed_trial, params, result);
        !failed.empty())
      return failed;
    if (rnorm <= std::max(params.tolerance * ref, roundoff)) {
      ws.keep_factor(n);
      return {};
    }
    if (params.keep_going && !params.keep_going()) return kStopped;
    if ((need_tangent && newton_steps == params.max_iterations) ||
        it == params.max_iterations * (qn_steps + 1)) {
      std::ostringstream m;
      m << "no convergence in " << newton_steps << " Newton iterations";
      if (it > newton_steps) m << " and " << it - newton_steps << " quasi-Newton steps";
      m << " (residual " << rnorm << ", needed " << std::max(params.tolerance * ref, roundoff) << ")";
      return m.str();
    }
    // The step: Newton (Levenberg-Marquardt) on a new tangent, or quasi-Newton on the last
    // factorisation; a quasi-Newton direction that is not one of descent (round-off in the
    // pairs) is replaced by a Newton step.
    Eigen::VectorXd du;
    bool fresh = false;
    for (;;) {
      if (need_tangent) {
        if (!have_tangent) ev = evaluate(sys, map, state, lambda, true, true, &ws.assembler());
        ++result.iterations;
        ++newton_steps;
        if (!(cholmod ? factorize_shifted(solver, ev.tangent, lm_shift, qn_steps > 0, result)
                      : solver.factorize(ev.tangent)))
          return "the tangent stiffness is singular (is the structure constrained?)";
        lbfgs.clear();
        checked = false;
        norms.assign(1, ev.residual.norm());
        since_factor = 0;
        fresh = true;
        need_tangent = false;
      }
      const bool solved = lbfgs.apply(-ev.residual, du, h0);
      if (fresh && !solved) return "the linear solve failed: " + solver.last_note();
      if (solved && !checked) {
        approximate_ok =
            single_precision && approximate_solve_agrees(solver, -ev.residual, du);
        checked = true;
      }
      if (fresh || (solved && du.dot(ev.residual) < 0.0)) break;
      need_tangent = true;
    }
    if (!fresh) {
      ++result.quasi_newton_iterations;
      ++since_factor;
    }
    const double s0 = du.dot(ev.residual);
    if (first_work < 0.0) first_work = std::abs(s0);
    // The energy criterion only on a Newton step: a quasi-Newton direction's du . r depends
    // on how well the old factorisation still fits.
    const bool energy_converged =
        fresh && std::abs(s0) <= params.tolerance * params.tolerance * first_work && it > 0;
    const Eigen::VectorXd du_full = map.expand(du);
    const double area_floor = collapse_floor(sys, state, params);
    const auto trial_at = [&](double a, ShellState& trial) {
      return evaluate_trial(sys, map, state, du_full, a, lambda, area_floor, trial_tangent,
                            &ws.assembler(), trial, collapsed_trial);
    };
    ShellState trial;
    Evaluation ev_trial = trial_at(1.0, trial);
    step_length = 1.0;
    // Backtracking (quadratic model of P(a), Nocedal & Wright 3.5) until the Armijo condition
    // P(a) <= P(0) + c a s0 holds. A full step far beyond an instability otherwise lands in a
    // state of 100 times the energy, from which the iteration wanders (measured on an
    // anastomosis at s = 0.35: no convergence in 30 iterations without the backtracking, 10
    // with it; on the pressurised fine arch, before the work term was counted, a step to 300
    // times the energy passed the residual test and two increments of s failed after 30
    // iterations each). Decreases below round-off (|s0| at 1e-12 E) are not tested.
    const double e0 = ev.internal_energy;
    double trial_work = external_work(sys, state, trial, lambda);
    if (params.line_search && !energy_converged && s0 < 0.0 &&
        std::abs(s0) > 1e-12 * std::abs(e0)) {
      constexpr double kArmijo = 1e-4;
      double a = 1.0;
      for (int search = 0; search < 12; ++search) {
        const double ea = ev_trial.internal_energy - trial_work;
        if (std::isfinite(ea) && ea <= e0 + kArmijo * a * s0) break;
        const double curvature = std::isfinite(ea) ? ea - e0 - s0 * a : HUGE_VAL;
        const double next = curvature > 0.0 ? -s0 * a * a / (2.0 * curvature) : 0.5 * a;
        a = std::clamp(next, 0.1 * a, 0.5 * a);
        ev_trial = trial_at(a, trial);
        trial_work = external_work(sys, state, trial, lambda);
      }
      step_length = a;
    }
    work_done += trial_work;
    if (qn_steps > 0 && std::isfinite(ev_trial.residual.norm()))
      lbfgs.add(step_length * du, ev_trial.residual - ev.residual);
    state = std::move(trial);
    ev = std::move(ev_trial);
    have_tangent = trial_tangent;
    if (energy_converged) {
      result.history.push_back({lambda, it + 1, ev.residual.norm(), ev.internal_energy, 1.0,
                                ev.internal_energy - work_done});
      result.residual = ev.residual.norm();
      result.energy = ev.internal_energy;
      ws.keep_factor(n);
      return {};
    }
    // A new tangent when the last one has served its count, or when the residual has not
    // halved over the last kWindow steps. (Also tried: a new tangent after a quasi-Newton step
    // cut below 1/4, or after 4-8 cut steps in a row: fewer steps on the inflation and the
    // subclavian flap, more on the patch aortoplasty, where a Levenberg-Marquardt shifted
    // factorisation is off by design and the pairs correct it; docs/performance.md.)
    norms.push_back(ev.residual.norm());
    const std::size_t k = norms.size();
    need_tangent = qn_steps == 0 || since_factor >= qn_steps ||
                   (k > kWindow && norms[k - 1] > 0.5 * norms[k - 1 - kWindow]);
  }
}

}  // namespace sutura::engine::detail
