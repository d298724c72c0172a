#include "single_precision_factor.hpp"

#include <Eigen/Core>

#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

namespace {

using Vec = Eigen::VectorXf;
// A supernode's block: nsrow x nscol, column-major with leading dimension nsrow; its top
// nscol x nscol square is lower triangular (the diagonal block), the rows below it are the
// off-diagonal rows, listed in L.s.
using Block = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;

// CHOLMOD's factor arrays are int for the int interface the engine uses (Eigen's
// CholmodSupernodalLLT with int indices).
const int* ints(const void* p) { return static_cast<const int*>(p); }

}  // namespace

void SinglePrecisionFactor::assign(const cholmod_factor& L) {
  if (!L.is_super || !L.is_ll || L.xtype != CHOLMOD_REAL || L.itype != CHOLMOD_INT)
    throw InvalidArgument("single-precision factor: needs a real supernodal LL^T factor");
  const auto* x = static_cast<const double*>(L.x);
  values_.assign(x, x + L.xsize);
}

void SinglePrecisionFactor::solve(const cholmod_factor& L, const Eigen::VectorXd& b,
                                  Eigen::VectorXd& x) {
  const auto n = static_cast<Eigen::Index>(L.n);
  if (b.size() != n) throw InvalidArgument("single-precision factor: right-hand side size");
  if (values_.size() != L.xsize)
    throw InvalidArgument("single-precision factor: assign() the factor before solving");
  const int* perm = ints(L.Perm);
  const int* super = ints(L.super);
  const int* row_start = ints(L.pi);    // per supernode: first entry in rows
  const int* value_start = ints(L.px);  // per supernode: first entry in values_
  const int* rows = ints(L.s);
  const auto nsuper = static_cast<Eigen::Index>(L.nsuper);
  y_.resize(static_cast<std::size_t>(n));
  work_.resize(L.maxesize);
  // No permutation stored: the natural ordering.
  for (Eigen::Index k = 0; k < n; ++k) y_[k] = static_cast<float>(b[perm ? perm[k] : k]);

  // Forward, L y = P b, supernode by supernode: the diagonal block's triangular solve, then the
  // off-diagonal rows' products subtracted from the rows they stand for.
  for (Eigen::Index s = 0; s < nsuper; ++s) {
    const int k1 = super[s], ncol = super[s + 1] - k1;
    const int nrow = row_start[s + 1] - row_start[s], below = nrow - ncol;
    const float* block = values_.data() + value_start[s];
    Eigen::Map<Vec> ys(y_.data() + k1, ncol);
    Block(block, ncol, ncol, Eigen::OuterStride<>(nrow))
        .triangularView<Eigen::Lower>()
        .solveInPlace(ys);
    if (below == 0) continue;
    Eigen::Map<Vec> e(work_.data(), below);
    e.noalias() = Block(block + ncol, below, ncol, Eigen::OuterStride<>(nrow)) * ys;
    const int* r = rows + row_start[s] + ncol;
    for (int i = 0; i < below; ++i) y_[r[i]] -= work_[i];
  }
  // Backward, L^T z = y, in reverse: the off-diagonal rows' contributions gathered, then the
  // transposed diagonal block's triangular solve.
  for (Eigen::Index s = nsuper - 1; s >= 0; --s) {
    const int k1 = super[s], ncol = super[s + 1] - k1;
    const int nrow = row_start[s + 1] - row_start[s], below = nrow - ncol;
    const float* block = values_.data() + value_start[s];
    Eigen::Map<Vec> ys(y_.data() + k1, ncol);
    if (below > 0) {
      const int* r = rows + row_start[s] + ncol;
      for (int i = 0; i < below; ++i) work_[i] = y_[r[i]];
      const Eigen::Map<const Vec> e(work_.data(), below);
      ys.noalias() -= Block(block + ncol, below, ncol, Eigen::OuterStride<>(nrow)).transpose() * e;
    }
    Block(block, ncol, ncol, Eigen::OuterStride<>(nrow))
        .transpose()
        .triangularView<Eigen::Upper>()
        .solveInPlace(ys);
  }
  x.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) x[perm ? perm[k] : k] = static_cast<double>(y_[k]);
}

}  // namespace sutura::engine::detail
