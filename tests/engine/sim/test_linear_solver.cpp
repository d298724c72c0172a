#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim_fixture.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/sim/linear_solver.hpp"

using namespace sutura::engine;
using sutura::engine::testing::Cantilever;

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

// solve_approximately: Cholmod solves with its factor rounded to single precision (an answer
// within float accuracy, not the double one, the same bits every time, and always from the
// latest factorisation: new values on the same pattern, then a new pattern); after an
// indefinite fallback, and for the other kinds, it is the exact solve.
TEST(LinearSolver, SolveApproximatelyIsTheCholeskySolveInSinglePrecision) {
  const auto A = spd(40);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd x_true(A.rows());
  for (int i = 0; i < x_true.size(); ++i) x_true[i] = u(rng);
  const Eigen::VectorXd b = A * x_true;
  auto s = make_linear_solver(LinearSolverKind::Cholmod);
  ASSERT_TRUE(s->factorize(A));
  Eigen::VectorXd exact, x, again;
  ASSERT_TRUE(s->solve(b, exact));
  ASSERT_TRUE(s->solve_approximately(b, x));
  const double error = (x - x_true).norm() / x_true.norm();
  EXPECT_LT(error, 1e-6);   // cond(A) < 9: a few float roundings
  EXPECT_GT(error, 1e-12);  // not the double solve
  ASSERT_TRUE(s->solve_approximately(b, again));
  EXPECT_EQ(again, x);
  ASSERT_TRUE(s->factorize(4.0 * A));
  ASSERT_TRUE(s->solve_approximately(b, x));
  EXPECT_LT((x - 0.25 * x_true).norm() / x_true.norm(), 1e-6);
  const auto B = spd(30);
  const Eigen::VectorXd y_true = Eigen::VectorXd::LinSpaced(B.rows(), -2.0, 1.0);
  ASSERT_TRUE(s->factorize_definite(B));
  ASSERT_TRUE(s->solve_approximately(B * y_true, x));
  EXPECT_LT((x - y_true).norm() / y_true.norm(), 1e-6);

  Eigen::SparseMatrix<double> C = spd(6);
  C.coeffRef(0, 0) = -3.0;  // indefinite: the LDL^T fallback
  const Eigen::VectorXd c = C * Eigen::VectorXd::Ones(C.rows());
  ASSERT_TRUE(s->factorize(C));
  ASSERT_TRUE(s->solve(c, exact));
  ASSERT_TRUE(s->solve_approximately(c, x));
  EXPECT_EQ(x, exact);
  for (auto kind : {LinearSolverKind::Ldlt, LinearSolverKind::Pcg}) {
    auto other = make_linear_solver(kind);
    ASSERT_TRUE(other->factorize(A));
    ASSERT_TRUE(other->solve(b, exact));
    ASSERT_TRUE(other->solve_approximately(b, x));
    EXPECT_EQ(x, exact) << to_string(kind);
  }
}

// On a shell tangent (the Sze strip, 6 DOF per node, membrane and bending stiffness (L/t)^2
// apart) the single-precision solve stays close to the exact one: measured 4e-7 relative.
TEST(LinearSolver, SolveApproximatelyOnAShellTangent) {
  Cantilever c(make_corotational_shell(), 1.0, 32, 2);
  const DofMap map(c.sys);
  const Evaluation ev = evaluate(c.sys, map, c.state, 1.0, true);
  auto s = make_linear_solver(LinearSolverKind::Cholmod);
  ASSERT_TRUE(s->factorize_definite(ev.tangent));
  const Eigen::VectorXd b = -ev.residual;
  Eigen::VectorXd exact, x;
  ASSERT_TRUE(s->solve(b, exact));
  ASSERT_TRUE(s->solve_approximately(b, x));
  EXPECT_LT((x - exact).norm() / exact.norm(), 1e-5);
  EXPECT_GT((x - exact).norm() / exact.norm(), 1e-12);
}

// The single-precision solve stays accurate even for a nearly singular matrix: rounding an
// accurately computed Cholesky factor entry by entry perturbs the matrix relatively (small
// eigenvalues keep their relative accuracy), unlike a factorisation computed in single
// precision. The 2D grid shifted to within 1e-10 of singular (cond about 1e11): the answer
// within 1e-6 (measured 3e-7, as for the unshifted grid). approximate_solve_agrees compares
// against the exact answer it is given: 1 % off is rejected.
TEST(LinearSolver, SinglePrecisionSolvesStayAccurateNearSingularity) {
  const int n = 40;
  // spd(n)'s smallest eigenvalue: 5 - 4 cos(pi / (n + 1)).
  const double lowest = 5.0 - 4.0 * std::cos(std::acos(-1.0) / (n + 1));
  Eigen::SparseMatrix<double> A = spd(n);
  for (int i = 0; i < n * n; ++i) A.coeffRef(i, i) -= lowest - 1e-10;
  auto s = make_linear_solver(LinearSolverKind::Cholmod);
  ASSERT_TRUE(s->factorize_definite(A));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n * n);
  Eigen::VectorXd exact, x;
  ASSERT_TRUE(s->solve(b, exact));
  EXPECT_GT(exact.norm(), 1e10);  // b has a large component along the near-null vector
  ASSERT_TRUE(s->solve_approximately(b, x));
  EXPECT_LT((x - exact).norm() / exact.norm(), 1e-6);
  EXPECT_TRUE(approximate_solve_agrees(*s, b, exact));
  EXPECT_FALSE(approximate_solve_agrees(*s, b, 1.01 * exact));
  // An exact solver agrees with itself.
  auto ldlt = make_linear_solver(LinearSolverKind::Ldlt);
  ASSERT_TRUE(ldlt->factorize(A));
  ASSERT_TRUE(ldlt->solve(b, x));
  EXPECT_TRUE(approximate_solve_agrees(*ldlt, b, x));
}
