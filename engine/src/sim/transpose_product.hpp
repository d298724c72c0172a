#pragma once
// y = A^T x for a column-major sparse matrix, on the OpenMP threads (private to
// engine/src/sim).
//
// Why: the implicit dynamics add the stiffness-proportional damping force beta/h K_d du to
// every residual, 5 to 7 times per step. Eigen's column-major product scatters each column
// into y on one thread: 1.2-1.5 ms at 5k elements (0.62M entries), a fifth of a step
// (docs/performance.md). In the transpose product each y_j is the dot product of column j
// with x, so the columns split between threads with no shared writes; K_d is symmetric (the
// symmetrised tangent), so A^T x is the product wanted.
//
// Determinism: each y_j is summed by one thread over its column's entries in storage order,
// so the bits do not depend on the thread count. Cost O(nnz); parallel above kParallelEntries.
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace sutura::engine::detail {

/// y = A^T x. Requires A compressed, x.size() == A.rows(); y is resized to A.cols().
void transpose_product(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& x,
                       Eigen::VectorXd& y);

}  // namespace sutura::engine::detail
