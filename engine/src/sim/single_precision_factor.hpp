#pragma once
// A CHOLMOD supernodal Cholesky factor rounded to single precision, and the permuted triangular
// solves on it (private to engine/src/sim; LinearSolver::solve_approximately).
//
// Why: a back-substitution reads the whole factor twice and does two flops per entry read, so it
// is bound by memory traffic, not arithmetic: nnz(L) is 7.5M at 20k elements (73 MB in double
// with the supernodes' padding). Iterations that correct the error of their own step (the
// quasi-Newton steps of an energy minimisation, the modified Newton of the dynamics) do not need
// the exact solve, so they read half the bytes (timings: docs/performance.md, "Measurements
// behind defaults").
//
// Two threads: the supernodal elimination tree is split into two halves and a top
// (supernode_tree.hpp). The halves' solves touch disjoint rows except the top's, so they run at
// the same time: forward, each half first collects its updates of top rows in its
// own buffer, added to the top rows afterwards (first half, then second); backward, the top is
// solved first and the halves then only read it. One core's memory traffic is the limit, so a
// second core halves the time or better (12.7 -> 5.1-7.3 ms at 20k elements, docs/performance.md).
// Deterministic and independent of the thread count: the split depends on the factor's
// structure only, and one thread runs the same operations in the same order, half after half.
//
// Accuracy: each entry of the (accurately computed) factor is rounded, a relative perturbation
// of L, and the solves run in single precision. Unlike a factorisation computed in single
// precision this keeps even a nearly singular matrix's small eigenvalues to relative accuracy:
// measured relative errors of the solution 4e-7 on the issue-3 tube's tangents at 5k and 20k
// elements and on the Sze strip's, and 3e-7 on a grid Laplacian shifted to cond 1e11
// (tests/engine/sim/test_linear_solver.cpp).
#include <array>
#include <vector>

#include <Eigen/Core>
#include <cholmod.h>

#include "supernode_tree.hpp"

namespace sutura::engine::detail {

class SinglePrecisionFactor {
 public:
  /// Rounds the values of `L` (supernodal LL^T, as CHOLMOD's supernodal factorisation leaves
  /// it) to single precision. Cost O(nnz(L)); memory 4 bytes per entry.
  void assign(const cholmod_factor& L);
  /// x = A^-1 b approximately, A = P^T L L^T P with the values last assigned and the structure
  /// (supernodes, row indices, permutation) of `L`, which must be the factor assigned from
  /// (numeric refactorisations change only values: assign again after each); `split` is that
  /// structure's split (split_supernode_tree). b.size() = L.n. Uses two OpenMP threads when the
  /// calling thread may (omp_get_max_threads() > 1) and the factor is large enough to pay for
  /// them; the result does not depend on it.
  void solve(const cholmod_factor& L, const SupernodeSplit& split, const Eigen::VectorXd& b,
             Eigen::VectorXd& x);

 private:
  // One group of supernodes: half 0 or 1 (whose updates of top rows go to its spill buffer),
  // or -1 for the top.
  void forward(const SupernodalArrays& a, const SupernodeSplit& split,
               const std::vector<int>& supernodes, int half);
  void backward(const SupernodalArrays& a, const std::vector<int>& supernodes, int half);

  std::vector<float> values_;  ///< L.x rounded, same layout (supernode by supernode)
  std::vector<float> y_;       ///< permuted right-hand side, then solution
  std::array<std::vector<float>, 2> spill_;  ///< per half: its updates of top rows (forward)
  std::array<std::vector<float>, 2> work_;   ///< per half: one supernode's off-diagonal rows
};

}  // namespace sutura::engine::detail
