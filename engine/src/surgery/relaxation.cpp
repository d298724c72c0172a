#include "sutura/engine/surgery/relaxation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

RestState congruent_rest(const std::vector<FaceIndices>& faces, const ShellState& state,
                         const RestState& base, const std::vector<bool>& congruent) {
  if (base.elements.size() != faces.size() || congruent.size() != faces.size())
    throw InvalidArgument("congruent_rest: one rest element and one flag per face needed");
  const RestState fresh = rest_from_state(faces, state);
  RestState out = base;
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (congruent[f]) out.elements[f] = fresh.elements[f];
  return out;
}

RestState rest_at(const RestState& y0, const RestState& x0, double s) {
  if (y0.elements.size() != x0.elements.size())
    throw InvalidArgument("rest_at: y0 and x0 differ in element count");
  if (s <= 0.0) return y0;
  if (s >= 1.0) return x0;
  RestState out;
  out.elements.resize(y0.elements.size());
  for (std::size_t f = 0; f < y0.elements.size(); ++f) {
    const ElementRest& a = y0.elements[f];
    const ElementRest& b = x0.elements[f];
    const Eigen::Matrix3d Ta = element_frame(a.X[0], a.X[1], a.X[2]);
    const Eigen::Matrix3d Tb = element_frame(b.X[0], b.X[1], b.X[2]);
    const Eigen::Matrix3d R = Ta * Tb.transpose();
    const Vec3 ca = (a.X[0] + a.X[1] + a.X[2]) / 3.0, cb = (b.X[0] + b.X[1] + b.X[2]) / 3.0;
    ElementRest& e = out.elements[f];
    for (int k = 0; k < 3; ++k) {
      e.X[k] = (1.0 - s) * a.X[k] + s * (ca + R * (b.X[k] - cb));
      e.Q[k] = a.Q[k].slerp(s, b.Q[k]);
    }
  }
  return out;
}

RelaxationSolver parse_relaxation_solver(const std::string& name) {
  if (name == "static") return RelaxationSolver::Static;
  if (name == "dynamic") return RelaxationSolver::Dynamic;
  throw InvalidArgument("unknown relaxation solver \"" + name +
                        "\" (expected \"static\" or \"dynamic\")");
}

