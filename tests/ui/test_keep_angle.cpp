// The window's keep-angle step (ui/src/keep_angle.hpp) without a window: it starts only where
// a held object has an angle below the limit, and a failed or cancelled step is undone whole,
// recorded, back to the shape the user's run left.
#include <gtest/gtest.h>

#include <stdexcept>

#include "../../ui/src/keep_angle.hpp"
#include "controller_fixture.hpp"
#include "sutura/app/element_check.hpp"
#include "sutura/app/op_builders.hpp"
#include "sutura/app/replay.hpp"
#include "sutura/app/report.hpp"

namespace fs = std::filesystem;
using namespace sutura;
using nlohmann::json;

namespace {

// The controller's fixture with the window's state on it.
struct Fixture : sutura::testing::ControllerFixture {
  std::unique_ptr<ui::GuiState> state;
  explicit Fixture(const std::string& name)
      : ControllerFixture("keep_" + name), state(std::make_unique<ui::GuiState>(*controller)) {}
};

// A strip of long thin triangles (5 mm by 0.05 mm: angles of about half a degree), and its
// root held: what a run might leave.
const json kThinStrip = {{"op", "generate"}, {"object", "a"}, {"shape", "strip"}, {"length", 10.0},
                         {"width", 2.0}, {"segments_length", 2}, {"segments_width", 40}};
const json kHoldRoot = {{"op", "constrain"}, {"object", "a"},
                        {"box", {{"min", {-0.1, -6, -1}}, {"max", {0.1, 6, 1}}}}};

std::string hash(const app::Workspace& w) { return app::position_hash(w.objects().front().mesh); }

// The thin strip, its root held, in the window's Simulate stage, as a run leaves it: the
// strip's hash and the plan's applied steps then.
struct AfterRun : Fixture {
  std::string before;
  std::size_t applied = 0;
  explicit AfterRun(const std::string& name) : Fixture(name) {
    if (!controller->run(kThinStrip).ok || !controller->run(kHoldRoot).ok) throw std::runtime_error("setup failed");
    state->stages.mesh_loaded();
    state->stages.simulation_started();
    before = hash(controller->workspace());
    applied = controller->plan().applied;
  }
};

}  // namespace

// take_back_keep_angle as finish_worker calls it when a run of the step fails or is cancelled.
TEST(KeepAngle, AFailedSettleIsUndoneWholeAndRecorded) {
  AfterRun f("undo");
  ui::GuiState& s = *f.state;
  const std::string before = f.before;
  const std::size_t applied = f.applied;
  ASSERT_LT(app::smallest_angles(f.controller->workspace()).front().degrees, 1.0);

  ui::ActionOutcome run;  // the user's run, as finish_worker passes it
  run.op = "simulate";
  run.ok = true;
  run.details = {{"seconds", 1.5}, {"warning", "the relaxed shape is not a stable equilibrium (test)"}};
  ASSERT_TRUE(ui::start_keep_angle(s, run));
  EXPECT_TRUE(s.keeping_angle);
  EXPECT_EQ(s.keep_angle_objects, std::vector<std::string>{"a"});
  ASSERT_EQ(s.queued_runs.size(), 1u);  // the settle, after this remesh
  EXPECT_EQ(s.queued_runs.front()["op"], "solve");
  // The run's own warning is shown before the step's message.
  ASSERT_GE(s.messages.size(), 2u);
  EXPECT_TRUE(s.messages[s.messages.size() - 2].error);
  EXPECT_NE(s.messages[s.messages.size() - 2].text.find("(test)"), std::string::npos);
  EXPECT_NE(s.messages.back().text.find("remeshing there and settling again"), std::string::npos);

  const auto remeshed = f.wait();
  ASSERT_TRUE(remeshed && remeshed->ok) << (remeshed ? remeshed->message : "timeout");
  EXPECT_EQ(f.controller->plan().applied, applied + 1);
  EXPECT_NE(hash(f.controller->workspace()), before);

  // Say the settle failed: everything the step did is taken back, as undo lines.
  ui::take_back_keep_angle(s, "solve after the remesh failed (test)");
  EXPECT_FALSE(s.keeping_angle);
  EXPECT_TRUE(s.queued_runs.empty());
  EXPECT_EQ(f.controller->plan().applied, applied);
  EXPECT_EQ(hash(f.controller->workspace()), before);
  EXPECT_EQ(s.stages.stage(), ui::Stage::Inspect);
  ASSERT_FALSE(s.messages.empty());
  EXPECT_TRUE(s.messages.back().error);
  EXPECT_NE(s.messages.back().text.find("taken back"), std::string::npos) << s.messages.back().text;
  // The recording replays to the same shape (generate, fix, remesh, undo).
  app::ReplayOptions o;
  o.out_dir = f.dir / "replayed";
  EXPECT_EQ(hash(app::replay(app::load_session(f.dir / "rec.jsonl"), o).workspace), before);
}

