// The parallel transpose product the dynamics use for the stiffness damping force
// (transpose_product.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <random>
#include <vector>

#include "transpose_product.hpp"

namespace sutura::engine {
namespace {

// A random rectangular matrix with enough entries to take the parallel path.
Eigen::SparseMatrix<double> random_matrix(int rows, int cols, int per_column, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> row(0, rows - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < cols; ++j)
    for (int k = 0; k < per_column; ++k) t.emplace_back(row(rng), j, value(rng));
  Eigen::SparseMatrix<double> A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = value(rng);
  return x;
}

TEST(TransposeProduct, EqualsEigensTransposeProduct) {
  for (const int per_column : {3, 40}) {  // below and above the parallel threshold
    const Eigen::SparseMatrix<double> A = random_matrix(3000, 5000, per_column, 7);
    const Eigen::VectorXd x = random_vector(A.rows(), 11);
    Eigen::VectorXd y;
    detail::transpose_product(A, x, y);
    const Eigen::VectorXd expected = A.transpose() * x;
    ASSERT_EQ(y.size(), A.cols());
    EXPECT_LE((y - expected).norm(), 1e-13 * expected.norm()) << per_column << " per column";
  }
}

TEST(TransposeProduct, GivesTheSameBitsOnOneAndTwoThreads) {
  const Eigen::SparseMatrix<double> A = random_matrix(20000, 20000, 30, 3);
  ASSERT_GE(A.nonZeros(), 100000);
  const Eigen::VectorXd x = random_vector(A.rows(), 5);
  const int before = omp_get_max_threads();
  Eigen::VectorXd one, two;
  omp_set_num_threads(1);
  detail::transpose_product(A, x, one);
  omp_set_num_threads(2);
  detail::transpose_product(A, x, two);
  omp_set_num_threads(before);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(0, std::memcmp(one.data(), two.data(), sizeof(double) * one.size()));
}

}  // namespace
}  // namespace sutura::engine
