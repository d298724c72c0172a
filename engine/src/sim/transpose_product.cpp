#include "transpose_product.hpp"

#include <cassert>

namespace sutura::engine::detail {
namespace {

// Below this many entries a product takes a few tens of microseconds and waking a second
// thread costs as much as it saves (a judgement: measured only at 0.62M entries).
constexpr Eigen::Index kParallelEntries = 100000;

}  // namespace

void transpose_product(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& x,
                       Eigen::VectorXd& y) {
  assert(A.isCompressed() && x.size() == A.rows());
  const Eigen::Index n = A.cols();
  y.resize(n);
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* value = A.valuePtr();
  const double* xs = x.data();
  double* ys = y.data();
#pragma omp parallel for schedule(static) if (A.nonZeros() >= kParallelEntries)
  for (Eigen::Index j = 0; j < n; ++j) {
    double sum = 0.0;
    for (int k = outer[j]; k < outer[j + 1]; ++k) sum += value[k] * xs[inner[k]];
    ys[j] = sum;
  }
}

}  // namespace sutura::engine::detail
