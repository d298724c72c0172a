// The material op by region: the whole object (one material, the original meaning), the wall
// (the object's first material; patches keep theirs) or the material of the face nearest a
// point (a patch), where the fields not given keep that material's values.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "replay_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sutura::app;

const std::string kHeader = "{\"format\": \"sutura-session\", \"version\": 3}\n";
// A tube with an elliptic patch (E 3, nu 0.45, t 0.4) in a slit of its wall at x = 4.
const std::string kPatchedTube =
    "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 30, "
    "\"segments_around\": 24, \"segments_along\": 30}\n"
    "{\"op\": \"material\", \"object\": \"t\", \"youngs_modulus\": 1.0, \"thickness\": 0.8}\n"
    "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 10], [4, 0, 20]]}\n"
    "{\"op\": \"patch\", \"object\": \"t\", \"start\": [4, 0, 10], \"end\": [4, 0, 20], \"width\": 4, "
    "\"material\": {\"youngs_modulus\": 3.0, \"poisson_ratio\": 0.45, \"thickness\": 0.4}}\n";

ReplayResult run(const std::string& text, const std::string& name) {
  return sutura::testing::replay_text(text, sutura::testing::scratch_dir("material", name));
}

const SceneObject& tube(const ReplayResult& r) { return *r.workspace.find("t"); }

// The patch's material index and a point in the middle of one of its faces.
std::pair<int, sutura::engine::Vec3> patch_face(const SceneObject& o) {
  for (std::size_t f = 0; f < o.mesh.num_faces(); ++f)
    if (o.sim.face_material[f] != 0) {
      const auto& t = o.mesh.faces()[f];
      const auto& x = o.mesh.positions();
      return {o.sim.face_material[f], (x[t[0]] + x[t[1]] + x[t[2]]) / 3.0};
    }
  ADD_FAILURE() << "no patch face";
  return {0, sutura::engine::Vec3::Zero()};
}

std::string point(const sutura::engine::Vec3& p) { return nlohmann::json::array({p.x(), p.y(), p.z()}).dump(); }

}  // namespace

TEST(MaterialRegions, TheWallMaterialLeavesThePatchAlone) {
  const ReplayResult before = run(kHeader + kPatchedTube, "before");
  const auto [patch, inside] = patch_face(tube(before));
  ASSERT_EQ(tube(before).sim.materials.size(), 2u);
  const ReplayResult r = run(kHeader + kPatchedTube +
                                 "{\"op\": \"material\", \"object\": \"t\", \"region\": \"wall\", "
                                 "\"youngs_modulus\": 2.0}\n",
                             "wall");
  const SceneObject& o = tube(r);
  ASSERT_EQ(o.sim.materials.size(), 2u);
  EXPECT_EQ(o.sim.face_material, tube(before).sim.face_material);
  EXPECT_EQ(o.sim.materials[0].youngs_modulus, 2.0);
  EXPECT_EQ(o.sim.materials[0].thickness, 0.8);  // not given: kept
  EXPECT_EQ(o.sim.materials[patch].youngs_modulus, 3.0);
  EXPECT_EQ(o.sim.materials[patch].thickness, 0.4);
  const auto& out = r.report["actions"].back();
  EXPECT_EQ(out["material"], 0) << out.dump();
}

TEST(MaterialRegions, APointPicksThePatchsMaterial) {
  const ReplayResult before = run(kHeader + kPatchedTube, "before_at");
  const auto [patch, inside] = patch_face(tube(before));
  const ReplayResult r = run(kHeader + kPatchedTube + "{\"op\": \"material\", \"object\": \"t\", \"at\": " +
                                 point(inside) + ", \"youngs_modulus\": 20.0, \"thickness\": 0.3}\n",
                             "at");
  const SceneObject& o = tube(r);
  EXPECT_EQ(o.sim.materials[patch].youngs_modulus, 20.0);
  EXPECT_EQ(o.sim.materials[patch].thickness, 0.3);
  EXPECT_EQ(o.sim.materials[patch].poisson_ratio, 0.45);  // not given: kept
  EXPECT_EQ(o.sim.materials[0].youngs_modulus, 1.0);      // the wall untouched
  const auto patch_faces = std::count(o.sim.face_material.begin(), o.sim.face_material.end(), patch);
  EXPECT_EQ(r.report["actions"].back()["faces"], patch_faces);
  EXPECT_GT(patch_faces, 0);
}

TEST(MaterialRegions, WithoutARegionOneMaterialCoversEverythingAsBefore) {
  const ReplayResult r = run(kHeader + kPatchedTube +
                                 "{\"op\": \"material\", \"object\": \"t\", \"youngs_modulus\": 2.0}\n",
                             "all");
  const SceneObject& o = tube(r);
  ASSERT_EQ(o.sim.materials.size(), 1u);
  EXPECT_EQ(o.sim.materials[0].youngs_modulus, 2.0);
  EXPECT_EQ(o.sim.materials[0].thickness, sutura::engine::ShellMaterial{}.thickness);  // defaults
  for (int m : o.sim.face_material) ASSERT_EQ(m, 0);
}

TEST(MaterialRegions, BadRegionsAreClearErrors) {
  const auto error = [](const std::string& text, const std::string& name) -> std::string {
    try {
      run(text, name);
    } catch (const SessionError& e) {
      EXPECT_EQ(e.line(), 6) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return {};
  };
  std::string e = error(kHeader + kPatchedTube +
                            "{\"op\": \"material\", \"object\": \"t\", \"region\": \"wall\", \"at\": [4, 0, 15]}\n",
                        "both");
  EXPECT_NE(e.find("either region or at"), std::string::npos) << e;
  e = error(kHeader + kPatchedTube + "{\"op\": \"material\", \"object\": \"t\", \"region\": \"patch\"}\n", "choice");
  EXPECT_NE(e.find("region"), std::string::npos) << e;
  e = error(kHeader + kPatchedTube + "{\"op\": \"material\", \"object\": \"t\", \"at\": [0, 0, 15]}\n", "far");
  EXPECT_NE(e.find("mm from the nearest face"), std::string::npos) << e;
  e = error(kHeader + kPatchedTube +
                "{\"op\": \"material\", \"object\": \"t\", \"region\": \"wall\", \"max_distance\": 2}\n",
            "stray");
  EXPECT_NE(e.find("max_distance"), std::string::npos) << e;
}

// What the window lists: one region per material with its face count, which add up to the
// object's faces; with the patch undone, every face is the wall's.
TEST(MaterialRegions, TheRegionsListEachMaterialWithItsFaces) {
  const ReplayResult r = run(kHeader + kPatchedTube, "list");
  const std::vector<MaterialRegion> regions = material_regions(tube(r));
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].material.youngs_modulus, 1.0);
  EXPECT_EQ(regions[1].material.youngs_modulus, 3.0);
  EXPECT_GT(regions[0].faces, 0u);
  EXPECT_GT(regions[1].faces, 0u);
  EXPECT_EQ(regions[0].faces + regions[1].faces, tube(r).mesh.num_faces());
  const ReplayResult undone = run(kHeader + kPatchedTube + "{\"op\": \"undo\"}\n", "undone");
  const std::vector<MaterialRegion> after = material_regions(tube(undone));
  for (std::size_t k = 1; k < after.size(); ++k) EXPECT_EQ(after[k].faces, 0u);
  EXPECT_EQ(after[0].faces, tube(undone).mesh.num_faces());
}
