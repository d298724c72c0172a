// design_patch: a patch's width chosen so that the repaired lumen meets a target, on the
// bundled coarse arch (the default session's plan: 80 mmHg, incision across the coarctation).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "replay_fixture.hpp"
#include "sutura/app/design_candidates.hpp"
#include "sutura/app/session.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sutura::app;
using nlohmann::json;

// The default session up to its patch (load, material, fix, pressure, solve, incise), its
// patch, relaxation and lumen measure as design_patch's parts.
struct Plan {
  std::string prefix;
  json patch, simulate, measure;
};

const Plan& plan() {
  static const Plan p = [] {
    Plan out;
    std::ifstream in(fs::path(SUTURA_SOURCE_DIR) / "assets/sessions/default.jsonl");
    std::string line;
    while (std::getline(in, line)) {
      json j = json::parse(line);
      if (j.contains("file") && j.value("op", "") == "load")
        j["file"] = (fs::path(SUTURA_SOURCE_DIR) / "assets/sessions" / j["file"].get<std::string>()).string();
      const std::string op = j.value("op", "");
      j.erase("note");
      if (op == "patch") {
        out.patch = j;
        break;
      }
      if (op != "measure") out.prefix += j.dump() + "\n";
    }
    while (std::getline(in, line)) {
      json j = json::parse(line);
      j.erase("note");
      if (j.value("op", "") == "simulate" && out.simulate.is_null()) out.simulate = j;
      if (j.value("op", "") == "measure" && out.measure.is_null()) out.measure = j;
    }
    return out;
  }();
  return p;
}

json without(json j, const std::vector<std::string>& keys) {
  for (const auto& k : keys) j.erase(k);
  return j;
}

std::string design(const json& target, const json& range, const json& extra = json::object()) {
  json op = {{"op", "design_patch"},
             {"object", "aorta"},
             {"patch", without(plan().patch, {"op", "object", "width"})},
             {"simulate", without(plan().simulate, {"op"})},
             {"measure", without(plan().measure, {"op", "object"})},
             {"width_range", range},
             {"target", target}};
  op.update(extra);
  return plan().prefix + op.dump() + "\n";
}

std::string hash(const ReplayResult& r) { return r.report["objects"]["aorta"]["position_hash"]; }

const json& design_action(const ReplayResult& r) {
  for (const json& a : r.report["actions"])
    if (a["op"] == "design_patch") return a;
  throw std::runtime_error("no design_patch in the report");
}

// 20 mm^2 (the default session's 4 mm patch gives 17.8): met within 5 % in at most 8
// relaxations; a plain replay of patch + simulate + measure at the chosen width ends in the
// same shape, bit for bit, and measures the same lumen.
TEST(DesignPatch, MeetsAMinimumAreaAndEqualsAPlainReplayOfItsWidth) {
  ASSERT_FALSE(plan().patch.is_null());
  const ReplayResult r = sutura::testing::replay_text(design({{"min_area_mm2", 20.0}}, {2, 8}),
                                                     sutura::testing::scratch_dir("design", "met"));
  const json& d = design_action(r);
  EXPECT_EQ(d["status"], "met") << d.dump(1);
  // The chosen candidate's run, as its simulate reports it: relaxed to s = 1, stable.
  EXPECT_EQ(d["s_reached"].get<double>(), 1.0);
  EXPECT_TRUE(d["equilibrium"]["stable"].get<bool>()) << d["equilibrium"].dump();
  EXPECT_FALSE(d.contains("warning"));
  EXPECT_LE(d["relaxations"].get<int>(), 8);
  EXPECT_EQ(d["candidates"].size(), d["relaxations"].get<std::size_t>());
  const double width = d["width_mm"].get<double>();
  EXPECT_GT(width, 4.0);
  EXPECT_LT(width, 8.0);
  const double area = r.report["measurements"]["lumen"]["after"]["min_area_mm2"].get<double>();
  EXPECT_GE(area, 20.0);
  EXPECT_LE(area, 21.0);
  // The area grows with the width over the candidates (the search's assumption).
  for (const json& a : d["candidates"])
    for (const json& b : d["candidates"])
      if (a["width_mm"].get<double>() < b["width_mm"].get<double>()) {
        EXPECT_LT(a["min_area_mm2"].get<double>(), b["min_area_mm2"].get<double>());
      }

  json patch = plan().patch;
  patch["width"] = width;
  const std::string plain = plan().prefix + patch.dump() + "\n" + plan().simulate.dump() + "\n" +
                            plan().measure.dump() + "\n";
  const ReplayResult p = sutura::testing::replay_text(plain, sutura::testing::scratch_dir("design", "plain"));
  EXPECT_EQ(hash(r), hash(p));
  EXPECT_EQ(p.report["measurements"]["lumen"]["after"]["min_area_mm2"].get<double>(), area);

  // One undo takes the whole design back: the incised aorta as before it.
  const ReplayResult u = sutura::testing::replay_text(design({{"min_area_mm2", 20.0}}, {2, 8}) + "{\"op\": \"undo\"}\n",
                                                     sutura::testing::scratch_dir("design", "undo"));
  const ReplayResult incised = sutura::testing::replay_text(plan().prefix, sutura::testing::scratch_dir("design", "incised"));
  EXPECT_EQ(hash(u), hash(incised));
}

