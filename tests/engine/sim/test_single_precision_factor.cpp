// The single-precision copy of a CHOLMOD factor and its two-thread solves
// (single_precision_factor.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <algorithm>
#include <vector>

#include "single_precision_factor.hpp"

namespace sutura::engine {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

class SupernodalLlt : public Eigen::CholmodSupernodalLLT<SpMat, Eigen::Lower> {
 public:
  [[nodiscard]] const cholmod_factor& factor() const { return *m_cholmodFactor; }
};

// 2D Laplacian plus identity on an n x n grid (CHOLMOD orders it by nested dissection).
SpMat grid(int n) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), 5.0);
      if (i + 1 < n) t.emplace_back(id(i, j), id(i + 1, j), -1.0), t.emplace_back(id(i + 1, j), id(i, j), -1.0);
      if (j + 1 < n) t.emplace_back(id(i, j), id(i, j + 1), -1.0), t.emplace_back(id(i, j + 1), id(i, j), -1.0);
    }
  SpMat A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

const int* ints(const void* p) { return static_cast<const int*>(p); }

// Every supernode is in exactly one list; the rows a half's supernode updates belong to that
// half or to the top (so the halves can be solved at the same time); the top holds its own
// ancestors (it is solved after the halves, forward); the halves carry about equal weight.
TEST(SinglePrecisionFactor, SplitsTheTreeIntoTwoIndependentBalancedHalvesAndATop) {
  const SpMat A = grid(120);
  SupernodalLlt llt;
  llt.compute(A);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const cholmod_factor& L = llt.factor();
  detail::SinglePrecisionFactor f;
  f.assign(L);
  const int* super = ints(L.super);
  const int* row_start = ints(L.pi);
  const int* rows = ints(L.s);
  const auto nsuper = static_cast<int>(L.nsuper);
  std::vector<int> group(static_cast<std::size_t>(nsuper), -2), column_group(L.n, -2);
  const auto put = [&](int s, int g) {
    ASSERT_EQ(group[s], -2) << "supernode " << s << " listed twice";
    group[s] = g;
    for (int k = super[s]; k < super[s + 1]; ++k) column_group[k] = g;
  };
  for (int h = 0; h < 2; ++h)
    for (const int s : f.halves()[h]) put(s, h);
  for (const int s : f.top()) put(s, -1);
  ASSERT_TRUE(std::none_of(group.begin(), group.end(), [](int g) { return g == -2; }));
  double weight[2] = {0.0, 0.0};
  for (int s = 0; s < nsuper; ++s) {
    const int ncol = super[s + 1] - super[s], nrow = row_start[s + 1] - row_start[s];
    if (group[s] >= 0) weight[group[s]] += static_cast<double>(nrow) * ncol;
    for (int p = row_start[s] + ncol; p < row_start[s + 1]; ++p) {
      const int g = column_group[rows[p]];
      if (group[s] >= 0) EXPECT_TRUE(g == group[s] || g == -1) << "supernode " << s;
      else EXPECT_EQ(g, -1) << "top supernode " << s << " updates a half";
    }
  }
  EXPECT_GT(weight[0], 0.0);
  EXPECT_GT(weight[1], 0.0);
  EXPECT_LE(std::max(weight[0], weight[1]), 0.55 * (weight[0] + weight[1]));
  EXPECT_LT(f.top().size(), static_cast<std::size_t>(nsuper) / 10);
}

// The halves run on two threads or one after the other: the same operations in the same
// order, so the same bits; and the answer is the single-precision one.
TEST(SinglePrecisionFactor, SolvesGiveTheSameBitsOnOneAndTwoThreads) {
  const SpMat A = grid(120);
  SupernodalLlt llt;
  llt.compute(A);
  ASSERT_EQ(llt.info(), Eigen::Success);
  detail::SinglePrecisionFactor f;
  f.assign(llt.factor());
  const Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd b = A * x_true;
  const int threads = omp_get_max_threads();
  Eigen::VectorXd one, two;
  omp_set_num_threads(1);
  f.solve(llt.factor(), b, one);
  omp_set_num_threads(2);
  f.solve(llt.factor(), b, two);
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);
  const double error = (two - x_true).norm() / x_true.norm();
  EXPECT_LT(error, 1e-6);
  EXPECT_GT(error, 1e-12);  // single precision, not the double solve
}

}  // namespace
}  // namespace sutura::engine