// retry_keep_angle_wider as finish_worker calls it when a run of the step fails: the step is
// undone and tried once more within kWiderKeepAngleRadius times the radius; a second failure
// takes it back for good.
TEST(KeepAngle, AFailedSettleIsTriedOnceMoreWithAWiderRegion) {
  AfterRun f("retry");
  ui::GuiState& s = *f.state;
  const std::string before = f.before;
  const std::size_t applied = f.applied;
  const double first = app::as_typed(s.remesh.small_angle_radius);

  ui::ActionOutcome run;
  run.op = "simulate";
  run.ok = true;
  ASSERT_TRUE(ui::start_keep_angle(s, run));
  EXPECT_EQ(s.keep_angle_radius, first);
  EXPECT_FALSE(s.keep_angle_widened);
  auto done = f.wait();
  ASSERT_TRUE(done && done->ok) << (done ? done->message : "timeout");

  ui::ActionOutcome failed;  // say the settle failed
  failed.op = "solve";
  failed.message = "no convergence (test)";
  ASSERT_TRUE(ui::retry_keep_angle_wider(s, failed));
  EXPECT_TRUE(s.keeping_angle);
  EXPECT_DOUBLE_EQ(s.keep_angle_radius, ui::kWiderKeepAngleRadius * first);
  EXPECT_TRUE(s.keep_angle_widened);
  ASSERT_EQ(s.queued_runs.size(), 1u);
  EXPECT_EQ(s.queued_runs.front()["op"], "solve");
  EXPECT_NE(s.messages.back().text.find("failed at its solve (no convergence (test))"), std::string::npos)
      << s.messages.back().text;
  EXPECT_NE(s.messages.back().text.find("instead and settling again"), std::string::npos) << s.messages.back().text;
  done = f.wait();
  ASSERT_TRUE(done && done->ok) << (done ? done->message : "timeout");
  // In effect: the user's steps and the wider remesh (the first remesh is undone, not redone).
  const app::Plan& plan = f.controller->plan();
  ASSERT_EQ(plan.applied, applied + 1);
  const nlohmann::json& remesh = plan.steps[plan.applied - 1].source;
  EXPECT_EQ(remesh["op"], "remesh");
  EXPECT_EQ(remesh["radius"].get<double>(), 0.9);  // 1.5 x 0.6, rounded as typed
  EXPECT_NE(hash(f.controller->workspace()), before);

  // The second attempt's settle fails too: taken back for good, no third attempt.
  EXPECT_FALSE(ui::retry_keep_angle_wider(s, failed));
  EXPECT_FALSE(s.keeping_angle);
  EXPECT_FALSE(f.controller->busy());
  EXPECT_TRUE(s.queued_runs.empty());
  EXPECT_EQ(f.controller->plan().applied, applied);
  EXPECT_EQ(hash(f.controller->workspace()), before);
  EXPECT_EQ(s.stages.stage(), ui::Stage::Inspect);
  EXPECT_TRUE(s.messages.back().error);
  EXPECT_NE(s.messages.back().text.find("taken back"), std::string::npos) << s.messages.back().text;
  // The recording (generate, fix, remesh, undo, remesh, undo) replays to the run's shape.
  app::ReplayOptions o;
  o.out_dir = f.dir / "replayed";
  EXPECT_EQ(hash(app::replay(app::load_session(f.dir / "rec.jsonl"), o).workspace), before);
}

TEST(KeepAngle, NothingStartsForAnObjectThatIsNotHeldNorAboveTheLimit) {
  Fixture f("none");
  ASSERT_TRUE(f.controller->run(kThinStrip).ok);
  ui::GuiState& s = *f.state;
  ui::ActionOutcome run;
  run.op = "simulate";
  run.ok = true;
  EXPECT_FALSE(ui::start_keep_angle(s, run));  // not held: left as it is
  EXPECT_FALSE(s.keeping_angle);
  EXPECT_FALSE(f.controller->busy());
  ASSERT_TRUE(f.controller->run(kHoldRoot).ok);
  s.remesh.below_angle = 0.1f;  // below every angle
  EXPECT_FALSE(ui::start_keep_angle(s, run));
  for (const auto& m : s.messages) EXPECT_FALSE(m.error) << m.text;  // nothing failed either
  // The warning after the step is about the objects it remeshed only.
  s.keep_angle_objects = {"a"};
  EXPECT_FALSE(ui::still_below_warning(s));
  s.remesh.below_angle = 20.0f;
  s.keep_angle_objects = {"other"};
  EXPECT_FALSE(ui::still_below_warning(s));
  s.keep_angle_objects = {"a"};
  const auto warning = ui::still_below_warning(s);
  ASSERT_TRUE(warning);
  EXPECT_NE(warning->find("'a' still has an angle of 0"), std::string::npos) << *warning;
}
