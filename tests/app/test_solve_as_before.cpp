// `solve` with `as_before`: a vessel meshed unloaded is pressurised before the surgery, and that
// pressurised state is "before" of measurements and snapshots and the reference of probes, so
// before and after compare like with like. Errors name line, op and field.
#include <gtest/gtest.h>

#include "replay_fixture.hpp"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "sutura/app/replay.hpp"
#include "sutura/app/session.hpp"

namespace fs = std::filesystem;
using namespace sutura::app;

namespace {

const std::string kHeader = "{\"format\": \"sutura-session\", \"version\": 3}\n";
// A vessel segment meshed at zero pressure (R 4 mm, wall 0.3 mm, E 1 MPa), held at both ends,
// with 80 mmHg on it.
const std::string kTube =
    "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20, "
    "\"segments_around\": 24, \"segments_along\": 24}\n"
    "{\"op\": \"material\", \"object\": \"t\", \"youngs_modulus\": 1.0, \"poisson_ratio\": 0.45, "
    "\"thickness\": 0.3}\n"
    "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n"
    "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n";
const std::string kAsBefore = "{\"op\": \"solve\", \"as_before\": true}\n";
const std::string kMeasure =
    "{\"op\": \"measure\", \"object\": \"t\", \"name\": \"mid\", \"plane\": "
    "{\"origin\": [0, 0, 10.2], \"normal\": [0, 0, 1]}}\n"
    "{\"op\": \"probe\", \"object\": \"t\", \"name\": \"wall\", \"point\": [4, 0, 10]}\n";
// The 24-gon of R 4 as meshed.
constexpr double kUnloadedArea = 49.69;

fs::path scratch(const std::string& name) { return sutura::testing::scratch_dir("as_before", name); }

ReplayResult run(const std::string& text, const std::string& name) {
  return sutura::testing::replay_text(text, scratch(name));
}

double area(const ReplayResult& r, const char* side) {
  return r.report.at("measurements").at("mid").at(side).at("area_mm2").get<double>();
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

TEST(SolveAsBefore, ThePressurisedVesselIsBefore) {
  const ReplayResult plain = run(kHeader + kTube + "{\"op\": \"solve\"}\n" + kMeasure, "plain");
  const ReplayResult r = run(kHeader + kTube + kAsBefore + kMeasure, "as_before");
  // Without it, "before" is the vessel as meshed, at zero pressure, and the probe sees the
  // inflation as a displacement.
  EXPECT_NEAR(area(plain, "before"), kUnloadedArea, 0.01);
  EXPECT_GT(area(plain, "after"), 1.1 * kUnloadedArea);
  EXPECT_GT(plain.report.at("probes").at("wall").at("|u|").get<double>(), 0.2);
  // With it, before is that inflated vessel: the same section on both sides, no displacement.
  EXPECT_DOUBLE_EQ(area(r, "before"), area(plain, "after"));
  EXPECT_DOUBLE_EQ(area(r, "after"), area(r, "before"));
  EXPECT_EQ(r.report.at("probes").at("wall").at("|u|").get<double>(), 0.0);
  bool reported = false;
  for (const auto& a : r.report.at("actions"))
    if (a.at("op") == "solve") reported = a.value("as_before", false);
  EXPECT_TRUE(reported);
  // Its colour maps are those of the pressurised wall: a hoop strain of about 10 %, not zero.
  ASSERT_EQ(r.workspace.objects().size(), 1u);
  const SceneObject& t = *r.workspace.objects().begin();
  ASSERT_EQ(t.before_measures.membrane_strain.size(), t.before.num_vertices());
  const double mid_strain = t.before_measures.membrane_strain[t.before.num_vertices() / 2];
  EXPECT_GT(mid_strain, 0.05);
  EXPECT_LT(mid_strain, 0.2);
}

TEST(SolveAsBefore, ALaterSolveLeavesBeforeWhereItWas) {
  const ReplayResult first = run(kHeader + kTube + kAsBefore + kMeasure, "first");
  const ReplayResult later =
      run(kHeader + kTube + kAsBefore +
              "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n{\"op\": \"solve\"}\n" +
              kMeasure,
          "later");
  EXPECT_DOUBLE_EQ(area(later, "before"), area(first, "before"));
  EXPECT_GT(area(later, "after"), 1.05 * area(later, "before"));
  EXPECT_GT(later.report.at("probes").at("wall").at("|u|").get<double>(), 0.05);
}

TEST(SolveAsBefore, UndoGivesTheUnloadedBeforeBack) {
  const ReplayResult r = run(kHeader + kTube + kAsBefore + "{\"op\": \"undo\"}\n" + kMeasure, "undo");
  EXPECT_NEAR(area(r, "before"), kUnloadedArea, 0.01);
  EXPECT_NEAR(area(r, "after"), kUnloadedArea, 0.01);
}

TEST(SolveAsBefore, BadRequestsNameTheLineTheOpAndTheField) {
  const std::string base = kHeader + kTube;  // lines 1-5
  failure(base + "{\"op\": \"solve\", \"as_before\": true, \"load_factor\": 0.5}\n", 6, "as_before");
  failure(base + "{\"op\": \"solve\", \"as_before\": \"yes\"}\n", 6, "as_before");
  const std::string incised =
      base + "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 6], [4, 0, 14]]}\n" + kAsBefore;
  EXPECT_NE(failure(incised, 7, "").find("solve it before the first edit"), std::string::npos);
}
