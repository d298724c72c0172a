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

// CHOLMOD's analysis and factorisation of a matrix, its tree's split, and the two-thread
// factorisation prepared for them.
class ParallelCholesky : public ::testing::Test {
 protected:
  void prepare(const Eigen::SparseMatrix<double>& A) {
    llt.compute(A);
    ASSERT_EQ(llt.info(), Eigen::Success);
    split = detail::split_supernode_tree(llt.factor());
    parallel.prepare(A, llt.factor(), split);
    ASSERT_TRUE(parallel.prepared());
  }

  testing::SupernodalLlt llt;
  detail::SupernodeSplit split;
  detail::ParallelCholesky parallel;
};

// The factor agrees with CHOLMOD's own to rounding (another summation order), solves to
// double accuracy through CHOLMOD, and has the same bits on one and two threads.
TEST_F(ParallelCholesky, FactorsLikeCholmodAndGivesTheSameBitsOnOneAndTwoThreads) {
  Eigen::SparseMatrix<double> A = testing::grid_laplacian(100);
  ASSERT_NO_FATAL_FAILURE(prepare(A));
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
  const detail::SupernodalArrays a(llt.factor());
  for (int s = 0; s < static_cast<int>(llt.factor().nsuper); ++s) {
    const int ncol = a.ncol(s), nrow = a.nrow(s);
    for (int c = 0; c < ncol; ++c)
      for (int r = c; r < nrow; ++r) {
        const std::size_t k = static_cast<std::size_t>(a.value_start[s]) + c * nrow + r;
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
TEST_F(ParallelCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  const Eigen::SparseMatrix<double> A = testing::grid_laplacian(60);
  ASSERT_NO_FATAL_FAILURE(prepare(A));
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