namespace {

void check(const ShellSystem& sys, const RestState& rest, const RestState& y0,
           const RestState& x0, const RelaxationParams& p) {
  if (sys.problem.rest != &rest)
    throw InvalidArgument("relax: the system's rest state must be the one relaxed");
  if (y0.elements.size() != x0.elements.size() || rest.elements.size() != x0.elements.size())
    throw InvalidArgument("relax: y0, x0 and the rest state differ in element count");
  if (p.steps < 1) throw InvalidArgument("relaxation steps must be at least 1");
  if (!(p.s_start >= 0.0 && p.s_start <= 1.0)) throw InvalidArgument("s_start must be in [0, 1]");
  if (!(p.s_end >= p.s_start && p.s_end <= 1.0))
    throw InvalidArgument("s_end must be in [s_start, 1]");
  if (p.settle_steps < 0) throw InvalidArgument("settle_steps must be >= 0");
  if (p.max_cuts < 0) throw InvalidArgument("max_cuts must be >= 0");
  if (p.max_escapes < 0) throw InvalidArgument("max_escapes must be >= 0");
  if (p.density && !(*p.density > 0.0 && std::isfinite(*p.density)))
    throw InvalidArgument("the relaxation's density must be finite and > 0 (t/mm^3)");
  if (!(p.increment_tolerance > 0.0 && p.increment_tolerance < 1.0))
    throw InvalidArgument("increment_tolerance must be in (0, 1)");
}

double residual_norm(const ShellSystem& sys, const ShellState& s) {
  return evaluate(sys, DofMap(sys), s, 1.0, false).residual.norm();
}

// Scales of the relaxation: the energy and the force the current shape would have in the
// target rest shape x0 (before any relaxation) bound what the run stores and transmits; they
// set the blow-up test and the force the residual tolerance is relative to.
struct Scales {
  double energy = 0.0;
  double force = 0.0;
};
Scales target_scales(const ShellSystem& sys, const RestState& x0, const ShellState& s) {
  ShellProblem p = sys.problem;
  p.rest = &x0;
  Eigen::VectorXd g;
  Scales out;
  out.energy = sys.model->energy_gradient(p, s, g);
  out.force = DofMap(sys).restrict(g).norm();
  return out;
}

StaticSolverParams increment_params(const RelaxationParams& params, const Scales& scales) {
  StaticSolverParams sp = params.statics;
  sp.lambda_start = sp.lambda_end = 1.0;
  sp.load_steps = 1;
  // The load factor is fixed at 1, so a retry with a smaller load increment would repeat the
  // failed solve exactly; the relaxation retries with a smaller increment of s instead.
  sp.max_step_cuts = 0;
  sp.energy_reference = std::max(sp.energy_reference, scales.energy);
  // Residuals are measured against the force of the whole relaxation, not the first residual
  // of one increment: after a few halvings that is so small that the relative tolerance
  // drops below round-off (measured: 7e-17 N asked of a 1e-2 N joining force).
  sp.force_reference = std::max(sp.force_reference, scales.force);
  // A relaxation minimises energy as the rest shape moves; a patch or a stretched stump may
  // buckle on the way, where the plain Newton direction is not a descent direction.
  sp.shift_indefinite = true;
  return sp;
}

// Norm of the support reactions (internal forces on fixed DOFs): the force scale of the
// final equilibrium, against which the settling solve measures its residual. Zero for an
// unconstrained structure.
double reaction_norm(const ShellSystem& sys, const ShellState& s) {
  Eigen::VectorXd g;
  sys.model->energy_gradient(sys.problem, s, g);
  const DofMap map(sys);
  double sum = 0.0;
  for (std::size_t i = 0; i < map.full_to_free.size(); ++i)
    if (map.full_to_free[i] < 0) sum += g[Eigen::Index(i)] * g[Eigen::Index(i)];
  return std::sqrt(sum);
}

bool settle_static(const ShellSystem& sys, ShellState& state, const RelaxationParams& params,
                   const Scales& scales, RelaxationResult& result, SolverWorkspace& workspace) {
  StaticSolverParams sp = increment_params(params, scales);
  sp.force_reference = std::max(sp.force_reference, reaction_norm(sys, state));
  const StaticResult r = solve_static(sys, state, sp, &workspace);
  result.newton_iterations += r.iterations;
  result.quasi_newton_iterations += r.quasi_newton_iterations;
  result.indefinite_iterations += r.indefinite_iterations;
  result.residual = r.residual;
  result.energy = r.energy;
  if (!r.converged) result.message = "settling to equilibrium failed: " + r.message;
  result.cancelled = r.stopped;
  return r.converged;
}

// Mean length of the rest elements' edges: the scale of a perturbation that stays within one
// element's reach of the current shape.
double mean_rest_edge(const RestState& rest) {
  double sum = 0.0;
  for (const auto& e : rest.elements)
    sum += (e.X[1] - e.X[0]).norm() + (e.X[2] - e.X[1]).norm() + (e.X[0] - e.X[2]).norm();
  return rest.elements.empty() ? 0.0 : sum / (3.0 * double(rest.elements.size()));
}

// Moves `state` (an unstable equilibrium) downhill along the unstable mode: the largest
// translation is `reach` and the largest rotation 0.1 rad (or 1/2, 1/4, 1/8 of the step), in
// the direction of the lower total potential energy. Along a direction of negative curvature
// the energy falls as a^2/2 v.Kv at first; a step that does not lower it (the quartic terms
// of a stiff branch), or that squashes a triangle below the solver's collapse guard
// (min_area_ratio), is shortened. Returns false if no step qualifies.
bool perturb_downhill(const ShellSystem& sys, ShellState& state, const UnstableMode& mode,
                      double reach, double min_area_ratio_floor) {
  const int d = sys.dofs_per_node();
  double largest = 0.0, turn = 0.0;
  for (std::size_t i = 0; i < state.x.size(); ++i) {
    largest = std::max(largest, mode.direction.segment<3>(Eigen::Index(d * i)).norm());
    if (d == 6) turn = std::max(turn, mode.direction.segment<3>(Eigen::Index(d * i + 3)).norm());
  }
  if (!(largest > 0.0) || !(reach > 0.0)) return false;
  constexpr double kMaxTurn = 0.1;  // rad
  const double a0 = turn > 0.0 ? std::min(reach / largest, kMaxTurn / turn) : reach / largest;
  const double area_floor =
      min_area_ratio_floor > 0.0
          ? std::min(min_area_ratio_floor, min_area_ratio(sys.problem, state))
          : 0.0;
  const DofMap map(sys);
  const double e0 = evaluate(sys, map, state, 1.0, false).internal_energy;
  for (double a = a0; a >= a0 / 8.0; a *= 0.5) {
    ShellState best;
    double best_p = e0;
    for (const double sign : {1.0, -1.0}) {
      ShellState trial = state;
      apply_increment(trial, sign * a * mode.direction, d);
      if (area_floor > 0.0 && min_area_ratio(sys.problem, trial) < area_floor) continue;
      const double p = evaluate(sys, map, trial, 1.0, false).internal_energy -
                       external_work(sys, state, trial, 1.0);
      if (std::isfinite(p) && p < best_p) {
        best_p = p;
        best = std::move(trial);
      }
    }
    if (best_p < e0) {
      state = std::move(best);
      return true;
    }
  }
  return false;
}

// The secant predictor of path following: the state at s_next extrapolated linearly from the
// last two converged increments (at s_prev and s), positions by their difference, triads by
// their relative rotation, scaled by ratio = (s_next - s) / (s - s_prev). Nodes that did not
// move (held ones) keep their state bit for bit.
ShellState extrapolate(const ShellState& prev, const ShellState& now, double ratio) {
  ShellState out = now;
  for (std::size_t i = 0; i < now.x.size(); ++i) {
    out.x[i] += ratio * (now.x[i] - prev.x[i]);
    if (now.D[i].coeffs() == prev.D[i].coeffs()) continue;
    const Eigen::AngleAxisd turn(now.D[i] * prev.D[i].inverse());
    out.D[i] = (Eigen::Quaterniond(Eigen::AngleAxisd(ratio * turn.angle(), turn.axis())) * now.D[i])
                   .normalized();
  }
  return out;
}

// Whether the predicted state is a better start than the converged one at the new rest shape:
// lower total potential energy (strain energy minus the work of the loads on the way from
// `now`), finite, and no triangle squashed further than the solver's collapse guard allows.
bool better_start(const ShellSystem& sys, const ShellState& now, const ShellState& predicted,
                  double min_area_ratio_floor) {
  const DofMap map(sys);
  const double e_now = evaluate(sys, map, now, 1.0, false).internal_energy;
  const double e_pred = evaluate(sys, map, predicted, 1.0, false).internal_energy -
                        external_work(sys, now, predicted, 1.0);
  if (!std::isfinite(e_pred) || !(e_pred < e_now)) return false;
  if (min_area_ratio_floor <= 0.0) return true;
  const double floor = std::min(min_area_ratio_floor, min_area_ratio(sys.problem, now));
  return min_area_ratio(sys.problem, predicted) >= floor;
}

RelaxationResult relax_static(const ShellSystem& sys, RestState& rest, const RestState& y0,
                              const RestState& x0, ShellState& state, const RelaxationParams& p,
                              const RelaxationHook& hook, const Scales& scales,
                              SolverWorkspace& workspace) {
  RelaxationResult result;
  double s = p.s_start;
  const double ds_planned = (p.s_end - p.s_start) / p.steps;
  double ds = ds_planned;
  // A failed increment is halved, down to 2^-max_cuts of the planned one; after two good
  // increments in a row a halved increment is doubled again (up to the planned one), so one
  // hard stretch of the path does not slow down all the rest of it. The floor is absolute,
  // not per run of failures: alternating failures and single successes would otherwise
  // shrink the increment without bound and crawl for ever instead of reporting the failure.
  const double ds_min = std::ldexp(ds_planned, -p.max_cuts);
  int done = 0, streak = 0, iterations_before = 0, quasi_before = 0;
  result.s_reached = s;
  // The converged state of the increment before the last one, for the secant predictor
  // (s_prev < 0: none yet). Its effect on the Newton iterations: docs/performance.md,
  // "Measurements behind defaults".
  ShellState prev;
  double s_prev = -1.0;
  ShellState converged = state;  // the last converged state (at s), what a failure returns
  const bool can_escape = p.check_stability && p.statics.linear_solver == LinearSolverKind::Cholmod;
  // The first increment's quasi-Newton steps start from the tangent at the start, a stable
  // equilibrium (factorize_for_quasi_newton), which spares the first increment a
  // Levenberg-Marquardt search (docs/performance.md, "Measurements behind defaults").
  if (p.statics.linear_solver == LinearSolverKind::Cholmod && p.statics.quasi_newton_steps > 0) {
    rest = rest_at(y0, x0, s);
    factorize_for_quasi_newton(sys, state, 1.0, workspace);
  }
  while (s < p.s_end - 1e-12) {
    // The last increment lands on s_end exactly (no round-off short of 1).
    const double s_next = s + ds >= p.s_end - 1e-9 ? p.s_end : s + ds;
    rest = rest_at(y0, x0, s_next);
    const ShellState good = state;
    if (p.predictor && s_prev >= 0.0) {
      ShellState predicted = extrapolate(prev, state, (s_next - s) / (s - s_prev));
      if (better_start(sys, state, predicted, p.statics.min_area_ratio)) state = std::move(predicted);
    }
    StaticSolverParams sp = increment_params(p, scales);
    if (s_next < p.s_end) sp.tolerance = std::max(sp.tolerance, p.increment_tolerance);
    const StaticResult r = solve_static(sys, state, sp, &workspace);
    result.newton_iterations += r.iterations;
    result.quasi_newton_iterations += r.quasi_newton_iterations;
    result.indefinite_iterations += r.indefinite_iterations;
    if (!r.converged) {
      state = good;
      rest = rest_at(y0, x0, s);
      if (r.stopped) {  // the caller's keep_going: no escape, no halving, no retry
        result.cancelled = true;
        return result;
      }
      // An increment that started from an unstable equilibrium (a symmetric shape held on an
      // unstable branch: the Levenberg-Marquardt iteration converges only linearly onto the
      // saddle it stays on, measured: 3e-9 short of 1e-8 after 30 iterations on a flat
      // compressed pair) is retried from the shape pushed downhill along an unstable mode
      // before it is halved; such pushes count against max_escapes (escape_instability).
      if (can_escape && result.escapes < p.max_escapes) {
        const std::optional<UnstableMode> mode = unstable_mode(sys, state, 1.0, 30, &workspace);
        if (mode && perturb_downhill(sys, state, *mode, 0.2 * mean_rest_edge(rest),
                                     p.statics.min_area_ratio)) {
          ++result.escapes;
          s_prev = -1.0;  // the secant through a push predicts nothing
          continue;
        }
      }
      if (ds <= ds_min * (1.0 + 1e-9)) {
        state = converged;
        std::ostringstream m;
        m << "relaxation failed at s = " << s_next << ": " << r.message
          << "; rolled back to s = " << s;
        result.message = m.str();
        return result;
      }
      streak = 0;
      ds *= 0.5;
      // A failed increment is reported too (phase "retry", at the s it restarts from): a run
      // of hard failures can take long, and the caller may want to stop it.
      const int left = int(std::ceil((p.s_end - s) / ds - 1e-9));
      RelaxationProgress retry{s, done, done + std::max(left, 0), r.residual, r.energy, "retry",
                               result.newton_iterations - iterations_before,
                               result.quasi_newton_iterations - quasi_before};
      if (hook && !hook(retry)) {
        result.cancelled = true;
        return result;
      }
      continue;
    }
    if (++streak >= 2 && ds < ds_planned) {
      ds = std::min(ds_planned, 2.0 * ds);
      streak = 0;
    }
    prev = good;
    s_prev = s;
    s = s_next;
    converged = state;
    result.s_reached = s;
    result.residual = r.residual;
    result.energy = r.energy;
    ++done;
    const int left = int(std::ceil((p.s_end - s) / ds - 1e-9));
    RelaxationProgress pr{s, done, done + std::max(left, 0), r.residual, r.energy, "relax",
                          result.newton_iterations - iterations_before,
                          result.quasi_newton_iterations - quasi_before};
    iterations_before = result.newton_iterations;
    quasi_before = result.quasi_newton_iterations;
    result.history.push_back(pr);
    if (hook && !hook(pr)) {
      result.cancelled = true;
      return result;
    }
  }
  result.ok = true;
  return result;
}

RelaxationResult relax_dynamic(const ShellSystem& sys, RestState& rest, const RestState& y0,
                               const RestState& x0, ShellState& state,
                               const RelaxationParams& p, const RelaxationHook& hook,
                               const Scales& scales) {
  RelaxationResult result;
  DynamicsParams dp = p.dynamics;
  // Steps taken at (or near) equilibrium have a round-off first residual; measure them
  // against the forces of the joining instead.
  dp.force_reference = std::max(dp.force_reference, 1e-3 * scales.force);
  // The damping here only has to settle the shape; the unturned stiffness damping, which also
  // damps rigid rotation, does that with a quarter of the factorisations of the corotated one
  // (DynamicsParams::corotated_damping).
  dp.corotated_damping = false;
  // The hook changes the rest shape every step, which the linearized scheme's energy guard
  // does not allow for (DynamicsScheme::Linearized).
  dp.scheme = DynamicsScheme::Newton;
  const int settle = p.s_end >= 1.0 && p.settle ? p.settle_steps : 0;
  dp.steps = p.steps + settle;
  DynamicsState ds{state, {}};
  double s_now = p.s_start;
  const StepHook step_hook = [&](int step) {
    if (step > 0) {
      const double e = sys.model->energy(sys.problem, ds.shell);
      RelaxationProgress pr{s_now, step, dp.steps, residual_norm(sys, ds.shell), e,
                            step <= p.steps ? "relax" : "settle"};
      result.history.push_back(pr);
      if (hook && !hook(pr)) {
        result.cancelled = true;
        return false;
      }
    }
    // The rest shape for step `step` (0-based): s advances linearly over the first p.steps.
    s_now = p.s_start + (p.s_end - p.s_start) * std::min(1.0, double(step + 1) / p.steps);
    rest = rest_at(y0, x0, s_now);
    return true;
  };
  // The pace-setting density (RelaxationParams::density): the same system with every
  // material's density replaced; only the mass reads it.
  ShellSystem paced = sys;
  std::vector<ShellMaterial> paced_materials;
  if (p.density) {
    paced_materials = *sys.problem.materials;
    for (ShellMaterial& m : paced_materials) m.density = *p.density;
    paced.problem.materials = &paced_materials;
  }
  const DynamicsResult r = simulate_dynamics(paced, ds, dp, step_hook);
  state = ds.shell;
  result.newton_iterations = r.newton_iterations;
  result.residual = r.residual;
  result.energy = r.strain_energy;
  // simulate_dynamics rolls back a failed step; the rest shape then matches the last good one.
  const int good_steps = r.steps_done;
  result.s_reached =
      p.s_start + (p.s_end - p.s_start) * std::min(1.0, double(good_steps) / p.steps);
  rest = rest_at(y0, x0, result.s_reached);
  if (r.stopped) {
    result.cancelled = true;
    return result;
  }
  if (!r.ok) {
    result.message = "relaxation " + r.message;
    return result;
  }
  result.ok = !result.cancelled;
  return result;
}

// An unstable settled shape is perturbed along an unstable mode and settled again, up to
// max_escapes times (RelaxationParams::max_escapes). A perturbation that cannot lower the
// energy, or a settle that fails, leaves the last settled (unstable) shape, which the report
// then flags. Only with the Cholmod solver: the settle must minimise the energy (the
// Levenberg-Marquardt shift and the energy line search, static_solver.hpp), or plain Newton
// would lead straight back to the saddle. Each escape is reported to `hook` as an "escape"
// step; returning false cancels (the state is kept as it is).
void escape_instability(const ShellSystem& sys, const RestState& rest, ShellState& state,
                        const RelaxationParams& params, const Scales& scales,
                        RelaxationResult& result, SolverWorkspace& workspace,
                        const RelaxationHook& hook) {
  if (params.statics.linear_solver != LinearSolverKind::Cholmod) return;
  const double reach = 0.2 * mean_rest_edge(rest);
  while (result.stability && result.stability->negative_modes > 0 &&
         result.escapes < params.max_escapes) {
    if (params.statics.keep_going && !params.statics.keep_going()) {
      result.cancelled = true;
      return;
    }
    const std::optional<UnstableMode> mode = unstable_mode(sys, state, 1.0, 30, &workspace);
    if (!mode) return;
    const ShellState settled = state;
    const RelaxationResult before = result;
    const int iterations_before = result.newton_iterations;
    const int quasi_before = result.quasi_newton_iterations;
    if (!perturb_downhill(sys, state, *mode, reach, params.statics.min_area_ratio) ||
        !settle_static(sys, state, params, scales, result, workspace)) {
      const bool stopped = result.cancelled;  // settle_static's solve said so
      state = settled;
      result = before;
      result.cancelled = stopped;
      return;
    }
    if (result.escapes++ == 0) result.stability_before_escapes = result.stability;
    result.stability = check_stability(sys, state, {}, &workspace);
    const int n = int(result.history.size()) + 1;
    RelaxationProgress pr{1.0, n, n, result.residual, result.energy, "escape",
                          result.newton_iterations - iterations_before,
                          result.quasi_newton_iterations - quasi_before};
    result.history.push_back(pr);
    if (hook && !hook(pr)) {
      result.cancelled = true;
      return;
    }
  }
}

}  // namespace

