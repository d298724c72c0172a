// The plan (plan.hpp): the steps SessionRunner keeps as actions change the workspace, what
// undo and redo do to them, and each step in words.
#include <gtest/gtest.h>

#include "replay_fixture.hpp"
#include "sutura/app/plan.hpp"
#include "sutura/app/session_runner.hpp"

namespace {

using nlohmann::json;
using sutura::app::describe_action;
using sutura::app::Plan;
using sutura::app::SessionRunner;

// A strip held at one end, loaded, incised; measured and snapshotted in between (not steps).
const char* kSession = R"({"format": "sutura-session", "version": 3}
{"op": "generate", "object": "s", "shape": "strip", "length": 20, "width": 4, "segments_length": 10, "segments_width": 2}
{"op": "fix", "object": "s", "nearest": [[0, 0, 0]], "note": "the clamp"}
{"op": "report", "file": "r.json"}
{"op": "force", "object": "s", "nearest": [[20, 0, 0]], "force": [0, 0, 1e-4]}
{"op": "incise", "object": "s", "points": [[5, 1, 0], [9, 1.3, 0]]}
{"op": "undo"}
{"op": "undo"}
{"op": "redo"}
{"op": "pressure", "object": "s", "pressure": 0.0107}
{"op": "undo"}
)";

// A runner for kSession in its own scratch directory (`undo_megabytes`: the undo history's
// memory limit).
struct Fixture {
  sutura::app::Session session;
  std::unique_ptr<SessionRunner> runner;
  explicit Fixture(const std::string& name, std::size_t undo_megabytes = sutura::app::Limits{}.undo_megabytes) {
    const auto dir = sutura::testing::scratch_dir("plan", name);
    session = sutura::app::parse_session(kSession, dir / "s.jsonl");
    sutura::app::ReplayOptions o;
    o.out_dir = dir / "out";
    o.limits.undo_megabytes = undo_megabytes;
    runner = std::make_unique<SessionRunner>(session.file, session.description, o);
  }
};

struct Replayed {
  std::vector<Plan> after;  // the plan after each action
};

Replayed run_session(const std::string& name) {
  Fixture f(name);
  Replayed r;
  for (const auto& a : f.session.actions) {
    f.runner->execute(a);
    r.after.push_back(f.runner->plan());
  }
  return r;
}

std::vector<std::string> ops(const Plan& p) {
  std::vector<std::string> out;
  for (const auto& s : p.steps) out.push_back(s.op);
  return out;
}

TEST(Plan, StepsAreTheChangingActionsAndUndoRedoMoveTheirEnd) {
  const Replayed r = run_session("steps");
  using V = std::vector<std::string>;
  // generate, fix: two steps; the report is not one.
  EXPECT_EQ(ops(r.after[2]), (V{"generate", "fix"}));
  EXPECT_EQ(r.after[2].applied, 2u);
  EXPECT_EQ(ops(r.after[4]), (V{"generate", "fix", "force", "incise"}));
  EXPECT_EQ(r.after[4].steps[3].line, 6);
  EXPECT_EQ(r.after[4].steps[1].source.value("note", ""), "the clamp");
  // Two undos leave the steps listed, two fewer in effect; a redo brings back the older.
  EXPECT_EQ(r.after[6].applied, 2u);
  EXPECT_EQ(r.after[6].steps.size(), 4u);
  EXPECT_EQ(r.after[7].applied, 3u);
  EXPECT_EQ(r.after[7].steps[2].op, "force");
  // A new step drops the undone incision, as it drops the redo history.
  EXPECT_EQ(ops(r.after[8]), (V{"generate", "fix", "force", "pressure"}));
  EXPECT_EQ(r.after[8].applied, 4u);
  EXPECT_EQ(r.after[8].undoable, 4u);
  EXPECT_EQ(r.after[9].applied, 3u);
  EXPECT_EQ(r.after[9].undoable, 3u);
  // The result is what the report lists for the action.
  EXPECT_TRUE(r.after[4].steps[3].result.contains("seconds"));
  EXPECT_EQ(r.after[4].steps[3].result.value("op", ""), "incise");
}

