#pragma once
// Stability of an equilibrium: is the state a strict local minimum of the total potential
// energy, or could a small disturbance carry it off to another shape?
//
// Second-variation test: an equilibrium is stable when the tangent stiffness on the free DOFs
// (the Hessian of the potential) is positive definite. That is one Cholesky factorisation. If
// it fails, the number of unstable modes is the number of negative eigenvalues, counted from the
// signs of D in an LDL^T factorisation (Sylvester's law of inertia: a congruence, and a
// symmetric permutation, keep the counts of positive, negative and zero eigenvalues). For the
// follower pressure the tangent carries the symmetrised load stiffness (loads.hpp), which is
// the Hessian exactly for a conservative pressure (a closed surface, or rims held fixed).
#include <optional>
#include <string>

#include "sutura/engine/sim/shell_system.hpp"
#include "sutura/engine/sim/static_solver.hpp"

namespace sutura::engine {

struct StabilityParams {
  double lambda = 1.0;      ///< load factor of the equilibrium (loads are scaled by it)
  /// Where the tangent is not positive definite, count the unstable modes (an extra simplicial
  /// LDL^T factorisation: about 0.1 s at 5k elements, 3 s at 20k). Off: negative_modes is -1
  /// for an unstable state.
  bool count_modes = true;
  /// The modes are counted on the diagonally scaled tangent S K S (S = diag|K|^-1/2: the same
  /// inertia, unit diagonal). A pivot of its LDL^T with |d| <= zero_pivot counts as tiny; the
  /// modes are then counted on S K S +- neutral_band I instead (a non-pivoting LDL^T's tiny
  /// pivot does not by itself mean that K is singular).
  double zero_pivot = 1e-12;
  /// Eigenvalues of S K S within +-neutral_band count as zero (neutral directions: free
  /// rigid-body motion, a mechanism, the onset of buckling).
  double neutral_band = 1e-8;
};

struct Stability {
  bool assessed = true;   ///< false: the test could not be made (summary says why)
  bool stable = false;    ///< the tangent is positive definite: a strict local minimum
  bool singular = false;  ///< eigenvalues near zero (neutral_band): neutral directions
  /// Negative eigenvalues of the tangent beyond the neutral band (0 when stable; -1 when not
  /// counted or not assessed).
  int negative_modes = -1;
  std::string summary;    ///< one sentence for a report, e.g. "stable equilibrium ..."
};

/// A direction of negative curvature of the tangent K at `state`: where an unstable
/// equilibrium can be left downhill (the energy falls as a^2/2 curvature along a v).
struct UnstableMode {
  Eigen::VectorXd direction;  ///< full DOFs (zero at fixed ones), unit norm over the free DOFs
  double curvature = 0.0;     ///< v^T K v < 0 (N/mm for translations)
};

/// Finds a direction of negative curvature by inverse iteration with the Levenberg-Marquardt
/// shifted tangent K + mu diag|K|, mu just above the smallest shift that makes it positive
/// definite (bracketed by decades from 1e-12 to 1e4, then bisected): the iteration amplifies
/// the components along the most negative eigenvalues of K most, so the Rayleigh quotient
/// v^T K v comes out negative. The start vector is a fixed pseudo-random sequence (the result
/// is deterministic). Cost: up to about 15 Cholesky factorisations (typically 8) plus
/// `iterations` back-substitutions and one sparse product. nullopt when K is positive definite
/// or no negative curvature was found.
std::optional<UnstableMode> unstable_mode(const ShellSystem& sys, const ShellState& state,
                                          double lambda = 1.0, int iterations = 30,
                                          SolverWorkspace* workspace = nullptr);

/// Checks the equilibrium `state` of `sys` at params.lambda. The state should be converged: the
/// test says nothing about states off equilibrium. `workspace` (optional) lends its
/// assembler's pattern and its Cholmod solver with the symbolic factorisation (one is made in
/// it if it holds another kind). Cost: one
/// tangent assembly and one Cholesky factorisation (plus one LDL^T when unstable and
/// count_modes, three where pivots come out tiny). Throws InvalidArgument for invalid
/// parameters.
Stability check_stability(const ShellSystem& sys, const ShellState& state,
                          const StabilityParams& params = {}, SolverWorkspace* workspace = nullptr);

}  // namespace sutura::engine
