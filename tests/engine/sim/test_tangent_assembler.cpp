#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "sutura/engine/sim/tangent_assembler.hpp"

using namespace sutura::engine;

namespace {

// Random triplets with many duplicates (like overlapping element blocks), values spread over
// several magnitudes so that the summation order shows in the last bits.
Triplets random_triplets(int n, std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-8, 8);
  Triplets K;
  for (std::size_t i = 0; i < count; ++i)
    K.emplace_back(index(rng), index(rng), std::ldexp(mantissa(rng), exponent(rng)));
  return K;
}

// The reference: a dense sum over free rows and columns, each entry in triplet order.
Eigen::MatrixXd serial_sum(const Triplets& K, const std::vector<int>& full_to_free, int num_free,
                           Eigen::MatrixXd* touched) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(num_free, num_free);
  *touched = Eigen::MatrixXd::Zero(num_free, num_free);
  for (const auto& t : K) {
    const int r = full_to_free[t.row()], c = full_to_free[t.col()];
    if (r < 0 || c < 0) continue;
    A(r, c) += t.value();
    (*touched)(r, c) = 1.0;
  }
  return A;
}

}  // namespace

TEST(TangentAssembler, SumsDuplicatesInTripletOrderAndDropsFixedDofs) {
  const int n = 60;
  std::vector<int> full_to_free(n);
  int free = 0;
  for (int i = 0; i < n; ++i) full_to_free[i] = (i % 7 == 3) ? -1 : free++;
  TangentAssembler assembler;
  // Large enough for the parallel paths (threshold 10,000 triplets); called twice with the
  // same structure (new values: the cached map), then with two other structures (rebuilds).
  const std::pair<std::uint32_t, double> calls[] = {{1u, 1.0}, {1u, 3.0}, {2u, 1.0}, {3u, 1.0}};
  for (const auto& [seed, scale] : calls) {
    Triplets K = random_triplets(n, 40000, seed);
    for (auto& t : K) t = Eigen::Triplet<double>(t.row(), t.col(), scale * t.value());
    Eigen::SparseMatrix<double> A;
    assembler.assemble(K, full_to_free, free, A);
    Eigen::MatrixXd touched;
    const Eigen::MatrixXd expected = serial_sum(K, full_to_free, free, &touched);
    ASSERT_EQ(A.rows(), free);
    ASSERT_EQ(A.cols(), free);
    ASSERT_TRUE(A.isCompressed());
    EXPECT_EQ(A.nonZeros(), static_cast<Eigen::Index>(touched.sum())) << "seed " << seed;
    // Bit for bit: the same additions in the same order as the serial sum.
    for (int c = 0; c < free; ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
        EXPECT_EQ(touched(it.row(), c), 1.0);
        EXPECT_EQ(it.value(), expected(it.row(), c)) << "(" << it.row() << ", " << c << ")";
      }
  }
}

TEST(TangentAssembler, NoticesAChangeOfTheFixedDofs) {
  const int n = 20;
  const Triplets K = random_triplets(n, 500, 7);
  std::vector<int> all(n), some(n);
  int free = 0;
  for (int i = 0; i < n; ++i) all[i] = i;
  for (int i = 0; i < n; ++i) some[i] = i < 5 ? -1 : free++;
  TangentAssembler assembler;
  Eigen::SparseMatrix<double> A, B;
  assembler.assemble(K, all, n, A);
  assembler.assemble(K, some, free, B);
  Eigen::MatrixXd touched;
  EXPECT_EQ(Eigen::MatrixXd(A), serial_sum(K, all, n, &touched));
  EXPECT_EQ(Eigen::MatrixXd(B), serial_sum(K, some, free, &touched));
  // Everything fixed: an empty matrix, and back to all free.
  const std::vector<int> none(n, -1);
  Eigen::SparseMatrix<double> C;
  assembler.assemble(K, none, 0, C);
  EXPECT_EQ(C.rows(), 0);
  EXPECT_EQ(C.nonZeros(), 0);
  assembler.assemble(K, all, n, A);
  EXPECT_EQ(Eigen::MatrixXd(A), serial_sum(K, all, n, &touched));
}

TEST(TangentAssembler, LeavesEmptyColumnsEmpty) {
  // Triplets only in columns 1 and 4 of 6: the other columns have no entries.
  const Triplets K{{0, 1, 1.0}, {5, 1, 2.0}, {0, 1, 0.5}, {3, 4, -1.0}};
  std::vector<int> all{0, 1, 2, 3, 4, 5};
  TangentAssembler assembler;
  Eigen::SparseMatrix<double> A;
  assembler.assemble(K, all, 6, A);
  ASSERT_EQ(A.nonZeros(), 3);
  EXPECT_EQ(A.coeff(0, 1), 1.5);
  EXPECT_EQ(A.coeff(5, 1), 2.0);
  EXPECT_EQ(A.coeff(3, 4), -1.0);
  for (int c : {0, 2, 3, 5}) EXPECT_EQ(A.col(c).nonZeros(), 0) << "column " << c;
}
