#include <gtest/gtest.h>

#include <cmath>

#include "sim_fixture.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/sim/stability.hpp"
#include "sutura/engine/sim/static_solver.hpp"

using namespace sutura::engine;
using sutura::engine::testing::Cantilever;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The clamped strip of sim_fixture (L 10, b 1, t 0.1, E 1.2e6, nu 0; EI = 100) compressed
// along its axis by a dead load P at the free end, solved to its straight equilibrium (a
// perfect strip stays straight past buckling: Newton with LDL^T finds the unstable branch).
Stability compressed(double P, int nl, const StabilityParams& params = {}) {
  Cantilever c(make_corotational_shell(), 0.0, nl, 2);
  c.sys.loads.nodal.clear();
  const auto tip = select_vertices(c.mesh.positions(),
                                   SelectPlaneBand{Vec3(10, 0, 0), Vec3(1, 0, 0), 1e-9});
  for (auto v : tip) c.sys.loads.nodal.push_back({v.index(), Vec3(-P / tip.size(), 0, 0), Vec3::Zero()});
  const StaticResult r = solve_static(c.sys, c.state, StaticSolverParams{});
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_LT(std::abs(c.tip_displacement().z()), 1e-9) << "the strip stayed straight";
  return check_stability(c.sys, c.state, params);
}

}  // namespace

TEST(Stability, EulerBucklingLoadsOfAClampedStripSeparateStableFromUnstable) {
  // Euler's column clamped at one end, free at the other: P_n = (2n-1)^2 pi^2 EI / (4 L^2),
  // so P_1 = 2.4674 and P_2 = 9 P_1. Below P_1 the straight strip is stable; between P_1 and
  // P_2 it has one unstable mode, above P_2 two (torsion and in-plane bending buckle far
  // higher: 2 E t^3 / b = 2400 and pi^2 E t b^3 / 48 = 2467). Bisected on this mesh (40
  // elements along the strip) the sign changes come at 1.00006 P_1 and 1.00065 P_2; the test
  // brackets each within 1%.
  const double P1 = kPi * kPi * 100.0 / (4.0 * 10.0 * 10.0);
  const Stability below = compressed(0.99 * P1, 40);
  EXPECT_TRUE(below.stable) << below.summary;
  EXPECT_EQ(below.negative_modes, 0);
  EXPECT_FALSE(below.singular);
  const Stability first = compressed(1.01 * P1, 40);
  EXPECT_FALSE(first.stable) << first.summary;
  EXPECT_FALSE(first.singular);
  EXPECT_EQ(first.negative_modes, 1) << first.summary;
  EXPECT_NE(first.summary.find("1 negative eigenvalue"), std::string::npos) << first.summary;
  EXPECT_EQ(compressed(0.99 * 9.0 * P1, 40).negative_modes, 1);
  EXPECT_EQ(compressed(1.01 * 9.0 * P1, 40).negative_modes, 2);
  // In tension nothing buckles.
  EXPECT_TRUE(compressed(-10.0 * P1, 40).stable);
}

TEST(Stability, TheUnstableModeOfACompressedStripIsEulersFirstBucklingMode) {
  // Between P_1 and P_2 the one direction of negative curvature is the first buckling mode,
  // w(x) = 1 - cos(pi x / (2 L)) for the clamped-free column.
  const double P1 = kPi * kPi * 100.0 / 400.0;
  for (const double factor : {0.5, 1.5}) {
    Cantilever c(make_corotational_shell(), 0.0, 40, 2);
    c.sys.loads.nodal.clear();
    const auto tip = select_vertices(c.mesh.positions(),
                                     SelectPlaneBand{Vec3(10, 0, 0), Vec3(1, 0, 0), 1e-9});
    for (auto v : tip)
      c.sys.loads.nodal.push_back({v.index(), Vec3(-factor * P1 / tip.size(), 0, 0), Vec3::Zero()});
    ASSERT_TRUE(solve_static(c.sys, c.state, StaticSolverParams{}).converged);
    const std::optional<UnstableMode> mode = unstable_mode(c.sys, c.state);
    if (factor < 1.0) {
      EXPECT_FALSE(mode.has_value()) << "stable below P_1";
      continue;
    }
    ASSERT_TRUE(mode.has_value());
    EXPECT_LT(mode->curvature, 0.0);
    // Correlation of the modal deflection w (the z translations) with Euler's shape.
    double ww = 0.0, ee = 0.0, we = 0.0;
    for (std::size_t i = 0; i < c.mesh.num_vertices(); ++i) {
      const double w = mode->direction[Eigen::Index(6 * i + 2)];
      const double e = 1.0 - std::cos(kPi * c.mesh.position(VertexId(i)).x() / 20.0);
      ww += w * w, ee += e * e, we += w * e;
    }
    EXPECT_GT(std::abs(we) / std::sqrt(ww * ee), 0.999);
  }
}

