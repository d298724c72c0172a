// The GUI's action path: record, then run with the replay executor; failures and
// cancellations are taken back; the recorded file replays to the same geometry; long ops run
// on a worker thread with progress and cancel.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>
#include <unistd.h>

#include "controller_fixture.hpp"
#include "sutura/app/replay.hpp"
#include "sutura/app/report.hpp"
#include "sutura/ui/session_controller.hpp"

namespace fs = std::filesystem;
using namespace sutura;
using nlohmann::json;

namespace {

using Fixture = sutura::testing::ControllerFixture;

const json kStrip = {{"op", "generate"}, {"object", "a"}, {"shape", "strip"},
                     {"segments_length", 20}, {"segments_width", 4}};
const json kFixEnd = {{"op", "constrain"}, {"object", "a"},
                      {"box", {{"min", {-0.1, -6, -1}}, {"max", {0.1, 6, 1}}}}};
const json kGravity = {{"op", "body_force"}, {"object", "a"}, {"acceleration", {0, 0, -9810}}};

std::string hash(const app::Workspace& w) { return app::position_hash(w.objects().front().mesh); }

}  // namespace

TEST(SessionController, RecordedActionsReplayToTheSameGeometry) {
  Fixture f("replay");
  ASSERT_TRUE(f.controller->run(kStrip).ok);
  ASSERT_TRUE(f.controller->run(kFixEnd).ok);
  ASSERT_TRUE(f.controller->run(kGravity).ok);
  const auto r = f.controller->run({{"op", "simulate"}, {"steps", 5}, {"dt", 1e-3}});
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.details["op"], "simulate");
  app::ReplayOptions o;
  o.out_dir = f.dir / "replayed";
  const auto replayed = app::replay(app::load_session(f.dir / "rec.jsonl"), o);
  EXPECT_EQ(hash(replayed.workspace), hash(f.controller->workspace()));
}

TEST(SessionController, BadOpsAreNotRecordedAndFailuresAreTakenBack) {
  Fixture f("fail");
  ASSERT_TRUE(f.controller->run(kStrip).ok);
  const int lines = f.controller->recorder().lines();
  const auto parse_error = f.controller->run({{"op", "generate"}, {"object", "b"}, {"shape", "cube"}});
  EXPECT_FALSE(parse_error.ok);
  EXPECT_NE(parse_error.message.find("shape"), std::string::npos);
  EXPECT_EQ(f.controller->recorder().lines(), lines);
  // Parses, fails when run (no such object): the line is removed again, state unchanged.
  const auto run_error = f.controller->run({{"op", "pressure"}, {"object", "zz"}, {"pressure", 0.01}});
  EXPECT_FALSE(run_error.ok);
  EXPECT_NE(run_error.message.find("no object named 'zz'"), std::string::npos);
  EXPECT_EQ(f.controller->recorder().lines(), lines);
  EXPECT_EQ(f.controller->workspace().objects().size(), 1u);
  app::ReplayOptions o;
  o.out_dir = f.dir / "replayed";
  EXPECT_NO_THROW(app::replay(app::load_session(f.dir / "rec.jsonl"), o));
}

TEST(SessionController, WorkerReportsProgressAndCancelRestoresThePreRunState) {
  Fixture f("cancel");
  ASSERT_TRUE(f.controller->run(kStrip).ok);
  ASSERT_TRUE(f.controller->run(kFixEnd).ok);
  ASSERT_TRUE(f.controller->run(kGravity).ok);
  const std::string before = hash(f.controller->workspace());
  const int lines = f.controller->recorder().lines();
  std::string why;
  ASSERT_TRUE(f.controller->start({{"op", "simulate"}, {"steps", 100000}, {"dt", 1e-3}}, why)) << why;
  EXPECT_TRUE(f.controller->busy());
  EXPECT_EQ(f.controller->recorder().lines(), lines + 1);  // recorded before it runs
  // Wait for live positions, pause, check that steps stop advancing, then cancel.
  for (int i = 0; i < 2000 && f.controller->progress().step < 3; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const auto running = f.controller->progress();
  ASSERT_GE(running.step, 3);
  ASSERT_EQ(running.positions.size(), 1u);
  EXPECT_EQ(running.positions[0].first, "a");
  f.controller->set_paused(true);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const int paused_at = f.controller->progress().step;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(f.controller->progress().step, paused_at);
  f.controller->cancel();
  std::optional<ui::ActionOutcome> outcome;
  for (int i = 0; i < 2000 && !outcome; ++i) {
    outcome = f.controller->poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(outcome);
  EXPECT_FALSE(outcome->ok);
  EXPECT_TRUE(outcome->cancelled);
  EXPECT_FALSE(f.controller->busy());
  EXPECT_EQ(hash(f.controller->workspace()), before);
  EXPECT_EQ(f.controller->recorder().lines(), lines);
}

// The GUI's --threads: a long op on the worker thread runs with the chosen count (OpenMP's
// count is per thread, so it is set where each op runs), the report records it, and the result
// is the one `sutura replay` gets with the same count.
TEST(SessionController, TheWorkerRunsWithTheChosenThreadCount) {
  Fixture f("threads", 1);
  ASSERT_TRUE(f.controller->run(kStrip).ok);
  ASSERT_TRUE(f.controller->run(kFixEnd).ok);
  ASSERT_TRUE(f.controller->run(kGravity).ok);
  std::string why;
  ASSERT_TRUE(f.controller->start({{"op", "solve"}}, why)) << why;
  std::optional<ui::ActionOutcome> outcome;
  for (int i = 0; i < 4000 && !outcome; ++i) {
    outcome = f.controller->poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(outcome);
  ASSERT_TRUE(outcome->ok) << outcome->message;
  f.controller->write_report();
  const json report = json::parse(std::ifstream(f.dir / "out" / "report.json"));
  EXPECT_EQ(report.at("threads").at("openmp"), 1);
  app::ReplayOptions o;
  o.out_dir = f.dir / "replayed";
  o.threads = 1;
  const app::ReplayResult r = app::replay(app::load_session(f.dir / "rec.jsonl"), o);
  EXPECT_EQ(hash(r.workspace), hash(f.controller->workspace()));
}
