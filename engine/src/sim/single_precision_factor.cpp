#include "single_precision_factor.hpp"

#include <omp.h>

#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

namespace {

using Vec = Eigen::VectorXf;
// A supernode's block: nsrow x nscol, column-major with leading dimension nsrow; its top
// nscol x nscol square is lower triangular (the diagonal block), the rows below it are the
// off-diagonal rows, listed in L.s.
using Block = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;

// Below this many factor entries (about 1k elements, a solve of a fraction of a millisecond)
// the solve stays on one thread. A judgement, not a measured optimum (measured from 5k up).
constexpr std::size_t kParallelEntries = 200000;

}  // namespace

void SinglePrecisionFactor::assign(const cholmod_factor& L) {
  if (!L.is_super || !L.is_ll || L.xtype != CHOLMOD_REAL || L.itype != CHOLMOD_INT)
    throw InvalidArgument("single-precision factor: needs a real supernodal LL^T factor");
  const auto* x = static_cast<const double*>(L.x);
  values_.assign(x, x + L.xsize);
}

// Forward, L y = P b, over `supernodes` in increasing order: the diagonal block's triangular
// solve, then the off-diagonal rows' products subtracted from the rows they stand for; a half
// (half >= 0) collects the products for top rows in its spill buffer instead.
void SinglePrecisionFactor::forward(const SupernodalArrays& a, const SupernodeSplit& split,
                                    const std::vector<int>& supernodes, int half) {
  float* spill = half >= 0 ? spill_[half].data() : nullptr;
  std::vector<float>& work = work_[half >= 0 ? half : 0];
  for (const int s : supernodes) {
    const int k1 = a.super[s], ncol = a.ncol(s), nrow = a.nrow(s), below = nrow - ncol;
    const float* block = values_.data() + a.value_start[s];
    Eigen::Map<Vec> ys(y_.data() + k1, ncol);
    Block(block, ncol, ncol, Eigen::OuterStride<>(nrow))
        .triangularView<Eigen::Lower>()
        .solveInPlace(ys);
    if (below == 0) continue;
    Eigen::Map<Vec> e(work.data(), below);
    e.noalias() = Block(block + ncol, below, ncol, Eigen::OuterStride<>(nrow)) * ys;
    const int* r = a.rows + a.row_start[s] + ncol;
    if (spill == nullptr) {
      for (int i = 0; i < below; ++i) y_[r[i]] -= work[i];
    } else {
      for (int i = 0; i < below; ++i) {
        if (split.is_top_column[r[i]]) spill[r[i]] += work[i];
        else y_[r[i]] -= work[i];
      }
    }
  }
}

// Backward, L^T z = y, over `supernodes` in decreasing order: the off-diagonal rows'
// contributions gathered, then the transposed diagonal block's triangular solve.
void SinglePrecisionFactor::backward(const SupernodalArrays& a, const std::vector<int>& supernodes,
                                     int half) {
  std::vector<float>& work = work_[half >= 0 ? half : 0];
  for (auto it = supernodes.rbegin(); it != supernodes.rend(); ++it) {
    const int s = *it;
    const int k1 = a.super[s], ncol = a.ncol(s), nrow = a.nrow(s), below = nrow - ncol;
    const float* block = values_.data() + a.value_start[s];
    Eigen::Map<Vec> ys(y_.data() + k1, ncol);
    if (below > 0) {
      const int* r = a.rows + a.row_start[s] + ncol;
      for (int i = 0; i < below; ++i) work[i] = y_[r[i]];
      const Eigen::Map<const Vec> e(work.data(), below);
      ys.noalias() -= Block(block + ncol, below, ncol, Eigen::OuterStride<>(nrow)).transpose() * e;
    }
    Block(block, ncol, ncol, Eigen::OuterStride<>(nrow))
        .transpose()
        .triangularView<Eigen::Upper>()
        .solveInPlace(ys);
  }
}

void SinglePrecisionFactor::solve(const cholmod_factor& L, const SupernodeSplit& split,
                                  const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const auto n = static_cast<Eigen::Index>(L.n);
  if (b.size() != n) throw InvalidArgument("single-precision factor: right-hand side size");
  if (values_.size() != L.xsize || split.is_top_column.size() != L.n)
    throw InvalidArgument("single-precision factor: assign() the factor before solving");
  const SupernodalArrays a(L);
  const auto* perm = static_cast<const int*>(L.Perm);
  y_.resize(static_cast<std::size_t>(n));
  // No permutation stored: the natural ordering.
  for (Eigen::Index k = 0; k < n; ++k) y_[k] = static_cast<float>(b[perm ? perm[k] : k]);
  for (int h = 0; h < 2; ++h) {
    work_[h].resize(L.maxesize);
    spill_[h].resize(static_cast<std::size_t>(n));
    for (const int t : split.top_columns) spill_[h][t] = 0.0f;
  }
  const bool parallel = omp_get_max_threads() > 1 && values_.size() >= kParallelEntries &&
                        !split.halves[0].empty() && !split.halves[1].empty();
#pragma omp parallel for num_threads(2) schedule(static, 1) if (parallel)
  for (int h = 0; h < 2; ++h) forward(a, split, split.halves[h], h);
  for (int h = 0; h < 2; ++h)
    for (const int t : split.top_columns) y_[t] -= spill_[h][t];
  forward(a, split, split.top, -1);
  backward(a, split.top, -1);
#pragma omp parallel for num_threads(2) schedule(static, 1) if (parallel)
  for (int h = 0; h < 2; ++h) backward(a, split.halves[h], h);
  x.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) x[perm ? perm[k] : k] = static_cast<double>(y_[k]);
}

}  // namespace sutura::engine::detail
