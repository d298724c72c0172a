// preview_patch (patch_preview.hpp): the patch the op would add, at its true size, on the
// host's surface, and the op's own error when it cannot be added.
#include <gtest/gtest.h>

#include <cmath>

#include "replay_fixture.hpp"
#include "sutura/app/patch_preview.hpp"
#include "sutura/app/session_runner.hpp"
#include "sutura/engine/errors.hpp"

namespace {

using nlohmann::json;
using sutura::app::SessionRunner;

// A tube of radius 4 along z with a 16 mm slit along its side, at x = 4.
const char* kSession = R"({"format": "sutura-session", "version": 3}
{"op": "generate", "object": "t", "shape": "tube", "radius": 4.0, "length": 40.0, "segments_around": 32, "segments_along": 40}
{"op": "incise", "object": "t", "points": [[4, 0, 12], [4, 0, 28]]}
)";

struct Fixture {
  std::filesystem::path dir;
  sutura::app::Session session;
  std::unique_ptr<SessionRunner> runner;
  explicit Fixture(const std::string& name)
      : dir(sutura::testing::scratch_dir("patch_preview", name)),
        session(sutura::app::parse_session(kSession, dir / "s.jsonl")) {
    sutura::app::ReplayOptions o;
    o.out_dir = dir / "out";
    runner = std::make_unique<SessionRunner>(session.file, session.description, o);
    for (const auto& a : session.actions) runner->execute(a);
  }
  sutura::app::Action action(const json& op) const { return sutura::app::parse_action(op, session.file, 9); }
};

json patch(double width, const std::string& shape = "ellipse", double z0 = 12.0) {
  return {{"op", "patch"}, {"object", "t"}, {"start", {4, 0, z0}}, {"end", {4, 0, 28}},
          {"shape", shape},  {"width", width}};
}

TEST(PatchPreview, OutlineIsThePatchAsCutOnTheWallAtItsTrueSize) {
  Fixture f("size");
  const auto& tube = f.runner->workspace().objects()[0];
  const auto action = f.action(patch(3.0));
  const auto p = sutura::app::preview_patch(tube, std::get<sutura::app::PatchOp>(action.op), 1'000'000);
  ASSERT_GE(p.outline.size(), 8u);
  EXPECT_EQ(p.outline.front(), p.outline.back());  // closed
  double z_min = 1e9, z_max = -1e9, y_min = 1e9, y_max = -1e9;
  for (const auto& q : p.outline) {
    // On the wall, not on the rest shape's tangent plane (which lies outside the tube: up to
    // r = 4.28 mm at 1.5 mm from the cut). The wall is polygonal: its vertices are at r <= 4
    // (the remeshed band's on the faces), its faces inside by at most two sagittas of their
    // edges (0.02 mm each).
    const double r = std::hypot(q.x(), q.y());
    EXPECT_LE(r, 4.0 + 1e-9);
    EXPECT_GE(r, 3.95);
    z_min = std::min(z_min, q.z()), z_max = std::max(z_max, q.z());
    y_min = std::min(y_min, q.y()), y_max = std::max(y_max, q.y());
  }
  EXPECT_NEAR(p.length, 16.0, 0.2);
  EXPECT_NEAR(z_max - z_min, 16.0, 0.5);
  // 3 mm across, laid on a wall of radius 4: the chord is 2 * 4 * sin(1.5 / 4) = 2.93 mm.
  EXPECT_NEAR(y_max - y_min, 2.93, 0.15);
  EXPECT_NEAR(0.5 * (y_max + y_min), 0.0, 0.05);
  // An ellipse 3 x 16 mm: pi/4 * 3 * 16 = 37.7 mm2, less what its polygon cuts off.
  EXPECT_NEAR(p.area, 37.7, 1.5);
  // The op adds the patch of that area (its seams matched to the lips afterwards).
  const json done = f.runner->execute(action);
  EXPECT_NEAR(done["patch_area_mm2"].get<double>(), p.area, 0.02 * p.area);
}

TEST(PatchPreview, WiderPatchWiderOutline) {
  Fixture f("wider");
  const auto& tube = f.runner->workspace().objects()[0];
  const auto a = f.action(patch(2.0)), b = f.action(patch(5.0));
  const auto pa = sutura::app::preview_patch(tube, std::get<sutura::app::PatchOp>(a.op), 1'000'000);
  const auto pb = sutura::app::preview_patch(tube, std::get<sutura::app::PatchOp>(b.op), 1'000'000);
  EXPECT_NEAR(pb.area / pa.area, 2.5, 0.15);
}

TEST(PatchPreview, SaysWhyAsTheOpWould) {
  Fixture f("refused");
  const auto& tube = f.runner->workspace().objects()[0];
  // A gusset (triangle) on a slit inside the wall is refused, before and when tried.
  const auto action = f.action(patch(3.0, "triangle"));
  std::string previewed;
  try {
    sutura::app::preview_patch(tube, std::get<sutura::app::PatchOp>(action.op), 1'000'000);
  } catch (const sutura::engine::InvalidArgument& e) {
    previewed = e.what();
  }
  ASSERT_FALSE(previewed.empty());
  try {
    f.runner->execute(action);
    FAIL() << "the op succeeded";
  } catch (const sutura::app::SessionError& e) {
    EXPECT_NE(std::string(e.what()).find(previewed), std::string::npos) << e.what();
  }
}

}  // namespace