// Out of reach within the range: "infeasible", the widest candidate left, two relaxations.
TEST(DesignPatch, ReportsAnInfeasibleTargetWithTheBestCandidate) {
  const ReplayResult r = sutura::testing::replay_text(design({{"min_area_mm2", 60.0}}, {2, 4}),
                                                     sutura::testing::scratch_dir("design", "infeasible"));
  const json& d = design_action(r);
  EXPECT_EQ(d["status"], "infeasible");
  EXPECT_EQ(d["width_mm"].get<double>(), 4.0);
  EXPECT_EQ(d["relaxations"].get<int>(), 2);
  EXPECT_NE(d["reason"].get<std::string>().find("widest patch"), std::string::npos);
  // A bulge limit no patch can keep: the band is reached, the limit is not.
  const ReplayResult b = sutura::testing::replay_text(
      design({{"min_area_mm2", 20.0}}, {2, 8}, {{"max_bulge", 1.0}}), sutura::testing::scratch_dir("design", "bulge"));
  EXPECT_EQ(design_action(b)["status"], "infeasible");
  EXPECT_NE(design_action(b)["reason"].get<std::string>().find("bulge"), std::string::npos);
}

// The candidates written for a job array replay to what design_patch measured for the same
// widths (both ends of the range are always its first two candidates), bit for bit.
TEST(DesignPatch, EmittedCandidatesReplayToTheOpsOwnCandidates) {
  const fs::path dir = sutura::testing::scratch_dir("design", "emit");
  const std::string text = design({{"min_area_mm2", 60.0}}, {2, 4});
  const ReplayResult r = sutura::testing::replay_text(text, dir);
  const json& d = design_action(r);
  ASSERT_EQ(d["candidates"].size(), 2u);
  const Session session = parse_session(text, dir / "plan.jsonl");
  const auto written = emit_design_candidates(session, dir / "candidates", 2);
  ASSERT_EQ(written.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(written[k].width, d["candidates"][k]["width_mm"].get<double>());
    ReplayOptions o;
    o.out_dir = dir / ("out" + std::to_string(k));
    const ReplayResult c = replay(load_session(written[k].file), o);
    EXPECT_EQ(c.report["measurements"]["lumen"]["after"]["min_area_mm2"].get<double>(),
              d["candidates"][k]["min_area_mm2"].get<double>());
  }
  EXPECT_TRUE(fs::exists(dir / "candidates" / "plan_candidates.json"));
  // The widest is width_max exactly (0.5 + 2.8 * 3 / 3 is not), and an empty objects list
  // means the object, as design_patch reads it.
  json simulate = without(plan().simulate, {"op"});
  simulate["objects"] = json::array();
  const auto grid = emit_design_candidates(
      parse_session(design({{"min_area_mm2", 20.0}}, {0.5, 3.3}, {{"simulate", simulate}}), dir / "grid.jsonl"),
      dir / "grid", 4);
  ASSERT_EQ(grid.size(), 4u);
  EXPECT_EQ(grid.front().width, 0.5);
  EXPECT_EQ(grid.back().width, 3.3);
  std::ifstream in(grid.back().file);
  const std::string last((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(last.find("\"objects\":[\"aorta\"]"), std::string::npos);
  // Never over existing files; a session without the op has no candidates.
  EXPECT_THROW((void)emit_design_candidates(session, dir / "candidates", 2), std::invalid_argument);
  EXPECT_THROW((void)emit_design_candidates(parse_session(plan().prefix, dir / "p.jsonl"), dir / "none", 2),
               std::invalid_argument);
}

// The narrowest patch already meets the target: one relaxation. Too few relaxations for the
// band: the narrowest candidate that meets the target, said so.
TEST(DesignPatch, TheNarrowestThatMeetsAndTheBandNotReached) {
  const ReplayResult r = sutura::testing::replay_text(design({{"min_area_mm2", 5.0}}, {2, 8}),
                                                     sutura::testing::scratch_dir("design", "narrowest"));
  EXPECT_EQ(design_action(r)["status"], "met");
  EXPECT_EQ(design_action(r)["width_mm"].get<double>(), 2.0);
  EXPECT_EQ(design_action(r)["relaxations"].get<int>(), 1);
  const ReplayResult t = sutura::testing::replay_text(
      design({{"min_area_mm2", 20.0}}, {2, 8}, {{"tolerance", 0.01}, {"max_relaxations", 2}}),
      sutura::testing::scratch_dir("design", "tolerance"));
  const json& d = design_action(t);
  EXPECT_EQ(d["status"], "not_within_tolerance");
  EXPECT_EQ(d["width_mm"].get<double>(), 8.0);
  EXPECT_EQ(d["relaxations"].get<int>(), 2);
}

// A candidate that fails (its measure finds no vessel) fails the op and leaves the workspace
// as the op found it: the report's shape is the incised aorta's.
TEST(DesignPatch, AFailedCandidateLeavesTheWorkspaceAsItWas) {
  json measure = without(plan().measure, {"op", "object"});
  measure["centreline"] = {{100, 100, 100}, {101, 100, 100}};
  const fs::path dir = sutura::testing::scratch_dir("design", "fails");
  std::string error;
  try {
    (void)sutura::testing::replay_text(design({{"min_area_mm2", 20.0}}, {2, 8}, {{"measure", measure}}), dir);
  } catch (const std::exception& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("the candidate 2.000 mm wide failed"), std::string::npos) << error;
  std::ifstream in(dir / "out" / "report.json");
  const json report = json::parse(in);
  EXPECT_EQ(report["status"], "failed");
  const ReplayResult incised = sutura::testing::replay_text(plan().prefix, sutura::testing::scratch_dir("design", "incised2"));
  EXPECT_EQ(report["objects"]["aorta"]["position_hash"], hash(incised));
}

std::string failure(const std::string& text) {
  try {
    (void)parse_session(text, "s.jsonl");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(DesignPatch, BadRequestsNameTheField) {
  const std::string header = "{\"format\": \"sutura-session\", \"version\": 3}\n";
  auto op = [&](const json& target, const json& range, const json& extra = json::object()) {
    const std::string text = design(target, range, extra);
    return header + text.substr(text.rfind('\n', text.size() - 2) + 1);  // its last line
  };
  EXPECT_NE(failure(op({{"min_area_mm2", 20}}, {4, 2})).find("width_range"), std::string::npos);
  EXPECT_NE(failure(op({{"min_area_mm2", 20}}, {-1, 2})).find("width_range"), std::string::npos);
  EXPECT_NE(failure(op({{"min_area_mm2", -5}}, {2, 4})).find("target.min_area_mm2"), std::string::npos);
  EXPECT_NE(failure(op({{"min_area_mm2", 20}, {"coarctation_index", 0.8}}, {2, 4})).find("target.min_area_mm2"),
            std::string::npos);
  EXPECT_NE(failure(op({{"coarctation_index", 3}}, {2, 4})).find("target.coarctation_index"), std::string::npos);
  EXPECT_NE(failure(op({{"min_area_mm2", 20}}, {2, 4}, {{"max_bulge", 0.5}})).find("max_bulge"), std::string::npos);
  json with_width = json::parse(op({{"min_area_mm2", 20}}, {2, 4}).substr(header.size()));
  with_width["patch"]["width"] = 4;
  EXPECT_NE(failure(header + with_width.dump() + "\n").find("patch.width"), std::string::npos);
  json no_relax = with_width;
  no_relax["patch"].erase("width");
  no_relax["simulate"].erase("relax");
  EXPECT_NE(failure(header + no_relax.dump() + "\n").find("simulate.relax"), std::string::npos);
  json no_target = no_relax;
  no_target["simulate"] = without(plan().simulate, {"op"});
  no_target.erase("target");
  EXPECT_NE(failure(header + no_target.dump() + "\n").find("target"), std::string::npos);
  // The z-score target: its site, BSA and z are checked, and it is one target among three.
  EXPECT_NE(failure(op({{"z_score", -2}}, {2, 4})).find("target.bsa_m2"), std::string::npos);
  EXPECT_NE(failure(op({{"z_score", -2}, {"bsa_m2", 3}}, {2, 4})).find("target.bsa_m2"), std::string::npos);
  EXPECT_NE(failure(op({{"z_score", -9}, {"bsa_m2", 0.2}}, {2, 4})).find("target.z_score"), std::string::npos);
  EXPECT_NE(failure(op({{"z_score", -2}, {"bsa_m2", 0.2}, {"site", "root"}}, {2, 4})).find("target.site"),
            std::string::npos);
  EXPECT_NE(failure(op({{"z_score", -2}, {"bsa_m2", 0.2}, {"min_area_mm2", 20}}, {2, 4})).find("target.min_area_mm2"),
            std::string::npos);
}

// A z-score target is the area of a circle of the z-score's diameter (Pettersen's isthmus at
// BSA 0.2 m^2, z = -2: engine::arch_diameter_at_z), a smallest-area target.
TEST(DesignPatch, AZScoreTargetIsTheAreaOfItsDiameter) {
  const std::string text = design({{"z_score", -2}, {"site", "isthmus"}, {"bsa_m2", 0.2}}, {2, 6});
  const Session s = parse_session(text, "/tmp/z.jsonl");  // the default session's header and steps
  const auto& d = std::get<DesignPatchOp>(s.actions.back().op);
  ASSERT_TRUE(d.z_score.has_value());
  const double D = sutura::engine::arch_diameter_at_z(sutura::engine::ArchSite::Isthmus, 0.2, -2.0);
  EXPECT_DOUBLE_EQ(d.z_score->diameter_mm, D);
  EXPECT_EQ(d.target, DesignPatchOp::Target::MinArea);
  EXPECT_DOUBLE_EQ(d.target_value, 0.25 * M_PI * D * D);
  EXPECT_GT(D, 3.0);  // a neonate's isthmus two standard deviations below the mean: a few mm
  EXPECT_LT(D, 6.0);
}

// Run: the isthmus at z = -1 for BSA 0.2 m^2 (4.54 mm, 16.16 mm^2) is met, and the result
// says which z-score it met.
TEST(DesignPatch, MeetsAZScoreTarget) {
  const ReplayResult r = sutura::testing::replay_text(design({{"z_score", -1}, {"site", "isthmus"}, {"bsa_m2", 0.2}}, {2, 6}),
                                                      sutura::testing::scratch_dir("design", "zscore"));
  const json& d = design_action(r);
  EXPECT_EQ(d["status"], "met") << d.dump();
  const double D = sutura::engine::arch_diameter_at_z(sutura::engine::ArchSite::Isthmus, 0.2, -1.0);
  EXPECT_DOUBLE_EQ(d["target"]["z_score"]["diameter_mm"].get<double>(), D);
  const double area = r.report["measurements"]["lumen"]["after"]["min_area_mm2"].get<double>();
  EXPECT_GE(area, 0.25 * M_PI * D * D);
  EXPECT_LE(area, 0.25 * M_PI * D * D * 1.05);
  EXPECT_NE(d["summary"].get<std::string>().find("target: isthmus z -1.00 at BSA 0.20 m^2, diameter 4.54 mm"),
            std::string::npos)
      << d["summary"];
}

}  // namespace
