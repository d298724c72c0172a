// The two-thread numeric supernodal Cholesky on CHOLMOD's symbolic analysis
// (parallel_cholesky.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include <vector>

#include "cholmod_fixture.hpp"
#include "parallel_cholesky.hpp"

namespace sutura::engine {
namespace {

std::vector<double> values(const cholmod_factor& L) {
  const auto* x = static_cast<const double*>(L.x);
  return {x, x + L.xsize};
}

// The factor agrees with CHOLMOD's own to rounding (another summation order), solves to
// double accuracy through CHOLMOD, and has the same bits on one and two threads.
TEST(ParallelCholesky, FactorsLikeCholmodAndGivesTheSameBitsOnOneAndTwoThreads) {
  Eigen::SparseMatrix<double> A = testing::grid_laplacian(100);
  testing::SupernodalLlt llt;
  llt.compute(A);
  ASSERT_EQ(llt.info(), Eigen::Success);
  detail::ParallelCholesky parallel;
  parallel.prepare(A, llt.factor());
  ASSERT_TRUE(parallel.prepared());
  // New values on the same pattern, as in a Newton loop.
  A = A * 2.0;
  for (int i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 0.01 * (i % 7);
  llt.factorize(A);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const std::vector<double> cholmod = values(llt.factor());
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  ASSERT_TRUE(parallel.factorize(A, llt.factor()));
  const std::vector<double> one = values(llt.factor());
  omp_set_num_threads(2);
  ASSERT_TRUE(parallel.factorize(A, llt.factor()));
  const std::vector<double> two = values(llt.factor());
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);
  // Only the lower triangles of the diagonal blocks and the rows below them are the factor;
  // compare those through a solve and entrywise where CHOLMOD wrote.
  double largest = 0.0, difference = 0.0;
  const int* super = testing::ints(llt.factor().super);
  const int* row_start = testing::ints(llt.factor().pi);
  const int* value_start = testing::ints(llt.factor().px);
  for (std::size_t s = 0; s < llt.factor().nsuper; ++s) {
    const int ncol = super[s + 1] - super[s], nrow = row_start[s + 1] - row_start[s];
    for (int c = 0; c < ncol; ++c)
      for (int r = c; r < nrow; ++r) {
        const std::size_t k = static_cast<std::size_t>(value_start[s]) + c * nrow + r;
        largest = std::max(largest, std::abs(cholmod[k]));
        difference = std::max(difference, std::abs(cholmod[k] - two[k]));
      }
  }
  EXPECT_LT(difference, 1e-13 * largest);
  EXPECT_EQ(llt.factor().minor, llt.factor().n);
  const Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd x = llt.solve(A * x_true);
  EXPECT_LT((x - x_true).norm() / x_true.norm(), 1e-13);
}

// A matrix that is not positive definite is refused, wherever its bad pivot lies.
TEST(ParallelCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  const Eigen::SparseMatrix<double> A = testing::grid_laplacian(60);
  testing::SupernodalLlt llt;
  llt.compute(A);
  ASSERT_EQ(llt.info(), Eigen::Success);
  detail::ParallelCholesky parallel;
  parallel.prepare(A, llt.factor());
  ASSERT_TRUE(parallel.prepared());
  // The grid Laplacian's eigenvalues are diagonal - 4 cos(...) - 4 cos(...): a diagonal of 1
  // gives negative ones (indefinite), and so does one negative diagonal entry anywhere.
  EXPECT_FALSE(parallel.factorize(testing::grid_laplacian(60, 1.0), llt.factor()));
  EXPECT_LT(llt.factor().minor, llt.factor().n);
  for (const int at : {0, 1800, 3599}) {
    Eigen::SparseMatrix<double> B = A;
    B.coeffRef(at, at) = -1.0;
    EXPECT_FALSE(parallel.factorize(B, llt.factor())) << "negative pivot at " << at;
  }
  EXPECT_TRUE(parallel.factorize(A, llt.factor()));
  EXPECT_EQ(llt.factor().minor, llt.factor().n);
}

}  // namespace
}  // namespace sutura::engine
