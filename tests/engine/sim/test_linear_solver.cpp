#include <gtest/gtest.h>

#include <random>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/sim/linear_solver.hpp"

using namespace sutura::engine;

namespace {
// 2D Laplacian plus identity on an n x n grid: sparse, symmetric positive definite.
Eigen::SparseMatrix<double> spd(int n) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), 5.0);
      if (i + 1 < n) t.emplace_back(id(i, j), id(i + 1, j), -1.0), t.emplace_back(id(i + 1, j), id(i, j), -1.0);
      if (j + 1 < n) t.emplace_back(id(i, j), id(i, j + 1), -1.0), t.emplace_back(id(i, j + 1), id(i, j), -1.0);
    }
  Eigen::SparseMatrix<double> A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}
}  // namespace

TEST(LinearSolver, AllKindsSolveSpdSystem) {
  const auto A = spd(20);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd x_true(A.rows());
  for (int i = 0; i < x_true.size(); ++i) x_true[i] = u(rng);
  const Eigen::VectorXd b = A * x_true;
  for (auto kind : {LinearSolverKind::Cholmod, LinearSolverKind::Ldlt, LinearSolverKind::Pcg}) {
    auto s = make_linear_solver(kind);
    ASSERT_TRUE(s->factorize(A)) << to_string(kind);
    Eigen::VectorXd x;
    ASSERT_TRUE(s->solve(b, x)) << to_string(kind);
    EXPECT_LT((x - x_true).norm() / x_true.norm(), 1e-8) << to_string(kind);
    // Reuse with new values on the same pattern (symbolic analysis cached).
    Eigen::SparseMatrix<double> A2 = 2.0 * A;
    ASSERT_TRUE(s->factorize(A2));
    ASSERT_TRUE(s->solve(b, x));
    EXPECT_LT((x - 0.5 * x_true).norm() / x_true.norm(), 1e-8) << to_string(kind);
  }
}

TEST(LinearSolver, CholmodFallsBackOnIndefiniteMatrix) {
  Eigen::SparseMatrix<double> A = spd(6);
  A.coeffRef(0, 0) = -3.0;  // symmetric indefinite
  Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd b = A * x_true;
  auto s = make_linear_solver(LinearSolverKind::Cholmod);
  ASSERT_TRUE(s->factorize(A));
  EXPECT_NE(s->last_note().find("LDL"), std::string::npos);
  Eigen::VectorXd x;
  ASSERT_TRUE(s->solve(b, x));
  EXPECT_LT((x - x_true).norm(), 1e-9);
}

TEST(LinearSolver, CholmodFactorizeDefiniteRefusesIndefiniteMatrixWithoutFallback) {
  Eigen::SparseMatrix<double> A = spd(6);
  auto s = make_linear_solver(LinearSolverKind::Cholmod);
  ASSERT_TRUE(s->factorize_definite(A));
  Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0), x;
  ASSERT_TRUE(s->solve(A * x_true, x));
  EXPECT_LT((x - x_true).norm(), 1e-9);
  A.coeffRef(0, 0) = -3.0;  // symmetric indefinite: no LDL^T behind the caller's back
  EXPECT_FALSE(s->factorize_definite(A));
  EXPECT_NE(s->last_note().find("not positive definite"), std::string::npos);
  EXPECT_EQ(s->last_note().find("LDL"), std::string::npos);
}

TEST(LinearSolver, FactorizeIndefiniteGoesStraightToLdltAndSolves) {
  // After a failed factorize_definite the caller asks for the indefinite path directly; the
  // solve must then use the LDL^T factor, not the failed Cholesky one. Then a definite
  // matrix again: back to Cholesky (no LDL^T note).
  Eigen::SparseMatrix<double> A = spd(6);
  A.coeffRef(0, 0) = -3.0;
  const Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  for (auto kind : {LinearSolverKind::Cholmod, LinearSolverKind::Ldlt}) {
    auto s = make_linear_solver(kind);
    if (kind == LinearSolverKind::Cholmod) {
      ASSERT_FALSE(s->factorize_definite(A));
    }
    ASSERT_TRUE(s->factorize_indefinite(A)) << to_string(kind);
    if (kind == LinearSolverKind::Cholmod) {
      EXPECT_NE(s->last_note().find("LDL"), std::string::npos);
    }
    Eigen::VectorXd x;
    ASSERT_TRUE(s->solve(A * x_true, x)) << to_string(kind);
    EXPECT_LT((x - x_true).norm(), 1e-9) << to_string(kind);
    const Eigen::SparseMatrix<double> B = spd(6);
    ASSERT_TRUE(s->factorize(B));
    EXPECT_EQ(s->last_note().find("LDL"), std::string::npos);
    ASSERT_TRUE(s->solve(B * x_true, x));
    EXPECT_LT((x - x_true).norm(), 1e-9) << to_string(kind);
  }
}

TEST(LinearSolver, ParseNames) {
  EXPECT_EQ(parse_linear_solver("pcg"), LinearSolverKind::Pcg);
  EXPECT_EQ(to_string(parse_linear_solver("cholmod")), "cholmod");
  EXPECT_THROW(parse_linear_solver("lu"), InvalidArgument);
}
