// The single-precision copy of a CHOLMOD factor and its two-thread solves
// (single_precision_factor.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include "cholmod_fixture.hpp"
#include "single_precision_factor.hpp"

namespace sutura::engine {
namespace {

// The halves run on two threads or one after the other: the same operations in the same
// order, so the same bits; and the answer is the single-precision one.
TEST(SinglePrecisionFactor, SolvesGiveTheSameBitsOnOneAndTwoThreads) {
  const Eigen::SparseMatrix<double> A = testing::grid_laplacian(120);
  testing::SupernodalLlt llt;
  llt.compute(A);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const detail::SupernodeSplit split = detail::split_supernode_tree(llt.factor());
  detail::SinglePrecisionFactor f;
  f.assign(llt.factor());
  const Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd b = A * x_true;
  const int threads = omp_get_max_threads();
  Eigen::VectorXd one, two;
  omp_set_num_threads(1);
  f.solve(llt.factor(), split, b, one);
  omp_set_num_threads(2);
  f.solve(llt.factor(), split, b, two);
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);
  const double error = (two - x_true).norm() / x_true.norm();
  EXPECT_LT(error, 1e-6);
  EXPECT_GT(error, 1e-12);  // single precision, not the double solve
}

}  // namespace
}  // namespace sutura::engine
