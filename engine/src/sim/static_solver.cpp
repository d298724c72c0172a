#include "sutura/engine/sim/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "lbfgs.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

// A load step's failure when StaticSolverParams::keep_going said no.
const std::string kStopped = "stopped by the caller";

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
            ? minimize(sys, map, state, lambda, params, solver, energy_scale, result, ws)
            : newton(sys, map, state, lambda, params, solver, energy_scale, result, assembler,
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
