#include "sutura/engine/sim/stability.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>

#include <Eigen/SparseCholesky>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

Stability check_stability(const ShellSystem& sys, const ShellState& state,
                          const StabilityParams& params, SolverWorkspace* workspace) {
  if (!std::isfinite(params.lambda)) throw InvalidArgument("stability: lambda must be finite");
  if (!(params.zero_pivot >= 0.0 && params.zero_pivot < 1.0))
    throw InvalidArgument("stability: zero_pivot must be in [0, 1)");
  SolverWorkspace local;
  SolverWorkspace& ws = workspace != nullptr ? *workspace : local;
  const DofMap map(sys);
  Stability out;
  if (map.num_free() == 0) {
    out.stable = true;
    out.negative_modes = 0;
    out.summary = "stable: every degree of freedom is held";
    return out;
  }
  const Evaluation ev = evaluate(sys, map, state, params.lambda, true, true, &ws.assembler());
  if (!ev.tangent.coeffs().allFinite()) {
    out.summary = "not assessed: the tangent stiffness is not finite";
    return out;
  }
  LinearSolver& cholesky = ws.solver(LinearSolverKind::Cholmod, {});
  if (cholesky.factorize_definite(ev.tangent)) {
    out.stable = true;
    out.negative_modes = 0;
    out.summary = "stable equilibrium: the tangent stiffness is positive definite (a local "
                  "minimum of the potential energy)";
    return out;
  }
  if (!params.count_modes) {
    out.summary = "unstable equilibrium: the tangent stiffness is not positive definite";
    return out;
  }
  // The inertia from LDL^T. Eigen's simplicial LDL^T does not pivot for stability, so a tiny
  // pivot may come out inaccurate, but its sign count is exact in exact arithmetic and robust
  // wherever no pivot is near zero; near-zero pivots are reported as singular instead.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(ev.tangent);
  const double scale = ev.tangent.diagonal().cwiseAbs().maxCoeff();
  if (ldlt.info() != Eigen::Success) {
    out.singular = true;
    out.summary = "singular tangent stiffness (a zero pivot): the state has neutral directions "
                  "(free rigid-body motion or a mechanism)";
    return out;
  }
  const Eigen::VectorXd d = ldlt.vectorD();
  int negative = 0, zero = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (!(std::abs(d[i]) > params.zero_pivot * scale)) ++zero;
    else if (d[i] < 0.0) ++negative;
  }
  std::ostringstream m;
  if (zero > 0) {
    out.singular = true;
    m << "singular tangent stiffness (" << zero << " zero pivot" << (zero > 1 ? "s" : "")
      << "): the state has neutral directions (free rigid-body motion or a mechanism)";
    if (negative > 0) m << " and " << negative << " unstable mode" << (negative > 1 ? "s" : "");
    out.summary = m.str();
    return out;
  }
  if (negative == 0) {
    // Cholesky failed on round-off alone: the smallest eigenvalue is at the noise level.
    out.singular = true;
    out.summary = "marginal: the tangent stiffness is positive semi-definite to round-off (an "
                  "eigenvalue near zero: at the onset of an instability)";
    return out;
  }
  out.negative_modes = negative;
  m << "unstable equilibrium: the tangent stiffness has " << negative << " negative eigenvalue"
    << (negative > 1 ? "s" : "") << " (a small disturbance would carry the shape away, e.g. "
    << "buckle it)";
  out.summary = m.str();
  return out;
}

std::optional<UnstableMode> unstable_mode(const ShellSystem& sys, const ShellState& state,
                                          double lambda, int iterations,
                                          SolverWorkspace* workspace) {
  if (!std::isfinite(lambda)) throw InvalidArgument("unstable_mode: lambda must be finite");
  if (iterations < 1) throw InvalidArgument("unstable_mode: iterations must be at least 1");
  SolverWorkspace local;
  SolverWorkspace& ws = workspace != nullptr ? *workspace : local;
  const DofMap map(sys);
  if (map.num_free() == 0) return std::nullopt;
  const Evaluation ev = evaluate(sys, map, state, lambda, true, true, &ws.assembler());
  const Eigen::SparseMatrix<double>& K = ev.tangent;
  LinearSolver& solver = ws.solver(LinearSolverKind::Cholmod, {});
  if (solver.factorize_definite(K)) return std::nullopt;
  const Eigen::VectorXd diag = K.diagonal().cwiseAbs().cwiseMax(1e-300);
  const auto factorize_shifted = [&](double mu) {
    Eigen::SparseMatrix<double> shifted = K;
    for (Eigen::Index i = 0; i < shifted.rows(); ++i) shifted.coeffRef(i, i) += mu * diag[i];
    return solver.factorize_definite(shifted);
  };
  // Inverse iteration converges as the ratio of the two smallest eigenvalues of the shifted
  // matrix, so the shift is brought close to the smallest that makes it definite, mu* (where
  // the most unstable mode's shifted eigenvalue passes zero): decades bracket it, four
  // bisections in log scale narrow the bracket to a factor 1.16. With a whole decade of
  // excess shift the soft modes all sit near mu diag and 30 iterations do not separate them
  // (a compressed strip at 1.5 times its buckling load: no negative curvature found).
  double hi = 1e-4, lo = 0.0;
  if (factorize_shifted(hi)) {
    for (lo = hi / 10.0; lo > 1e-12 && factorize_shifted(lo); lo /= 10.0) hi = lo;
  } else {
    for (lo = hi, hi *= 10.0; hi <= 1e4 && !factorize_shifted(hi); hi *= 10.0) lo = hi;
    if (hi > 1e4) return std::nullopt;
  }
  for (int i = 0; i < 4 && lo > 0.0; ++i) {
    const double mid = std::sqrt(lo * hi);
    (factorize_shifted(mid) ? hi : lo) = mid;
  }
  if (!factorize_shifted(hi)) return std::nullopt;
  // A fixed start with components of both signs everywhere (a multiplicative congruential
  // sequence): deterministic, and not orthogonal to any mode in practice.
  Eigen::VectorXd v(K.rows()), next;
  std::uint64_t seed = 0x9E3779B97F4A7C15ull;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    v[i] = static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5;
  }
  v.normalize();
  for (int it = 0; it < iterations; ++it) {
    if (!solver.solve(v, next) || !next.allFinite() || next.norm() == 0.0) return std::nullopt;
    v = next.normalized();
  }
  const double curvature = v.dot(K * v);
  if (!(curvature < 0.0)) return std::nullopt;
  return UnstableMode{map.expand(v), curvature};
}

}  // namespace sutura::engine
