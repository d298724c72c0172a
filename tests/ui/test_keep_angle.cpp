// The window's keep-angle step (ui/src/keep_angle.hpp) without a window: it starts only where
// a held object has an angle below the limit, and a failed or cancelled step is undone whole,
// recorded, back to the shape the user's run left.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <unistd.h>

#include "../../ui/src/keep_angle.hpp"
#include "sutura/app/element_check.hpp"
#include "sutura/app/replay.hpp"
#include "sutura/app/report.hpp"

namespace fs = std::filesystem;
using namespace sutura;
using nlohmann::json;

namespace {

struct Fixture {
  fs::path dir;
  std::unique_ptr<ui::SessionController> controller;
  std::unique_ptr<ui::GuiState> state;
  explicit Fixture(const std::string& name) {
    dir = fs::temp_directory_path() / ("sutura_keep_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    app::ReplayOptions o;
    o.out_dir = dir / "out";
    controller = std::make_unique<ui::SessionController>(ui::SessionRecorder::create(dir / "rec.jsonl", "test"), o);
    state = std::make_unique<ui::GuiState>(*controller);
  }
  ~Fixture() { fs::remove_all(dir); }
  // Waits for the running op, up to a minute.
  std::optional<ui::ActionOutcome> wait() {
    std::optional<ui::ActionOutcome> outcome;
    for (int i = 0; i < 12000 && !outcome; ++i) {
      outcome = controller->poll();
      if (!outcome) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return outcome;
  }
};

// A strip of long thin triangles (5 mm by 0.05 mm: angles of about half a degree), and its
// root held: what a run might leave.
const json kThinStrip = {{"op", "generate"}, {"object", "a"}, {"shape", "strip"}, {"length", 10.0},
                         {"width", 2.0}, {"segments_length", 2}, {"segments_width", 40}};
const json kHoldRoot = {{"op", "constrain"}, {"object", "a"},
                        {"box", {{"min", {-0.1, -6, -1}}, {"max", {0.1, 6, 1}}}}};

std::string hash(const app::Workspace& w) { return app::position_hash(w.objects().front().mesh); }

}  // namespace

TEST(KeepAngle, AFailedSettleIsUndoneWholeAndRecorded) {
  Fixture f("undo");
  ASSERT_TRUE(f.controller->run(kThinStrip).ok);
  ASSERT_TRUE(f.controller->run(kHoldRoot).ok);
  ui::GuiState& s = *f.state;
  s.stages.mesh_loaded();
  s.stages.simulation_started();
  const std::string before = hash(f.controller->workspace());
  const std::size_t applied = f.controller->plan().applied;
  ASSERT_LT(app::smallest_angles(f.controller->workspace()).front().degrees, 1.0);

  ui::ActionOutcome run;  // the user's run, as finish_worker passes it
  run.op = "simulate";
  run.ok = true;
  run.details = {{"seconds", 1.5}, {"warning", "the relaxed shape is not a stable equilibrium (test)"}};
  ASSERT_TRUE(ui::start_keep_angle(s, run));
  EXPECT_TRUE(s.keeping_angle);
  ASSERT_EQ(s.queued_runs.size(), 1u);  // the settle, after this remesh
  EXPECT_EQ(s.queued_runs.front()["op"], "solve");
  // The run's own warning is shown before the remesh's messages.
  bool warned = false;
  for (const auto& m : s.messages) warned = warned || (m.error && m.text.find("(test)") != std::string::npos);
  EXPECT_TRUE(warned);

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
  EXPECT_FALSE(ui::still_below_warning(s));
  s.remesh.below_angle = 20.0f;
  const auto warning = ui::still_below_warning(s);
  ASSERT_TRUE(warning);
  EXPECT_NE(warning->find("'a' still has an angle of 0"), std::string::npos) << *warning;
}
