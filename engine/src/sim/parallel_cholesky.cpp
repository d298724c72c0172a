#include "parallel_cholesky.hpp"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <stdexcept>

#include "blas_threads.hpp"

// BLAS and LAPACK (OpenBLAS here), Fortran calling convention; the one-character arguments'
// hidden lengths are not read by OpenBLAS (CHOLMOD declares them the same way).
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
            const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            double* b, const int* ldb);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* beta, double* c, const int* ldc);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b,
            const int* ldb, const double* beta, double* c, const int* ldc);
}

namespace sutura::engine::detail {

namespace {

constexpr int kTopGroup = 2;

}  // namespace

void ParallelCholesky::prepare(const Eigen::SparseMatrix<double>& A, const cholmod_factor& L,
                               const SupernodeSplit& split) {
  split_ = nullptr;
  if (!L.is_super || !L.is_ll || L.xtype != CHOLMOD_REAL || L.itype != CHOLMOD_INT ||
      L.x == nullptr || A.rows() != static_cast<Eigen::Index>(L.n))
    throw std::logic_error("parallel Cholesky: needs a numeric supernodal LL^T factor of A");
  if (!A.isCompressed()) return;  // left to CHOLMOD: the fill map indexes compressed values
  const auto n = static_cast<int>(L.n);
  const auto nsuper = static_cast<int>(L.nsuper);
  const SupernodalArrays a(L);
  const int* row_start = a.row_start;
  const int* rows = a.rows;
  const auto* perm = static_cast<const int*>(L.Perm);
  // The fan-out finds an update's rows in its target's row list by one merge walk: both must
  // be increasing. CHOLMOD's are; a factor whose are not is left to CHOLMOD (not prepared).
  for (int s = 0; s < nsuper; ++s)
    for (int p = row_start[s] + 1; p < row_start[s + 1]; ++p)
      if (rows[p] <= rows[p - 1]) return;
  std::vector<int> group(static_cast<std::size_t>(nsuper), kTopGroup);
  for (int h = 0; h < 2; ++h)
    for (const int s : split.halves[h]) group[s] = h;
  top_offset_.assign(static_cast<std::size_t>(nsuper), -1);
  top_size_ = 0;
  for (const int s : split.top) {
    top_offset_[s] = top_size_;
    top_size_ += a.block_size(s);
  }
  std::vector<int> inverse(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) inverse[perm ? perm[k] : k] = k;
  for (auto& f : fill_) f.clear();
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  for (int j = 0; j < n; ++j) {
    for (int e = outer[j]; e < outer[j + 1]; ++e) {
      if (inner[e] < j) continue;  // the lower triangle, as CHOLMOD reads A
      const int p = inverse[inner[e]], q = inverse[j];
      const int r = std::max(p, q), c = std::min(p, q);
      const int s = split.column_super[c];
      const int* first = rows + row_start[s];
      const int* last = rows + row_start[s + 1];
      const int* at = std::lower_bound(first, last, r);
      if (at == last || *at != r)
        throw std::logic_error("parallel Cholesky: an entry of A is outside the factor's pattern");
      fill_[group[s]].emplace_back(e, a.value_start[s] +
                                          static_cast<std::int64_t>(c - a.super[s]) * a.nrow(s) +
                                          (at - first));
    }
  }
  split_ = &split;
}

int ParallelCholesky::factorize_group(const Eigen::SparseMatrix<double>& A, cholmod_factor& L,
                                      int g) {
  const SupernodalArrays a(L);
  const int* super = a.super;
  const int* row_start = a.row_start;
  const int* value_start = a.value_start;
  const int* rows = a.rows;
  const SupernodeSplit& split = *split_;
  auto* x = static_cast<double*>(L.x);
  const std::vector<int>& supernodes = g == kTopGroup ? split.top : split.halves[g];
  // A's entries into the zeroed blocks; the top also takes both halves' updates.
  for (const int s : supernodes)
    std::fill(x + value_start[s], x + value_start[s] + a.block_size(s), 0.0);
  const double* values = A.valuePtr();
  for (const auto& [from, to] : fill_[g]) x[to] = values[from];
  if (g == kTopGroup) {
    for (int h = 0; h < 2; ++h)
      for (const int s : split.top) {
        const double* copy = top_copy_[h].data() + top_offset_[s];
        double* block = x + value_start[s];
        for (std::int64_t k = 0; k < a.block_size(s); ++k) block[k] += copy[k];
      }
  }
  std::vector<double>& update = update_[g == kTopGroup ? 0 : g];
  std::vector<int>& relative = relative_[g == kTopGroup ? 0 : g];
  const double one = 1.0, zero = 0.0;
  for (const int s : supernodes) {
    const int k1 = super[s], ncol = a.ncol(s), nrow = a.nrow(s), below = nrow - ncol;
    double* block = x + value_start[s];
    int info = 0;
    dpotrf_("L", &ncol, block, &nrow, &info);
    if (info != 0) return k1 + info - 1;
    if (below == 0) continue;
    dtrsm_("R", "L", "T", "N", &below, &ncol, &one, block, &nrow, block + ncol, &nrow);
    // Fan-out: the rows below, in runs that belong to one ancestor t each.
    const int* r = rows + row_start[s] + ncol;
    for (int j = 0; j < below;) {
      const int t = split.column_super[r[j]];
      int e = j;
      while (e < below && r[e] < super[t + 1]) ++e;
      const int m = below - j, width = e - j, rest = m - width;
      update.resize(static_cast<std::size_t>(m) * width);
      // C = L_s(rows j.., :) L_s(rows j..e, :)^T, m x width: its top square by syrk (lower
      // half), the rows under it by gemm.
      dsyrk_("L", "N", &width, &ncol, &one, block + ncol + j, &nrow, &zero, update.data(), &m);
      if (rest > 0)
        dgemm_("N", "T", &rest, &width, &ncol, &one, block + ncol + e, &nrow, block + ncol + j,
               &nrow, &zero, update.data() + width, &m);
      const int trow = a.nrow(t);
      const int* target_rows = rows + row_start[t];
      relative.resize(static_cast<std::size_t>(m));
      for (int i = 0, p = 0; i < m; ++i) {
        while (p < trow && target_rows[p] != r[j + i]) ++p;
        if (p == trow) throw std::logic_error("parallel Cholesky: an update outside its target");
        relative[i] = p;
      }
      double* target = (g != kTopGroup && split.is_top_column[r[j]])
                           ? top_copy_[g].data() + top_offset_[t]
                           : x + value_start[t];
      for (int c = 0; c < width; ++c) {
        double* column = target + static_cast<std::int64_t>(r[j + c] - super[t]) * trow;
        const double* u = update.data() + static_cast<std::int64_t>(c) * m;
        for (int i = c; i < m; ++i) column[relative[i]] -= u[i];
      }
      j = e;
    }
  }
  return -1;
}

bool ParallelCholesky::factorize(const Eigen::SparseMatrix<double>& A, cholmod_factor& L) {
  if (!prepared() || A.rows() != static_cast<Eigen::Index>(L.n) || !A.isCompressed())
    throw std::logic_error("parallel Cholesky: prepare() for this structure first");
  const SingleThreadedBlas one_thread;  // each half's kernels on its own thread
  for (int h = 0; h < 2; ++h) top_copy_[h].assign(static_cast<std::size_t>(top_size_), 0.0);
  int failed[3] = {-1, -1, -1};  // per group: the column whose pivot failed
  const bool parallel = omp_get_max_threads() > 1;
  std::exception_ptr error[2];  // an exception must not leave an OpenMP region
#pragma omp parallel for num_threads(2) schedule(static, 1) if (parallel)
  for (int h = 0; h < 2; ++h) {
    try {
      failed[h] = factorize_group(A, L, h);
    } catch (...) {
      error[h] = std::current_exception();
    }
  }
  for (const auto& e : error)
    if (e) std::rethrow_exception(e);
  if (failed[0] < 0 && failed[1] < 0) failed[kTopGroup] = factorize_group(A, L, kTopGroup);
  int minor = static_cast<int>(L.n);
  for (const int f : failed)
    if (f >= 0) minor = std::min(minor, f);
  L.minor = static_cast<std::size_t>(minor);
  return minor == static_cast<int>(L.n);
}

}  // namespace sutura::engine::detail
