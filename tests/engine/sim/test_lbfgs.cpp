// The L-BFGS inverse-Hessian product used by the static solver's quasi-Newton steps.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "lbfgs.hpp"

namespace sutura::engine::detail {
namespace {

// A random symmetric positive definite matrix (fixed seed) and the initial inverse H0 = D^-1
// of its diagonal, as a solve callback.
struct Quadratic {
  Eigen::MatrixXd A;
  Eigen::VectorXd d;
  explicit Quadratic(int n) {
    std::srand(7);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
    A = B * B.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    d = A.diagonal();
  }
  [[nodiscard]] bool h0(const Eigen::VectorXd& q, Eigen::VectorXd& z) const {
    z = q.cwiseQuotient(d);
    return true;
  }
};

TEST(Lbfgs, WithoutPairsItIsTheInitialInverse) {
  const Quadratic f(6);
  const LbfgsHistory h(4);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(6, 1.0, 6.0);
  Eigen::VectorXd z;
  ASSERT_TRUE(h.apply(q, z, [&](const auto& a, auto& b) { return f.h0(a, b); }));
  EXPECT_LT((z - q.cwiseQuotient(f.d)).norm(), 1e-15);
}

// Every BFGS update makes H satisfy the secant equation H y = s of the pair just added, and
// keeps H symmetric positive definite.
TEST(Lbfgs, SatisfiesTheSecantEquationAndStaysPositiveDefinite) {
  const int n = 8;
  const Quadratic f(n);
  LbfgsHistory h(5);
  const auto h0 = [&](const Eigen::VectorXd& a, Eigen::VectorXd& b) { return f.h0(a, b); };
  std::srand(11);
  for (int k = 0; k < 7; ++k) {
    const Eigen::VectorXd s = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd y = f.A * s;  // the gradient change of the quadratic
    ASSERT_TRUE(h.add(s, y));
    Eigen::VectorXd z;
    ASSERT_TRUE(h.apply(y, z, h0));
    EXPECT_LT((z - s).norm(), 1e-12 * s.norm()) << "pair " << k;
    // H as a matrix, column by column: symmetric and positive definite.
    Eigen::MatrixXd H(n, n);
    for (int j = 0; j < n; ++j) {
      Eigen::VectorXd col;
      ASSERT_TRUE(h.apply(Eigen::VectorXd::Unit(n, j), col, h0));
      H.col(j) = col;
    }
    EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(0.5 * (H + H.transpose())).info(), Eigen::Success);
  }
  EXPECT_EQ(h.size(), 5);  // the depth: the oldest pairs were dropped
}

// With n conjugate directions of the quadratic (A-orthogonal), BFGS recovers the exact inverse
// Hessian (Nocedal & Wright, Theorem 6.4 setting): H = A^-1 whatever H0 was.
TEST(Lbfgs, RecoversTheInverseHessianFromConjugateDirections) {
  const int n = 6;
  const Quadratic f(n);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(f.A);  // eigenvectors are conjugate
  LbfgsHistory h(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::VectorXd s = eig.eigenvectors().col(k);
    ASSERT_TRUE(h.add(s, f.A * s));
  }
  const Eigen::MatrixXd inverse = f.A.inverse();
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd col;
    ASSERT_TRUE(h.apply(Eigen::VectorXd::Unit(n, j), col,
                        [&](const auto& a, auto& b) { return f.h0(a, b); }));
    EXPECT_LT((col - inverse.col(j)).norm(), 1e-12 * inverse.norm()) << "column " << j;
  }
}

// A pair with s.y <= 0 (negative curvature along s: the energy is not convex there) would make
// H indefinite; it is skipped, and so is a non-finite one.
TEST(Lbfgs, SkipsPairsWithoutPositiveCurvature) {
  LbfgsHistory h(3);
  const Eigen::VectorXd s = Eigen::VectorXd::Ones(4);
  EXPECT_FALSE(h.add(s, -s));
  EXPECT_FALSE(h.add(s, Eigen::VectorXd::Zero(4)));
  Eigen::VectorXd nan = s;
  nan[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(h.add(s, nan));
  EXPECT_EQ(h.size(), 0);
  EXPECT_TRUE(h.add(s, 2.0 * s));
  EXPECT_EQ(h.size(), 1);
}

}  // namespace
}  // namespace sutura::engine::detail