TEST(Stability, ModesAreCountedOnlyWhenAsked) {
  const double P1 = kPi * kPi * 100.0 / 400.0;
  StabilityParams p;
  p.count_modes = false;
  const Stability s = compressed(1.5 * P1, 20, p);
  EXPECT_FALSE(s.stable);
  EXPECT_EQ(s.negative_modes, -1);
  EXPECT_NE(s.summary.find("unstable"), std::string::npos) << s.summary;
}

TEST(Stability, AnUnsupportedStructureIsSingularNotStable) {
  // Free rigid-body motion: six zero eigenvalues, none negative.
  Cantilever c(make_corotational_shell(), 0.0, 8, 2);
  c.sys.constraints = Constraints{};
  const Stability s = check_stability(c.sys, c.state);
  EXPECT_TRUE(s.assessed);
  EXPECT_FALSE(s.stable) << s.summary;
  EXPECT_TRUE(s.singular) << s.summary;
  EXPECT_EQ(s.negative_modes, 0);
  EXPECT_NE(s.summary.find("6 eigenvalues near zero"), std::string::npos) << s.summary;
  // Held at one end but compressed past P_1: one unstable mode, nothing neutral.
  const double P1 = kPi * kPi * 100.0 / 400.0;
  const Stability one = compressed(1.5 * P1, 20);
  EXPECT_FALSE(one.singular) << one.summary;
  EXPECT_EQ(one.negative_modes, 1);
}

TEST(Stability, AWorkspaceGivesTheSameAnswerAndEveryDofHeldIsStable) {
  Cantilever c(make_corotational_shell(), 0.0, 8, 2);
  SolverWorkspace ws;
  EXPECT_TRUE(check_stability(c.sys, c.state, {}, &ws).stable);
  EXPECT_TRUE(check_stability(c.sys, c.state, {}, &ws).stable);
  // A workspace that served the checks (and the shifted factorisations of unstable_mode)
  // gives a later solve bit for bit what a fresh one gives.
  Cantilever a(make_corotational_shell(), 4.0, 8, 2), b(make_corotational_shell(), 4.0, 8, 2);
  EXPECT_FALSE(unstable_mode(a.sys, a.state, 1.0, 30, &ws).has_value());
  StaticSolverParams sp;
  sp.load_steps = 2;
  ASSERT_TRUE(solve_static(a.sys, a.state, sp, &ws).converged);
  ASSERT_TRUE(solve_static(b.sys, b.state, sp).converged);
  for (std::size_t i = 0; i < a.state.x.size(); ++i) EXPECT_EQ(a.state.x[i], b.state.x[i]);
  std::vector<VertexId> all;
  for (std::size_t v = 0; v < c.mesh.num_vertices(); ++v) all.emplace_back(v);
  c.sys.constraints.fix(all, kAllDofs, c.mesh.num_vertices());
  const Stability held = check_stability(c.sys, c.state);
  EXPECT_TRUE(held.stable);
  EXPECT_EQ(held.negative_modes, 0);
}

TEST(Stability, RejectsBadParameters) {
  Cantilever c(make_corotational_shell(), 0.0, 4, 1);
  StabilityParams p;
  p.lambda = std::nan("");
  EXPECT_THROW(check_stability(c.sys, c.state, p), InvalidArgument);
  p = {};
  p.zero_pivot = -1.0;
  EXPECT_THROW(check_stability(c.sys, c.state, p), InvalidArgument);
  p = {};
  p.neutral_band = 0.0;
  EXPECT_THROW(check_stability(c.sys, c.state, p), InvalidArgument);
  EXPECT_THROW(unstable_mode(c.sys, c.state, 1.0, 0), InvalidArgument);
}
