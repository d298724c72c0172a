// Limits (issue 27, ../shared/robustness/hang_*): work beyond them is refused before the
// session runs or after the op that crosses them, naming line, field, amount, limit and flag;
// the undo history stays within its memory; a time limit stops a run cleanly.
#include "sutura/app/limits.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "sutura/app/replay.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sutura::app;

const std::string kHeader = "{\"format\": \"sutura-session\", \"version\": 3}\n";

std::string tube(const std::string& name, int around, int along) {
  return "{\"op\": \"generate\", \"object\": \"" + name + "\", \"shape\": \"tube\", \"radius\": 4, \"length\": 30, "
         "\"segments_around\": " + std::to_string(around) + ", \"segments_along\": " + std::to_string(along) + "}\n";
}

fs::path scratch(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("sutura_limits_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

ReplayResult run(const std::string& text, const std::string& name, const ReplayOptions& base = {}) {
  const fs::path dir = scratch(name);
  ReplayOptions o = base;
  o.out_dir = dir / "out";
  return replay(parse_session(text, dir / "s.jsonl"), o);
}

// The error of a session refused at `line`, with report.json written as failed.
std::string refusal(const std::string& text, int line, const std::string& field, const ReplayOptions& base = {}) {
  const fs::path dir = scratch("refused");
  ReplayOptions o = base;
  o.out_dir = dir / "out";
  try {
    replay(parse_session(text, dir / "s.jsonl"), o);
  } catch (const SessionError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    std::ifstream in(o.out_dir / "report.json");
    std::stringstream report;
    report << in.rdbuf();
    EXPECT_NE(report.str().find("\"status\": \"failed\""), std::string::npos);
    return e.what();
  }
  ADD_FAILURE() << "not refused";
  return {};
}

TEST(Limits, WorkBeyondThemIsRefusedBeforeAnyOpRuns) {
  // A tube at the generators' ceiling, 20 million faces (hang_tube_10M_faces).
  std::string e = refusal(kHeader + tube("t", 3162, 3162), 2, "segments");
  EXPECT_NE(e.find("a generated mesh of 19,996,488 faces exceeds the limit of 1,000,000 (--max-faces raises it)"),
            std::string::npos) << e;
  // 10^7 dynamics steps (hang_simulate_1e7_steps): refused before the tube is even made.
  e = refusal(kHeader + tube("t", 16, 12) + "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n" +
                  "{\"op\": \"simulate\", \"steps\": 10000000}\n",
              4, "steps");
  EXPECT_NE(e.find("a run of 10,000,000 steps exceeds the limit of 100,000 (--max-steps"), std::string::npos) << e;
  // A patch cut at 3 um (hang_patch_edge_length_0.003).
  e = refusal(kHeader + tube("t", 24, 20) + "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 10], [4, 0, 20]]}\n" +
                  "{\"op\": \"patch\", \"object\": \"t\", \"start\": [4, 0, 10], \"end\": [4, 0, 20], \"width\": 4, "
                  "\"edge_length\": 0.003}\n",
              4, "edge_length");
  EXPECT_NE(e.find("a patch of about 10,266,667 faces"), std::string::npos) << e;
  // The 101st object (hang_2000_objects).
  std::string many = kHeader;
  for (int i = 0; i < 101; ++i) {
    std::string name = "o";
    name += std::to_string(i);  // not "o" + ...: GCC 12's -Wrestrict false positive
    many += tube(name, 3, 1);
  }
  e = refusal(many, 102, "object");
  EXPECT_NE(e.find("101 objects exceeds the limit of 100 (--max-objects"), std::string::npos) << e;
  // Raised, the same work runs.
  ReplayOptions raised;
  raised.limits.objects = 101;
  EXPECT_EQ(run(many, "many", raised).report["status"], "ok");
}

TEST(Limits, FacesAreCheckedAfterEveryOp) {
  ReplayOptions small;
  small.limits.faces_per_object = 1000;
  small.limits.faces_in_all = 1500;
  // 960 faces each: the first is within both limits, the second crosses the sum.
  std::string e = refusal(kHeader + tube("a", 24, 20) + tube("b", 24, 20), 3, "", small);
  EXPECT_NE(e.find("the objects have 1920 faces in all, more than the limit of 1500 (--max-faces-in-all"),
            std::string::npos) << e;
  // A patch grows its object past the per-object limit.
  e = refusal(kHeader + tube("t", 24, 20) + "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 10], [4, 0, 20]]}\n" +
                  "{\"op\": \"patch\", \"object\": \"t\", \"start\": [4, 0, 10], \"end\": [4, 0, 20], \"width\": 4}\n",
              4, "", small);
  EXPECT_NE(e.find("object 't' has "), std::string::npos) << e;
  EXPECT_NE(e.find("faces, more than the limit of 1000 per object (--max-faces"), std::string::npos) << e;
}

TEST(Limits, TheUndoHistoryStaysWithinItsMemory) {
  const std::string edits = kHeader + tube("t", 24, 20) +
                            "{\"op\": \"material\", \"object\": \"t\", \"thickness\": 0.5}\n"
                            "{\"op\": \"material\", \"object\": \"t\", \"thickness\": 0.6}\n";
  // Room for everything: two undos go back to the generated tube's material.
  EXPECT_EQ(run(edits + "{\"op\": \"undo\"}\n{\"op\": \"undo\"}\n", "undo_ok").report["status"], "ok");
  // No room: nothing is kept, and undo says why.
  ReplayOptions none;
  none.limits.undo_megabytes = 0;
  const std::string e = refusal(edits + "{\"op\": \"undo\"}\n", 5, "", none);
  EXPECT_NE(e.find("nothing more to undo: the history keeps at most 64 states and 0 MiB (--max-undo-mb"),
            std::string::npos) << e;
  // Room for one tube's state (about 0.6 MB): the second undo finds the oldest dropped.
  ReplayOptions one;
  one.limits.undo_megabytes = 1;
  const std::string e2 = refusal(edits + "{\"op\": \"undo\"}\n{\"op\": \"undo\"}\n", 6, "", one);
  EXPECT_NE(e2.find("nothing more to undo"), std::string::npos) << e2;
  EXPECT_LT(object_bytes(run(kHeader + tube("t", 24, 20), "bytes").workspace.objects().front()),
            std::size_t(1) << 20);
}

// The history shares what did not change: 30 tubes generated one by one cost it nothing, where
// whole copies would have held 435 tubes (about 260 MB).
TEST(Limits, TheUndoHistoryHoldsOnlyWhatChanged) {
  std::string s = kHeader;
  for (int i = 0; i < 30; ++i) {
    std::string name = "t";  // not "t" + std::to_string(i): GCC 12 warns falsely (-Wrestrict)
    name += std::to_string(i);
    s += tube(name, 24, 20);
  }
  s += "{\"op\": \"material\", \"object\": \"t3\", \"thickness\": 0.5}\n";
  for (int i = 0; i < 31; ++i) s += "{\"op\": \"undo\"}\n";
  for (int i = 0; i < 31; ++i) s += "{\"op\": \"redo\"}\n";
  ReplayOptions one;
  one.limits.undo_megabytes = 1;  // one changed tube (0.6 MB) fits, two do not
  const ReplayResult r = run(s, "shared", one);
  ASSERT_EQ(r.report["status"], "ok") << r.report.dump();
  ASSERT_EQ(r.workspace.objects().size(), 30u);
  EXPECT_EQ(r.workspace.find("t3")->sim.materials.front().thickness, 0.5);
  EXPECT_EQ(r.workspace.find("t4")->sim.materials.front().thickness, sutura::engine::ShellMaterial{}.thickness);
}

TEST(Limits, ATimeLimitStopsARunCleanlyWithItsReport) {
  ReplayOptions limited;
  limited.time_limit = 0.5;
  const auto t0 = std::chrono::steady_clock::now();
  const ReplayResult r = run(kHeader + tube("t", 32, 40) + "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n" +
                                 "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n" +
                                 "{\"op\": \"simulate\", \"steps\": 100000}\n" +
                                 "{\"op\": \"export\", \"object\": \"t\", \"file\": \"t.ply\"}\n",
                             "time", limited);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.report["status"], "stopped");
  EXPECT_NE(r.report["error"].get<std::string>().find("the time limit of 0.5 s was reached (--time-limit)"),
            std::string::npos) << r.report["error"];
  EXPECT_NE(r.report["error"].get<std::string>().find(":5: op 'simulate'"), std::string::npos) << r.report["error"];
  EXPECT_LT(seconds, 10.0);  // 100,000 steps take minutes; the stop comes within a step
  EXPECT_EQ(r.report["actions"].size(), 3u);  // generate, fix, pressure; not the export
}

}  // namespace