RelaxationResult relax(const ShellSystem& sys, RestState& rest, const RestState& y0,
                       const RestState& x0, ShellState& state, const RelaxationParams& params,
                       const RelaxationHook& hook) {
  check(sys, rest, y0, x0, params);
  const Scales scales = target_scales(sys, x0, state);
  // One pattern and one ordering for every increment and the settling: the structure of the
  // system does not change during a relaxation, only its rest shape.
  SolverWorkspace workspace;
  RelaxationResult result =
      params.solver == RelaxationSolver::Static
          ? relax_static(sys, rest, y0, x0, state, params, hook, scales, workspace)
          : relax_dynamic(sys, rest, y0, x0, state, params, hook, scales);
  if (!result.ok || result.cancelled || result.s_reached < 1.0 || !params.settle) return result;
  // Settle to a tight static equilibrium, measured against the support reactions (a
  // structure without supports settles by the dynamics alone: a static solve is singular).
  if (reaction_norm(sys, state) > 0.0) {
    const ShellState good = state;
    const int iterations_before_settle = result.newton_iterations;
    const int quasi_before_settle = result.quasi_newton_iterations;
    if (!settle_static(sys, state, params, scales, result, workspace)) {
      state = good;
      result.ok = false;
      return result;
    }
    const int settle_iterations = result.newton_iterations - iterations_before_settle;
    RelaxationProgress pr{1.0, int(result.history.size()) + 1, int(result.history.size()) + 1,
                          result.residual, result.energy, "settle", settle_iterations,
                          result.quasi_newton_iterations - quasi_before_settle};
    result.history.push_back(pr);
    // Asked before the stability check, an eigen-solve.
    if ((hook && !hook(pr)) || (params.check_stability && params.statics.keep_going &&
                                !params.statics.keep_going())) {
      result.cancelled = true;
      return result;
    }
    if (params.check_stability) {
      result.stability = check_stability(sys, state, {}, &workspace);
      escape_instability(sys, rest, state, params, scales, result, workspace, hook);
    }
  }
  return result;
}

}  // namespace sutura::engine