TEST(Plan, ChangesCountTheActionsThatChangedTheWorkspace) {
  Fixture f("changes");
  std::vector<std::uint64_t> changes;
  for (const auto& a : f.session.actions) {
    f.runner->execute(a);
    changes.push_back(f.runner->changes());
  }
  // generate, fix: 1, 2; the report changes nothing; force, incise: 3, 4; undo, undo, redo:
  // 5, 6, 7; pressure 8; undo 9.
  EXPECT_EQ(changes, (std::vector<std::uint64_t>{1, 2, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(Plan, ARestoredCheckpointTakesTheSteps) {
  Fixture f("checkpoint");
  SessionRunner& runner = *f.runner;
  runner.execute(f.session.actions.at(0));
  const auto checkpoint = runner.checkpoint();
  runner.execute(f.session.actions.at(1));
  ASSERT_EQ(runner.plan().steps.size(), 2u);
  runner.restore(*checkpoint);
  EXPECT_EQ(runner.plan().steps.size(), 1u);
  EXPECT_EQ(runner.plan().applied, 1u);
}

TEST(Plan, UndoableStopsWhereTheUndoHistoryWasDropped) {
  Fixture f("limits", 0);  // nothing the workspace does not share is kept
  for (int i = 0; i < 5; ++i) f.runner->execute(f.session.actions.at(i));
  const Plan p = f.runner->plan();
  EXPECT_EQ(p.applied, 4u);
  EXPECT_LT(p.undoable, p.applied);
}

TEST(Plan, DescribesEachOpInWords) {
  EXPECT_EQ(describe_action(json::parse(R"({"op": "load", "object": "aorta", "file": "../anatomy/coarse/aorta.ply"})")),
            "Open aorta.ply as 'aorta'");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "fix", "object": "aorta", "boundary": "all"})")),
            "Hold every open end of 'aorta'");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "pressure", "object": "aorta", "pressure": 0.0107})")),
            "Pressure of 80 mmHg (0.0107 MPa) on 'aorta'");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "solve", "objects": ["aorta"], "as_before": true})")),
            "Pressurise 'aorta' before surgery (static solve: the pre-operative shape)");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "solve", "objects": ["a", "b", "c"], "load_factor": 0.5})")),
            "Solve 'a', 'b' and 'c' for equilibrium up to load factor 0.5");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "remesh", "object": "aorta", "below_angle": 20, "radius": 0.6})")),
            "Remesh 'aorta' where an angle is below 20 degrees");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "incise", "object": "aorta", "points": [[0,0,0],[1,0,0],[2,0,0]]})")),
            "Incise 'aorta' through 3 points, cut through");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "incise", "object": "a", "points": [[0,0,0],[1,0,0]], "mode": "snap"})")),
            "Incise 'a' through 2 points, snapped to mesh edges");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "patch", "object": "aorta", "shape": "triangle", "width": 4.5})")),
            "Patch into 'aorta': gusset, 4.5 mm wide");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "design_patch", "object": "aorta", "target": {"min_area_mm2": 20}})")),
            "Design a patch for 'aorta': the width that gives a smallest lumen area of 20 mm2");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "design_patch", "object": "a", "target": {"coarctation_index": 0.8}})")),
            "Design a patch for 'a': the width that gives a coarctation index of 0.8");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "export_patch_template", "object": "a", "file": "t.pdf"})")),
            "Cutting template of a patch of 'a'");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "join", "object": "a", "chains": [{"loop": [0,0,0]}, {"loop": [1,0,0]}]})")),
            "End-to-end anastomosis on 'a'");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "join", "object": "a", "chains": [{"from": [0,0,0], "to": [1,0,0]}, {"from": [0,1,0], "to": [1,1,0]}]})")),
            "Suture on 'a'");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "resect", "object": "a", "planes": [{}, {}], "anastomosis": true})")),
            "Resect a segment of 'a' with end-to-end anastomosis");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "simulate", "objects": ["a"], "relax": {"solver": "dynamic"}})")),
            "Relax 'a' to the repaired shape (damped dynamics)");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "simulate", "dt": 0.0010000000474974513, "steps": 60})")),
            "Run dynamics of every object: 60 steps of 0.001 s");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "material", "object": "a", "region": "wall", "youngs_modulus": 1.5, "thickness": 0.6})")),
            "Material of 'a', the wall: E 1.5 MPa, t 0.6 mm");
  EXPECT_EQ(describe_action(json::parse(R"({"op": "generate", "object": "p", "shape": "cylinder_panel"})")),
            "Generate a cylinder panel as 'p'");
  // An op the describer does not know, and one without an object, still read.
  EXPECT_EQ(describe_action(json::parse(R"({"op": "future_op", "object": "a"})")), "future_op on 'a'");
  EXPECT_EQ(describe_action(json::parse(R"({"op": 3})")), "?");
}

// Every op that makes a step names its object.
TEST(Plan, EveryChangingOpNamesItsObject) {
  for (const char* op : {"generate", "load", "material", "fix", "constrain", "force", "line_load", "pressure",
                         "body_force", "solve", "unload", "simulate", "incise", "join", "patch", "resect", "remesh"}) {
    const std::string text = describe_action(json{{"op", op}, {"object", "x"}, {"objects", {"x"}}});
    EXPECT_NE(text.find("'x'"), std::string::npos) << op << ": " << text;
  }
}

}  // namespace
