// The `unload` op: an imaged, pressurised tube stays where it was imaged, now in equilibrium
// under its pressure, with "before" the imaged shape; a solve after it has nothing to do; undo
// gives the old rest back; and the errors name line, op and field.
#include <gtest/gtest.h>

#include "replay_fixture.hpp"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "sutura/app/replay.hpp"
#include "sutura/app/session.hpp"

namespace fs = std::filesystem;
using namespace sutura::app;

namespace {

const std::string kHeader = "{\"format\": \"sutura-session\", \"version\": 3}\n";
// A vessel segment imaged at 80 mmHg (R 4 mm there, wall 0.3 mm, E 1 MPa), held at both ends.
const std::string kImaged =
    "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20, "
    "\"segments_around\": 24, \"segments_along\": 24}\n"
    "{\"op\": \"material\", \"object\": \"t\", \"youngs_modulus\": 1.0, \"poisson_ratio\": 0.45, "
    "\"thickness\": 0.3}\n"
    "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n"
    "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n";
const std::string kMeasure =
    "{\"op\": \"measure\", \"object\": \"t\", \"name\": \"mid\", \"plane\": "
    "{\"origin\": [0, 0, 10.2], \"normal\": [0, 0, 1]}}\n"
    "{\"op\": \"probe\", \"object\": \"t\", \"name\": \"wall\", \"point\": [4, 0, 10]}\n";

fs::path scratch(const std::string& name) { return sutura::testing::scratch_dir("unload", name); }

ReplayResult run(const std::string& text, const std::string& name) {
  return sutura::testing::replay_text(text, scratch(name));
}

nlohmann::json action(const ReplayResult& r, const std::string& op, int nth = 0) {
  for (const auto& a : r.report.at("actions"))
    if (a.at("op") == op && nth-- == 0) return a;
  ADD_FAILURE() << "no action " << op;
  return {};
}

std::string failure(const std::string& text, int line, const std::string& field) {
  try {
    run(text, "fail");
  } catch (const SessionError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "the session did not fail";
  return {};
}

}  // namespace

TEST(UnloadOp, TheImagedTubeStaysImagedInEquilibriumUnderItsPressure) {
  const ReplayResult r =
      run(kHeader + kImaged + "{\"op\": \"unload\", \"object\": \"t\"}\n" +
              "{\"op\": \"solve\"}\n" + kMeasure,
          "imaged");
  const nlohmann::json u = action(r, "unload");
  EXPECT_TRUE(u.at("converged").get<bool>());
  EXPECT_LE(u.at("max_deviation_mm").get<double>(), u.at("tolerance_mm").get<double>());
  EXPECT_LE(u.at("max_deviation_mm").get<double>(), 0.01 * 4.0);  // 1 % of the radius
  EXPECT_GT(u.at("max_unloading_mm").get<double>(), 0.2);          // the pressure widens it
  EXPECT_EQ(u.at("history").size(), u.at("iterations").get<std::size_t>());
  // A solve after it has no load left to ramp and starts in equilibrium.
  const nlohmann::json s = action(r, "solve");
  EXPECT_LE(s.at("iterations").get<int>(), 1) << s.dump();
  // Before = the imaged shape = now: the 24-gon of R 4 (49.69 mm^2) on both sides, and the
  // wall has not moved from where it was imaged.
  const nlohmann::json mid = r.report.at("measurements").at("mid");
  EXPECT_NEAR(mid.at("before").at("area_mm2").get<double>(), 49.69, 0.01);
  EXPECT_NEAR(mid.at("after").at("area_mm2").get<double>(), 49.69, 0.01 * 49.69);
  EXPECT_LT(r.report.at("probes").at("wall").at("|u|").get<double>(), 0.01 * 4.0);
  // The pre-operative state is the stressed one: its strains (what "before" shows in colour)
  // are the pressurised wall's, a hoop strain of about 10 %, not zero.
  ASSERT_EQ(r.workspace.objects().size(), 1u);
  const SceneObject& t = *r.workspace.objects().begin();
  ASSERT_EQ(t.before_measures.membrane_strain.size(), t.before.num_vertices());
  const double mid_strain = t.before_measures.membrane_strain[t.before.num_vertices() / 2];
  EXPECT_GT(mid_strain, 0.05);
  EXPECT_LT(mid_strain, 0.2);
}

TEST(UnloadOp, WithoutUnloadThePressureInflatesTheImagedShapeASecondTime) {
  // The contrast the op exists for: solving the imaged shape as if stress-free widens it by
  // about as much again.
  const ReplayResult r = run(kHeader + kImaged + "{\"op\": \"solve\"}\n" + kMeasure, "twice");
  EXPECT_GT(r.report.at("probes").at("wall").at("|u|").get<double>(), 0.2);
  const nlohmann::json mid = r.report.at("measurements").at("mid");
  EXPECT_GT(mid.at("after").at("area_mm2").get<double>(), 1.1 * 49.69);
}

TEST(UnloadOp, UndoGivesTheStressFreeImagedShapeBack) {
  // After undo the pressure is pending again on the imaged rest: a solve inflates it.
  const ReplayResult r =
      run(kHeader + kImaged + "{\"op\": \"unload\", \"object\": \"t\"}\n{\"op\": \"undo\"}\n" +
              "{\"op\": \"solve\"}\n" + kMeasure,
          "undo");
  EXPECT_GT(r.report.at("probes").at("wall").at("|u|").get<double>(), 0.2);
}

TEST(UnloadOp, BadRequestsNameTheLineTheOpAndTheField) {
  const std::string base = kHeader + kImaged;  // lines 1-5
  failure(base + "{\"op\": \"unload\", \"object\": \"t\", \"analysis\": \"linear\"}\n", 6, "analysis");
  failure(base + "{\"op\": \"unload\", \"object\": \"t\", \"iterations\": 0}\n", 6, "iterations");
  failure(base + "{\"op\": \"unload\", \"object\": \"t\", \"shape_tolerance\": -1}\n", 6,
          "shape_tolerance");
  failure(base + "{\"op\": \"unload\", \"object\": \"t\", \"objects\": [\"t\"]}\n", 6, "objects");
  failure(base + "{\"op\": \"unload\"}\n", 6, "object");
  // At run time: an incised vessel, one without loads, one free to move.
  const std::string incised =
      base + "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 6], [4, 0, 14]]}\n"
             "{\"op\": \"unload\", \"object\": \"t\"}\n";
  EXPECT_NE(failure(incised, 7, "").find("unload it before the first edit"), std::string::npos);
  const std::string unloaded_tube =
      kHeader +
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20}\n"
      "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n"
      "{\"op\": \"unload\", \"object\": \"t\"}\n";
  EXPECT_NE(failure(unloaded_tube, 4, "").find("has no loads to unload"), std::string::npos);
  const std::string free_tube =
      kHeader +
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20}\n"
      "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n"
      "{\"op\": \"unload\", \"object\": \"t\"}\n";
  EXPECT_NE(failure(free_tube, 4, "").find("can move as a rigid body"), std::string::npos);
}
