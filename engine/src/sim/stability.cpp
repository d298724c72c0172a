#include "sutura/engine/sim/stability.hpp"

#include <cmath>
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

}  // namespace sutura::engine
