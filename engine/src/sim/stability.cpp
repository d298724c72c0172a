#include "sutura/engine/sim/stability.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>

#include <Eigen/SparseCholesky>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

struct Inertia {
  bool ok = false;   // the factorisation ran to the end (no exactly zero pivot)
  int negative = 0;  // pivots below -tiny
  int tiny = 0;      // pivots within +-tiny
};

Inertia inertia(const SpMat& A, double tiny) {
  const Eigen::SimplicialLDLT<SpMat, Eigen::Lower> ldlt(A);
  Inertia out;
  if (ldlt.info() != Eigen::Success) return out;
  out.ok = true;
  const Eigen::VectorXd d = ldlt.vectorD();
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (!(std::abs(d[i]) > tiny)) ++out.tiny;
    else if (d[i] < 0.0) ++out.negative;
  }
  return out;
}

}  // namespace

Stability check_stability(const ShellSystem& sys, const ShellState& state,
                          const StabilityParams& params, SolverWorkspace* workspace) {
  if (!std::isfinite(params.lambda)) throw InvalidArgument("stability: lambda must be finite");
  if (!(params.zero_pivot >= 0.0 && params.zero_pivot < 1.0))
    throw InvalidArgument("stability: zero_pivot must be in [0, 1)");
  if (!(params.neutral_band > 0.0 && params.neutral_band < 1.0))
    throw InvalidArgument("stability: neutral_band must be in (0, 1)");
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
    out.assessed = false;
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
  // The inertia from LDL^T. Eigen's simplicial LDL^T does not pivot, so a tiny pivot only says
  // that a leading block of the reordered matrix is nearly singular, not that K is. Then (and
  // when LDL^T finds no negative pivot although Cholesky failed: round-off) the counts of
  // K + delta D and K - delta D (D = diag|K|) decide: equal, K has that many negative
  // eigenvalues and none near zero; different, the difference lies within +-delta of zero
  // (delta = neutral_band, on the scaled matrix below).
  // All on S K S with S = diag|K|^-1/2 (a congruence: the same inertia), whose diagonal is
  // +-1, so the thresholds mean the same for translations (E t) and rotations (E t^3).
  const Eigen::VectorXd s =
      ev.tangent.diagonal().cwiseAbs().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const SpMat scaled = s.asDiagonal() * ev.tangent * s.asDiagonal();
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(scaled.rows());
  const double tiny = params.zero_pivot;
  const Inertia direct = inertia(scaled, tiny);
  int negative = direct.negative, neutral = 0;
  if (!direct.ok || direct.tiny > 0 || direct.negative == 0) {
    const Inertia plus = inertia(shift_diagonal(scaled, ones, params.neutral_band), tiny);
    const Inertia minus = inertia(shift_diagonal(scaled, ones, -params.neutral_band), tiny);
    if (!plus.ok || !minus.ok || plus.tiny > 0 || minus.tiny > 0) {
      out.assessed = false;
      out.summary = "not assessed: the tangent stiffness and its shifts have zero pivots";
      return out;
    }
    negative = plus.negative;
    neutral = minus.negative - plus.negative;
  }
  out.negative_modes = negative;
  out.singular = neutral > 0;
  std::ostringstream m;
  if (negative == 0) {
    m << "marginal: the tangent stiffness is positive semi-definite with " << neutral
      << " eigenvalue" << (neutral > 1 ? "s" : "") << " near zero (neutral directions: free "
      << "rigid-body motion, a mechanism, or the onset of an instability)";
  } else {
    m << "unstable equilibrium: the tangent stiffness has " << negative << " negative eigenvalue"
      << (negative > 1 ? "s" : "");
    if (neutral > 0) m << " and " << neutral << " near zero";
    m << " (a small disturbance would carry the shape away, e.g. buckle it)";
  }
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
    return solver.factorize_definite(shift_diagonal(K, diag, mu));
  };
  // Inverse iteration converges as the ratio of the two smallest eigenvalues of the shifted
  // matrix, so the shift is brought close to the smallest that makes it definite, mu* (where
  // the most unstable mode's shifted eigenvalue passes zero): decades from 1e-12 to 1e4
  // bracket it, four bisections in log scale narrow the bracket to a factor 1.16. With a
  // whole decade of excess shift the soft modes all sit near mu diag and 30 iterations do not
  // separate them (a compressed strip at 1.5 times its buckling load: no negative curvature
  // found).
  int e_hi = -4;  // the bracket [10^e_lo, 10^e_hi]: definite at e_hi, not at e_lo
  if (factorize_shifted(1e-4)) {
    while (e_hi > -12 && factorize_shifted(std::pow(10.0, e_hi - 1))) --e_hi;
  } else {
    do {
      if (++e_hi > 4) return std::nullopt;
    } while (!factorize_shifted(std::pow(10.0, e_hi)));
  }
  double lo = std::pow(10.0, e_hi - 1), hi = std::pow(10.0, e_hi);
  for (int i = 0; i < 4; ++i) {
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
