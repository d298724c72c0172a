// The collapse barrier (area_barrier.hpp): derivatives against central differences, inactive
// above its activation ratio, unbounded as a triangle collapses, and what it does to a solve.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim_fixture.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/sim/area_barrier.hpp"
#include "sutura/engine/sim/static_solver.hpp"

using namespace sutura::engine;
using sutura::engine::testing::Cantilever;

namespace {

double barrier_energy(const AreaBarrier& b, const ShellState& s, int d, Eigen::VectorXd* g = nullptr,
                      Triplets* K = nullptr) {
  Eigen::VectorXd local = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.x.size() * d));
  const double e = b.add_energy_gradient_hessian(s, d, local, K);
  if (g != nullptr) *g = local;
  return e;
}

/// A 2 x 1 strip (4 triangles) whose corner (2, 0.5) is pushed towards the opposite edge so
/// the triangles using it keep about 10 % of their area, then perturbed at random in 3D.
ShellState squashed(const Cantilever& c, unsigned seed) {
  ShellState s = c.state;
  const auto v = select_vertices(c.mesh.positions(), SelectNearest{{Vec3(2, 0.5, 0)}})[0];
  s.x[v.index()].y() = -0.4;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (Vec3& x : s.x) x += Vec3(u(rng), u(rng), u(rng));
  return s;
}

}  // namespace

TEST(AreaBarrier, GradientAndHessianMatchCentralDifferences) {
  Cantilever c(make_corotational_shell(), 0.0, 2, 1, 2.0, 1.0, 0.1, 1.0);
  const AreaBarrier barrier(c.sys.problem, AreaBarrierParams{});
  const int d = 6;
  for (unsigned seed : {1u, 2u, 3u}) {
    ShellState s = squashed(c, seed);
    Eigen::VectorXd g;
    Triplets trip;
    const double e = barrier_energy(barrier, s, d, &g, &trip);
    ASSERT_GT(e, 0.0);
    const Eigen::Index n = g.size();
    Eigen::SparseMatrix<double> H(n, n);
    H.setFromTriplets(trip.begin(), trip.end());
    const Eigen::MatrixXd Hd = Eigen::MatrixXd(H);
    EXPECT_LT((Hd - Hd.transpose()).norm(), 1e-12 * Hd.norm());
    const double h = 1e-6;
    for (std::size_t v = 0; v < s.x.size(); ++v) {
      for (int k = 0; k < 3; ++k) {
        ShellState p = s, m = s;
        p.x[v][k] += h;
        m.x[v][k] -= h;
        Eigen::VectorXd gp, gm;
        const double ep = barrier_energy(barrier, p, d, &gp);
        const double em = barrier_energy(barrier, m, d, &gm);
        const Eigen::Index row = static_cast<Eigen::Index>(d * v + k);
        EXPECT_NEAR(g[row], (ep - em) / (2 * h), 1e-6 * (1.0 + std::abs(g[row]))) << v << " " << k;
        const Eigen::VectorXd column = (gp - gm) / (2 * h);
        EXPECT_LT((Hd.col(row) - column).norm(), 1e-5 * (1.0 + Hd.norm())) << v << " " << k;
      }
      for (int k = 3; k < 6; ++k) EXPECT_EQ(g[static_cast<Eigen::Index>(d * v + k)], 0.0);
    }
  }
}

TEST(AreaBarrier, InactiveAboveActivationAndUnboundedAtCollapse) {
  Cantilever c(make_corotational_shell(), 0.0, 2, 1, 2.0, 1.0, 0.1, 1.0);
  const AreaBarrier barrier(c.sys.problem, AreaBarrierParams{});
  Eigen::VectorXd g;
  Triplets trip;
  // Rest shape, a rigid motion and a stretch: no energy, no force, no stiffness.
  ShellState s = c.state;
  EXPECT_EQ(barrier_energy(barrier, s, 6, &g, &trip), 0.0);
  EXPECT_EQ(g.norm(), 0.0);
  EXPECT_TRUE(trip.empty());
  const Eigen::AngleAxisd R(1.1, Vec3(0.3, -1, 2).normalized());
  for (Vec3& x : s.x) x = 1.5 * (R * x) + Vec3(3, 1, -2);
  EXPECT_EQ(barrier_energy(barrier, s, 6, &g), 0.0);
  // Squash the corner's triangles: at ratio r the energy grows like -ln r.
  const auto v = select_vertices(c.mesh.positions(), SelectNearest{{Vec3(2, 0.5, 0)}})[0];
  double previous = 0.0;
  for (const double r : {0.3, 0.2, 0.1, 1e-2, 1e-4, 1e-8}) {
    ShellState q = c.state;
    q.x[v.index()].y() = -0.5 + r;  // the triangles using it keep the fraction r of their area
    const double e = barrier_energy(barrier, q, 6);
    if (r >= 0.25) {
      EXPECT_EQ(e, 0.0);
    } else {
      EXPECT_GT(e, previous) << r;
      previous = e;
    }
  }
  EXPECT_GT(previous, 5.0 * barrier_energy(barrier, [&] {
    ShellState q = c.state;
    q.x[v.index()].y() = -0.5 + 1e-2;
    return q;
  }(), 6));
  // Fully collapsed: infinite, which the solvers treat as non-finite.
  ShellState flat = c.state;
  flat.x[v.index()].y() = -0.5;
  EXPECT_TRUE(std::isinf(barrier_energy(barrier, flat, 6)));
}

TEST(AreaBarrier, RejectsBadParameters) {
  Cantilever c(make_corotational_shell(), 0.0, 1, 1);
  EXPECT_THROW(AreaBarrier(c.sys.problem, AreaBarrierParams{1.0, 1.0}), InvalidArgument);
  EXPECT_THROW(AreaBarrier(c.sys.problem, AreaBarrierParams{0.25, 0.0}), InvalidArgument);
}
