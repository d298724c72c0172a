#include "sutura/engine/sim/unload.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/QR>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

constexpr double kSmallestStep = 1.0 / 16.0;

double mean_edge_length(const std::vector<FaceIndices>& faces, const std::vector<Vec3>& x) {
  double sum = 0.0;
  std::size_t n = 0;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      sum += (x[f[(k + 1) % 3]] - x[f[k]]).norm();
      ++n;
    }
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

struct Deviation {
  double max = 0.0;
  double rms = 0.0;
};

Deviation deviation(const std::vector<Vec3>& target, const std::vector<Vec3>& x) {
  Deviation d;
  double sum = 0.0;
  for (std::size_t i = 0; i < target.size(); ++i) {
    const double e = (target[i] - x[i]).norm();
    d.max = std::max(d.max, e);
    sum += e * e;
  }
  d.rms = target.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(target.size()));
  return d;
}

// Every load at full value under lambda: fixed_loads join the ramped ones, so the first solve
// brings all of them in from the unloaded shape.
Loads all_loads(const ShellSystem& sys) {
  Loads l = sys.loads;
  l.nodal.insert(l.nodal.end(), sys.fixed_loads.nodal.begin(), sys.fixed_loads.nodal.end());
  l.pressures.insert(l.pressures.end(), sys.fixed_loads.pressures.begin(),
                     sys.fixed_loads.pressures.end());
  l.body_force_per_area += sys.fixed_loads.body_force_per_area;
  return l;
}

}  // namespace

UnloadResult unload(const ShellSystem& sys, const std::vector<Vec3>& target,
                    const UnloadParams& params, SolverWorkspace* workspace) {
  if (sys.model == nullptr || sys.problem.faces == nullptr)
    throw InvalidArgument("unload: the system has no model or no faces");
  if (sys.problem.num_nodes == 0) throw InvalidArgument("unload: the system has no nodes");
  if (target.size() != sys.problem.num_nodes)
    throw InvalidArgument("unload: " + std::to_string(target.size()) + " target positions for " +
                          std::to_string(sys.problem.num_nodes) + " nodes");
  if (params.max_iterations < 1) throw InvalidArgument("unload: max_iterations must be at least 1");
  if (params.acceleration_depth < 0) throw InvalidArgument("unload: acceleration_depth must be >= 0");
  if (!(params.tolerance >= 0.0) || !std::isfinite(params.tolerance))
    throw InvalidArgument("unload: tolerance must be finite and >= 0");
  for (const Vec3& p : target)
    if (!p.allFinite()) throw InvalidArgument("unload: a target position is not finite");

  const std::vector<FaceIndices>& faces = *sys.problem.faces;
  UnloadResult result;
  result.tolerance =
      params.tolerance > 0.0 ? params.tolerance : 0.01 * mean_edge_length(faces, target);

  ShellSystem s = sys;
  s.loads = all_loads(sys);
  s.fixed_loads = Loads{};
  RestState rest;
  s.problem.rest = &rest;
  SolverWorkspace local;
  SolverWorkspace& ws = workspace != nullptr ? *workspace : local;

  // The unloaded guess X and the equilibrium with it. The first solve starts unloaded at the
  // target with identity triads and ramps the loads in; later ones start at the last
  // equilibrium with every load at full value.
  const auto n = static_cast<Eigen::Index>(3 * target.size());
  const Eigen::Map<const Eigen::VectorXd> xt(target.data()->data(), n);
  Eigen::VectorXd X = xt;
  ShellState state{target, std::vector<Quat>(target.size(), Quat::Identity())};
  Eigen::VectorXd X_good, f_good;  // the rest of the last successful solve and its deviation
  // Anderson's history: the last depth + 1 rest shapes and deviations.
  std::vector<Eigen::VectorXd> hist_X, hist_f;
  Deviation last{};
  double step = 1.0;
  for (int k = 0; k < params.max_iterations; ++k) {
    std::vector<Vec3> Xv(target.size());
    Eigen::Map<Eigen::VectorXd>(Xv.data()->data(), n) = X;
    rest = rest_from_state(faces, ShellState{Xv, std::vector<Quat>(Xv.size(), Quat::Identity())});
    StaticSolverParams sp = params.solver;
    sp.lambda_start = k == 0 ? 0.0 : 1.0;
    sp.lambda_end = 1.0;
    if (k > 0) sp.load_steps = 1;
    ShellState trial = state;
    const StaticResult r = solve_static(s, trial, sp, &ws);
    result.solver_iterations += r.iterations + r.quasi_newton_iterations;
    UnloadIteration it;
    it.solver_iterations = r.iterations + r.quasi_newton_iterations;
    it.step = step;
    it.accelerated = hist_X.size() >= 2;
    if (r.stopped) {
      result.stopped = true;
      result.message = "unload stopped in forward solve " + std::to_string(k + 1);
      result.history.push_back(it);
      return result;
    }
    if (!r.converged) {
      it.solved = false;
      result.history.push_back(it);
      if (k == 0 || step <= kSmallestStep) {
        result.message = "unload failed: forward solve " + std::to_string(k + 1) +
                         " did not converge (" + r.message + ")";
        return result;
      }
      // Back to the last equilibrium's rest, half as far along its deviation, unaccelerated.
      step *= 0.5;
      hist_X.clear();
      hist_f.clear();
      X = X_good + step * f_good;
      continue;
    }
    state = trial;
    const Deviation d = deviation(target, state.x);
    it.max_deviation = d.max;
    it.rms_deviation = d.rms;
    result.history.push_back(it);
    result.max_deviation = d.max;
    result.rms_deviation = d.rms;
    if (d.max <= result.tolerance) {
      result.converged = true;
      result.rest_positions = Xv;
      result.rest = rest;
      result.state = state;
      for (std::size_t i = 0; i < Xv.size(); ++i)
        result.max_unloading = std::max(result.max_unloading, (target[i] - Xv[i]).norm());
      return result;
    }
    const Eigen::VectorXd f = xt - Eigen::Map<const Eigen::VectorXd>(state.x.data()->data(), n);
    if (k > 0 && d.max > last.max) {  // growing: restart the history, shorten the step
      step = std::max(kSmallestStep, 0.5 * step);
      hist_X.clear();
      hist_f.clear();
    }
    last = d;
    X_good = X;
    f_good = f;
    hist_X.push_back(X);
    hist_f.push_back(f);
    if (static_cast<int>(hist_X.size()) > params.acceleration_depth + 1) {
      hist_X.erase(hist_X.begin());
      hist_f.erase(hist_f.begin());
    }
    const auto m = static_cast<Eigen::Index>(hist_X.size()) - 1;
    if (m == 0) {
      X = X + step * f;
      continue;
    }
    // Anderson (type II): the combination of the last steps whose deviations best cancel f,
    // in the least-squares sense (column-pivoting QR: deterministic, rank-revealing).
    Eigen::MatrixXd dF(n, m), dX(n, m);
    for (Eigen::Index j = 0; j < m; ++j) {
      dF.col(j) = hist_f[j + 1] - hist_f[j];
      dX.col(j) = hist_X[j + 1] - hist_X[j];
    }
    const Eigen::VectorXd gamma = dF.colPivHouseholderQr().solve(f);
    X = X + step * f - (dX + step * dF) * gamma;
  }
  std::ostringstream m;
  m << "unload did not converge in " << params.max_iterations
    << " forward solves: the loaded shape is still " << result.max_deviation
    << " mm from the target (tolerance " << result.tolerance << " mm)";
  result.message = m.str();
  return result;
}

}  // namespace sutura::engine
