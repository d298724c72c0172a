// patch_plan: a patch cut flat, laid over an incision, and its edges paired with the lips.
#include "sutura/engine/surgery/patch_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/surface_point.hpp"

namespace sutura::engine {
namespace {

const Vec3 kStart(4, 0, 6.0), kEnd(4, 0, 14.0);  // an 8 mm slit along a tube's wall

IncisionResult slit() { return incise(make_tube({4.0, 20.0, 48, 40}), {kStart, kEnd}); }

TEST(PatchPlan, AnEllipseIsCutFlatAndLaidOnTheHostOverTheSlit) {
  const IncisionResult cut = slit();
  PatchPlanParams pp;
  pp.width = 3.0;
  const PatchPlan plan = plan_patch(cut.mesh, kStart, kEnd, pp);
  EXPECT_NEAR(plan.incision_length, 8.0, 0.05);
  EXPECT_NEAR(chain_length(cut.mesh, plan.lip_left), 8.0, 0.05);
  EXPECT_NEAR(chain_length(cut.mesh, plan.lip_right), 8.0, 0.05);
  // Cut flat: every rest vertex in one plane.
  const auto& r = plan.rest.positions();
  const Vec3 n = (r[1] - r[0]).cross(r[2] - r[0]).normalized();
  double off_plane = 0.0;
  for (const Vec3& p : r) off_plane = std::max(off_plane, std::abs(n.dot(p - r[0])));
  EXPECT_LT(off_plane, 1e-9);
  // Laid over the closed slit as a narrow tent: its edges beside the lips (within 0.4 lip
  // edge lengths, here 0.26 mm of 0.52), the rest arched outwards, never into the lumen, and
  // no triangle degenerate.
  EXPECT_EQ(plan.placed.faces(), plan.rest.faces());
  for (const auto& chain : {plan.edge_left, plan.edge_right})
    for (VertexId v : chain.vertices)
      EXPECT_LT(closest_surface_point(cut.mesh, plan.placed.position(v)).distance, 0.27) << v.value;
  for (const Vec3& p : plan.placed.positions()) {
    // Not into the lumen: the edges are offset in the lips' (faceted) tangent planes, so they
    // may dip below the round tube by a fraction of the 0.52 mm lip spacing, no more.
    EXPECT_GE(std::hypot(p.x(), p.y()), 4.0 - 0.05);
    EXPECT_LT(std::hypot(p.x(), p.y()), 4.0 + 0.76);  // a tent of half the half-width at most
  }
  for (std::size_t f = 0; f < plan.placed.num_faces(); ++f)
    EXPECT_GT(plan.placed.face_area(FaceId{int(f)}), 1e-6) << f;
  // Its outline is as long as the ellipse's (the rest edges of both sides add up to it).
  const double a = 4.0, b = 1.5;  // semi-axes: length 8 (the slit), width 3
  const double h = std::pow(a - b, 2) / std::pow(a + b, 2);
  const double ramanujan = std::numbers::pi * (a + b) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h)));
  const double outline = chain_length(plan.rest, plan.edge_left) + chain_length(plan.rest, plan.edge_right);
  EXPECT_NEAR(outline, ramanujan, 0.03 * ramanujan);
  // The edges run from end to end of the slit like the lips.
  EXPECT_GE(plan.edge_left.vertices.size(), 3u);
  EXPECT_GE(plan.edge_right.vertices.size(), 3u);
}

TEST(PatchPlan, ShapesThatDoNotFitTheIncisionAreRefused) {
  const IncisionResult cut = slit();
  PatchPlanParams pp;
  pp.shape = PatchShape::Triangle;  // a gusset needs an incision opened from the boundary
  EXPECT_THROW(plan_patch(cut.mesh, kStart, kEnd, pp), InvalidArgument);
  pp.shape = PatchShape::Ellipse;
  pp.width = 0.1;  // 80 times narrower than long
  EXPECT_THROW(plan_patch(cut.mesh, kStart, kEnd, pp), InvalidArgument);
  pp.width = 3.0;
  EXPECT_THROW(plan_patch(cut.mesh, kStart + Vec3(0, 0, -4), kEnd, pp), InvalidArgument);  // no lip there
}

}  // namespace
}  // namespace sutura::engine
