#pragma once
// Numeric supernodal Cholesky factorisation on two threads, on CHOLMOD's symbolic analysis
// (private to engine/src/sim; used by the CHOLMOD linear solver for large factors).
//
// Why: CHOLMOD's numeric factorisation works through the supernodes one after the other; its
// parallelism is OpenBLAS's, inside each dense block, and most blocks of a shell tangent are
// too small for it (6 to a few hundred columns): one Newton iteration at 20k elements kept the
// second core nearly idle during the factorisation (CPU time = wall time). Here the elimination
// tree is split into two independent halves and a top (supernode_tree.hpp); each half is
// factorised on its own thread, and the top, which the halves' updates reach, afterwards.
//
// How: right-looking supernodal LL^T ("fan-out") into CHOLMOD's own factor object, so that its
// solves, the single-precision copy and everything else use the result unchanged. Per supernode
// s in order: potrf of the diagonal block, trsm of the rows below it, then for each ancestor t
// that s's rows reach, the update L_s(rows >= t) L_s(rows of t)^T (gemm) subtracted from t's
// block. A half's updates of top blocks go to that half's own copy of the top blocks, which
// are subtracted from the top after both halves, first half's first: the sums are taken in a
// fixed order, so the factor is bit-identical from run to run and for any thread count (one
// thread runs the same operations, half after half). It differs from CHOLMOD's own factor in
// the last bits (another summation order), as any two Cholesky codes do.
//
// Cost: the same flops as CHOLMOD's factorisation; the halves' share runs in parallel. Memory:
// one integer per entry of A's lower triangle (where it goes in L), and two copies of the top
// blocks. Dense kernels: BLAS and LAPACK (OpenBLAS, one thread per call).
#include <cstdint>
#include <vector>

#include <Eigen/Sparse>
#include <cholmod.h>

#include "supernode_tree.hpp"

namespace sutura::engine::detail {

class ParallelCholesky {
 public:
  /// Prepares for the structure of `L` (CHOLMOD's supernodal LL^T factor of A's pattern, with
  /// its values allocated: after a numeric factorisation by CHOLMOD, or the symbolic factor
  /// converted by cholmod_change_factor), its split (split_supernode_tree; kept by reference:
  /// it must outlive this object's use of it) and A's pattern.
  /// Must be called again after any new symbolic analysis. Leaves it unprepared (prepared()
  /// false: keep factorising with CHOLMOD) if A is not compressed or L's row lists are not
  /// increasing. Cost O(nnz(A) log + nnz(L.s)).
  void prepare(const Eigen::SparseMatrix<double>& A, const cholmod_factor& L,
               const SupernodeSplit& split);
  [[nodiscard]] bool prepared() const { return split_ != nullptr; }
  /// Overwrites L's values with the Cholesky factor of P A P^T (A symmetric, its lower
  /// triangle used; A and L with the structures prepared for). Returns false if A is not
  /// positive definite (L's values are then meaningless; L.minor: a column where it failed).
  /// A must be compressed.
  bool factorize(const Eigen::SparseMatrix<double>& A, cholmod_factor& L);

 private:
  // Fills, factorises and fans out the supernodes of one group (0, 1: the halves, whose updates
  // of top blocks go to their own copies; 2: the top). Returns the column whose pivot was not
  // positive (the matrix is not positive definite), or -1.
  int factorize_group(const Eigen::SparseMatrix<double>& A, cholmod_factor& L, int group);

  const SupernodeSplit* split_ = nullptr;  ///< the prepared structure's split
  // Per group (the two halves, then the top): where each entry of A's lower triangle goes,
  // as pairs (index into A's values, index into L's values).
  std::vector<std::pair<std::int64_t, std::int64_t>> fill_[3];
  std::vector<std::int64_t> top_offset_;  ///< per supernode: its block's start in a top copy
  std::int64_t top_size_ = 0;
  std::vector<double> top_copy_[2];       ///< per half: its updates of the top blocks
  std::vector<double> update_[2];         ///< per half: one update block (gemm output)
  std::vector<int> relative_[2];          ///< per half: rows' positions in the target block
};

}  // namespace sutura::engine::detail
