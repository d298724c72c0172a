// Named open ends: a landmarks file given to `load` names the ends listed under the mesh
// file's stem; end_name matches them to the boundary loops as they are now, and a loop an
// incision has opened no longer matches. Bad landmarks are errors naming the file and field.
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "replay_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sutura::app;

const fs::path kAnatomy = fs::path(SUTURA_ASSETS_DIR) / "anatomy" / "coarse";

fs::path scratch(const std::string& name) { return sutura::testing::scratch_dir("ends", name); }

ReplayResult run(const std::string& lines, const fs::path& dir) {
  return sutura::testing::replay_text("{\"format\": \"sutura-session\", \"version\": 3}\n" + lines, dir);
}

std::string load_line(const fs::path& landmarks) {
  return "{\"op\": \"load\", \"object\": \"aorta\", \"file\": \"" + (kAnatomy / "aorta.ply").string() +
         "\", \"landmarks\": \"" + landmarks.string() + "\"}\n";
}

}  // namespace

TEST(EndNames, TheBundledArchsEndsAreNamedFromItsLandmarks) {
  const fs::path dir = scratch("arch");
  const ReplayResult r = run(load_line(kAnatomy / "landmarks.json"), dir);
  const SceneObject& a = *r.workspace.find("aorta");
  std::set<std::string> names;
  for (const auto& loop : a.mesh.boundary_loops()) names.insert(end_name(a, loop));
  EXPECT_EQ(names, (std::set<std::string>{"ascending_root", "descending", "innominate", "left_common_carotid",
                                           "left_subclavian"}));
  EXPECT_EQ(r.report["actions"][0]["end_names"].size(), 5u);
  // An incision from the subclavian's open end opens its loop into the cut: no longer that end.
  const ReplayResult cut = run(load_line(kAnatomy / "landmarks.json") +
                                   "{\"op\": \"incise\", \"object\": \"aorta\", \"points\": [[14.831, 13.679, "
                                   "34.732], [13.696, 13.088, 32.04], [12.935, 12.691, 30.234]]}\n",
                               scratch("cut"));
  const SceneObject& c = *cut.workspace.find("aorta");
  std::multiset<std::string> after;
  for (const auto& loop : c.mesh.boundary_loops()) after.insert(end_name(c, loop));
  EXPECT_EQ(after.count("left_subclavian"), 0u);
  EXPECT_EQ(after.count(""), 1u);
  EXPECT_EQ(after.count("descending"), 1u);
}

TEST(EndNames, BadLandmarksAreClearErrors) {
  const fs::path dir = scratch("bad");
  const auto error = [&](const std::string& content) -> std::string {
    const fs::path file = dir / "landmarks.json";
    std::ofstream(file) << content;
    try {
      run(load_line(file), dir);
    } catch (const SessionError& e) {
      EXPECT_EQ(e.line(), 2) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "no error for " << content;
    return {};
  };
  std::string e = error("{\"pulmonary\": {\"ends\": []}}");
  EXPECT_NE(e.find("no entry 'aorta'"), std::string::npos) << e;
  EXPECT_NE(e.find("landmarks.json"), std::string::npos) << e;
  e = error("{\"aorta\": {\"ends\": [{\"name\": \"root\", \"centre\": [0, 0], \"normal\": [0, 0, 1], \"radius\": 4}]}}");
  EXPECT_NE(e.find("aorta.ends[0].centre"), std::string::npos) << e;
  e = error("{\"aorta\": {\"ends\": [{\"name\": \"root\", \"centre\": [0, 0, 0], \"normal\": [0, 0, 1], \"radius\": -1}]}}");
  EXPECT_NE(e.find("aorta.ends[0].radius"), std::string::npos) << e;
  e = error("{\"aorta\": ");
  EXPECT_NE(e.find("not valid JSON (at byte 11)"), std::string::npos) << e;
}
