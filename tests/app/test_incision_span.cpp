// incision_span: the piece of a vessel's centreline along an incision, which the planning
// window's patch design measures; and the design_patch op built from it.
#include "sutura/app/incision_span.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "sutura/app/op_builders.hpp"
#include "sutura/app/session.hpp"
#include "sutura/engine/generators.hpp"
#include "replay_fixture.hpp"

namespace {

using sutura::engine::Vec3;

sutura::engine::SurfaceMesh tube() {
  sutura::engine::TubeParams p;
  p.radius = 4.0;
  p.length = 40.0;
  p.segments_around = 32;
  p.segments_along = 40;
  return sutura::engine::make_tube(p);
}

// On a straight tube the span is the axis from 3 mm before the first end to 3 mm past the
// second, in the order given; its sections may be twice the radius wide.
TEST(IncisionSpan, RunsAlongTheAxisPastBothEnds) {
  const auto mesh = tube();
  const sutura::app::IncisionSpan span = sutura::app::incision_span(mesh, {4, 0, 25}, {0, 4, 12}, 3.0);
  ASSERT_GE(span.centreline.size(), 2u);
  EXPECT_NEAR(span.centreline.front().z(), 28.0, 0.3);
  EXPECT_NEAR(span.centreline.back().z(), 9.0, 0.3);
  EXPECT_NEAR(span.length_mm, 19.0, 0.3);
  for (const Vec3& p : span.centreline) EXPECT_LT(std::hypot(p.x(), p.y()), 0.2) << p.transpose();
  EXPECT_NEAR(span.max_radius_mm, 8.0, 0.4);
  // Within the path: a margin longer than the tube stops at its ends.
  const sutura::app::IncisionSpan whole = sutura::app::incision_span(mesh, {4, 0, 10}, {4, 0, 30}, 100.0);
  EXPECT_NEAR(whole.length_mm, 40.0, 1.0);
}

// Incised first: the slit (24 mm long, 48 mm round, longer than the tube's 25 mm ends) is
// neither the centreline's root nor a path end; the span still runs along the axis.
TEST(IncisionSpan, AnIncisionsSlitIsNotAnEnd) {
  const auto dir = sutura::testing::scratch_dir("incision_span", "slit");
  const sutura::app::ReplayResult r = sutura::testing::replay_text(
      "{\"format\": \"sutura-session\", \"version\": 3}\n"
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 40, "
      "\"segments_around\": 32, \"segments_along\": 40}\n"
      "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 8], [4, 0, 32]]}\n",
      dir);
  const auto& mesh = r.workspace.find("t")->mesh;
  ASSERT_EQ(mesh.boundary_loops().size(), 3u) << "two ends and the slit";
  const sutura::app::IncisionSpan span = sutura::app::incision_span(mesh, {4, 0, 8}, {4, 0, 32}, 3.0);
  EXPECT_NEAR(span.centreline.front().z(), 5.0, 0.5);
  EXPECT_NEAR(span.centreline.back().z(), 35.0, 0.5);
  for (const Vec3& p : span.centreline) EXPECT_LT(std::hypot(p.x(), p.y()), 1.0) << p.transpose();
}

TEST(IncisionSpan, RefusesWhatItCannotPlace) {
  const auto mesh = tube();
  EXPECT_THROW((void)sutura::app::incision_span(mesh, {4, 0, 10}, {4, 0, 20}, -1.0), std::invalid_argument);
  EXPECT_THROW((void)sutura::app::incision_span(mesh, {4, 0, 10}, {0, 4, 10}, 3.0), std::invalid_argument)
      << "both ends at one height project to one point";
}

// The window's design_patch op parses as a session line and measures along the span.
TEST(IncisionSpan, TheDesignOpParses) {
  const auto mesh = tube();
  sutura::app::DesignTarget t;
  const sutura::app::IncisionSpan span = sutura::app::incision_span(mesh, {4, 0, 25}, {4, 0, 12}, 3.0);
  t.centreline = span.centreline;
  t.max_radius = span.max_radius_mm;
  const nlohmann::json patch = sutura::app::patch_op("t", "ellipse", {4, 0, 25}, {4, 0, 12}, 4.0,
                                                     {{"youngs_modulus", 3.0}, {"thickness", 0.4}});
  const nlohmann::json op = sutura::app::design_patch_op(patch, 3, false, t);
  const sutura::app::Action a = sutura::app::parse_action(op, "s.jsonl", 2);
  const auto& d = std::get<sutura::app::DesignPatchOp>(a.op);
  EXPECT_EQ(d.patch.object, "t");
  EXPECT_EQ(d.measure.centreline.size(), span.centreline.size());
  EXPECT_EQ(d.measure.stations, 20) << "one a mm of the 19 mm span, plus one";
  EXPECT_DOUBLE_EQ(d.measure.max_radius, span.max_radius_mm);
  EXPECT_DOUBLE_EQ(d.target_value, 20.0);
  ASSERT_TRUE(d.max_bulge.has_value());
  EXPECT_DOUBLE_EQ(*d.max_bulge, 1.4);
}

// The window's z-score target parses as the session's {z_score, site, bsa_m2}, to the
// diameter the window shows (the isthmus at z = -1 for BSA 0.2 m^2: 4.54 mm, docs/anatomy.md).
TEST(IncisionSpan, TheDesignOpsZScoreTargetParses) {
  const auto mesh = tube();
  sutura::app::DesignTarget t;
  const sutura::app::IncisionSpan span = sutura::app::incision_span(mesh, {4, 0, 25}, {4, 0, 12}, 3.0);
  t.centreline = span.centreline;
  t.z_score = sutura::app::DesignZScore{-1.0, "isthmus", 0.2};
  const nlohmann::json patch = sutura::app::patch_op("t", "ellipse", {4, 0, 25}, {4, 0, 12}, 4.0,
                                                     {{"youngs_modulus", 3.0}, {"thickness", 0.4}});
  const nlohmann::json op = sutura::app::design_patch_op(patch, 3, false, t);
  const sutura::app::Action a = sutura::app::parse_action(op, "s.jsonl", 2);
  const auto& d = std::get<sutura::app::DesignPatchOp>(a.op);
  ASSERT_TRUE(d.z_score.has_value());
  EXPECT_EQ(d.z_score->site, sutura::engine::ArchSite::Isthmus);
  EXPECT_DOUBLE_EQ(d.z_score->z, -1.0);
  EXPECT_DOUBLE_EQ(d.z_score->bsa_m2, 0.2);
  const double diameter = sutura::app::z_score_diameter_mm(*t.z_score);
  EXPECT_NEAR(diameter, 4.54, 0.005);
  EXPECT_DOUBLE_EQ(d.z_score->diameter_mm, diameter);
  EXPECT_DOUBLE_EQ(d.target_value, 0.25 * M_PI * diameter * diameter);
}

TEST(IncisionSpan, TheWindowsZScoreSitesAreTheSessionsAndBadTargetsAreRefusedInWords) {
  EXPECT_EQ(sutura::app::z_score_sites(),
            (std::vector<std::string>{"transverse_arch", "isthmus", "descending_aorta"}));
  for (const sutura::app::DesignZScore& bad : {sutura::app::DesignZScore{-1.0, "isthmus", 0.05},
                                             sutura::app::DesignZScore{-6.0, "isthmus", 0.2},
                                             sutura::app::DesignZScore{-1.0, "arch", 0.2}}) {
    try {
      (void)sutura::app::z_score_diameter_mm(bad);
      ADD_FAILURE() << "no error for " << bad.site << " z " << bad.z << " BSA " << bad.bsa_m2;
    } catch (const std::runtime_error& e) {
      EXPECT_GT(std::string(e.what()).size(), 10u);
    }
  }
}

}  // namespace
