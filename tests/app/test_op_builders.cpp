// The ops the GUI records: a loaded mesh inside the recording's directory is named relative to
// it, so that a recording and the meshes beside it can move together; any other mesh by its
// absolute path.
#include <gtest/gtest.h>

#include <fstream>
#include <unistd.h>

#include "sutura/app/op_builders.hpp"
#include "sutura/app/session.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/mesh_io.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"

namespace fs = std::filesystem;
using namespace sutura::app;

TEST(OpBuilders, ALoadedMeshBesideTheRecordingIsNamedRelativeToIt) {
  const fs::path dir = fs::temp_directory_path() / ("sutura_op_builders_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "patient" / "scans");
  for (const fs::path& f : {dir / "patient" / "vessel.ply", dir / "patient" / "scans" / "v.stl", dir / "elsewhere.ply"})
    std::ofstream(f) << "x";
  const fs::path recording = dir / "patient" / "plan.jsonl";
  EXPECT_EQ(load_op("a", dir / "patient" / "vessel.ply", recording)["file"], "vessel.ply");
  EXPECT_EQ(load_op("a", dir / "patient" / "." / "scans" / ".." / "scans" / "v.stl", recording)["file"],
            "scans/v.stl");
  // Outside the recording's directory, and a file that does not exist: absolute.
  EXPECT_EQ(load_op("a", dir / "elsewhere.ply", recording)["file"], (dir / "elsewhere.ply").string());
  EXPECT_EQ(load_op("a", dir / "patient" / "gone.ply", recording)["file"], (dir / "patient" / "gone.ply").string());
  // A relative file is relative to the working directory, as typed.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir / "patient");
  const nlohmann::json typed = load_op("a", "vessel.ply", recording);
  fs::current_path(cwd);
  EXPECT_EQ(typed["file"], "vessel.ply");
  EXPECT_EQ(typed["op"], "load");
  EXPECT_EQ(typed["object"], "a");
  EXPECT_FALSE(typed.contains("prepare"));
  const nlohmann::json prepared = load_op("a", dir / "patient" / "vessel.ply", recording, true, 0.5);
  EXPECT_EQ(prepared["prepare"]["smoothing"], 10);
  EXPECT_EQ(prepared["prepare"]["edge_length"], 0.5);
  fs::remove_all(dir);
}

// A region's material: the wall by name, a patch by a point on one of its faces (the centroid
// of its lowest-numbered face, which the material op resolves back to that face).
TEST(OpBuilders, AMaterialIsRecordedForItsRegionOnly) {
  sutura::engine::StripParams sp;
  sp.segments_length = 4;
  sp.segments_width = 2;
  const sutura::engine::SurfaceMesh m = sutura::engine::make_strip(sp);
  std::vector<int> face_material(m.num_faces(), 0);
  face_material[5] = face_material[9] = 1;
  const nlohmann::json wall = material_op(m, face_material, "a", 0, 2.5, 0.45, 1.0);
  EXPECT_EQ(wall["region"], "wall");
  EXPECT_FALSE(wall.contains("at"));
  EXPECT_EQ(wall["youngs_modulus"], 2.5);
  const nlohmann::json patch = material_op(m, face_material, "a", 1, 30.0, 0.45, 0.3);
  EXPECT_FALSE(patch.contains("region"));
  const auto& t = m.faces()[5];
  const sutura::engine::Vec3 c = (m.positions()[t[0]] + m.positions()[t[1]] + m.positions()[t[2]]) / 3.0;
  EXPECT_EQ(patch["at"], point_json(c));
  EXPECT_THROW(material_op(m, face_material, "a", 2, 1.0, 0.45, 1.0), std::invalid_argument);
  // Only the values given: the region keeps the others.
  const nlohmann::json thinner = material_op(m, face_material, "a", 1, std::nullopt, std::nullopt, 0.35);
  EXPECT_EQ(thinner["thickness"], 0.35);
  EXPECT_FALSE(thinner.contains("youngs_modulus"));
  EXPECT_FALSE(thinner.contains("poisson_ratio"));
}

// What a float field records: the decimal the surgeon typed, not the float's binary expansion.
TEST(OpBuilders, FloatFieldsAreRecordedAsTyped) {
  EXPECT_EQ(as_typed(0.45f), 0.45);
  EXPECT_EQ(as_typed(2.5f), 2.5);
  EXPECT_EQ(as_typed(1e-3f), 0.001);
  EXPECT_EQ(as_typed(0.35f), 0.35);
  EXPECT_EQ(float(as_typed(0.1f)), 0.1f);  // reads back as the same float
}

// A snapshot of a cut-open view records the plane, and the session reads it back as the same
// plane (normalised).
TEST(OpBuilders, ASnapshotOfACutOpenViewRecordsItsPlane) {
  SnapshotView view;
  view.camera.eye = {0.0f, -40.0f, 0.0f};
  const nlohmann::json plain = snapshot_op("a.png", view, false, "none");
  EXPECT_FALSE(plain.contains("clip"));
  view.clip = sutura::render::ClipPlane{{1.0f, 2.0f, 3.0f}, {0.0f, -1.0f, 0.0f}};
  const nlohmann::json cut = snapshot_op("a.png", view, true, "none");
  ASSERT_TRUE(cut.contains("clip"));
  EXPECT_EQ(cut["clip"]["point"], nlohmann::json::array({1.0f, 2.0f, 3.0f}));
  EXPECT_EQ(cut["clip"]["normal"], nlohmann::json::array({0.0f, -1.0f, 0.0f}));
  const auto session = sutura::app::parse_session(
      "{\"format\": \"sutura-session\", \"version\": 3}\n" + cut.dump() + "\n", "/tmp/s.jsonl");
  const auto& op = std::get<sutura::app::SnapshotOp>(session.actions.at(0).op);
  ASSERT_TRUE(op.clip.has_value());
  EXPECT_DOUBLE_EQ(op.clip->point[2], 3.0);
  EXPECT_DOUBLE_EQ(op.clip->normal[1], -1.0);
}

// The Fix tool's two clicks hold the boundary run between them, as the join op would resolve
// it (nearest boundary vertices, boundary direction): every vertex of that run and only those,
// in all DOFs; clicks on two different loops are refused, naming why.
TEST(OpBuilders, TheFixToolHoldsTheBoundaryRunBetweenItsClicks) {
  const sutura::engine::SurfaceMesh m =
      sutura::engine::load_mesh(std::string(SUTURA_SOURCE_DIR) + "/tests/gui/two_strips.obj");
  const sutura::engine::Vec3 a(18, -5, 0), b(18, 5, 0);  // the corners of strip 1's facing end
  const nlohmann::json op = fix_run_op(m, "strips", a + sutura::engine::Vec3(0.1, 0.1, 0), b, true);
  EXPECT_EQ(op["op"], "fix");
  EXPECT_EQ(op["object"], "strips");
  EXPECT_EQ(op["dofs"], nlohmann::json::array({"all"}));
  sutura::engine::ChainSpec spec;
  spec.from = a;
  spec.to = b;
  std::vector<int> want;
  for (auto v : sutura::engine::find_boundary_chain(m, spec).vertices) want.push_back(v.value);
  ASSERT_GE(want.size(), 2u);
  EXPECT_EQ(op["vertices"].get<std::vector<int>>(), want);
  EXPECT_EQ(m.position(sutura::engine::VertexId(want.front())), a);
  EXPECT_EQ(m.position(sutura::engine::VertexId(want.back())), b);
  // Without the fix op (an older build's op table): the same vertices through constrain.
  EXPECT_EQ(fix_run_op(m, "strips", a, b, false)["op"], "constrain");
  // Strip 1's corner and strip 2's: no run joins them.
  try {
    (void)fix_run_op(m, "strips", a, sutura::engine::Vec3(22, -5, 0), true);
    ADD_FAILURE() << "a run across two loops";
  } catch (const sutura::engine::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("loop"), std::string::npos) << e.what();
  }
}

TEST(OpBuilders, TheCuttingTemplateIsOfTheLastPatchWithItsStartProximal) {
  Plan plan;
  plan.steps.push_back({3, "patch", {{"op", "patch"}, {"object", "a"}, {"start", {1, 2, 3}}, {"end", {4, 5, 6}}}, {}});
  plan.steps.push_back({4, "patch", {{"op", "patch"}, {"object", "b"}, {"start", {0, 0, 0}}, {"end", {1, 1, 1}}}, {}});
  plan.steps.push_back({5, "patch", {{"op", "patch"}, {"object", "a"}, {"start", {7, 8, 9}}, {"end", {4, 5, 6}}}, {}});
  plan.applied = 3;
  nlohmann::json op = patch_template_op(plan, "a", 2, "t.pdf");
  EXPECT_EQ(op, nlohmann::json({{"op", "export_patch_template"}, {"object", "a"}, {"file", "t.pdf"},
                                {"patch", 2}, {"proximal", {7, 8, 9}}}));
  plan.applied = 2;  // the second patch on "a" undone
  op = patch_template_op(plan, "a", 1, "t.pdf");
  EXPECT_EQ(op["proximal"], nlohmann::json({1, 2, 3}));
  EXPECT_EQ(op["patch"], 1);
  try {
    (void)patch_template_op(plan, "a", 0, "t.pdf");
    ADD_FAILURE() << "no patch, yet an op";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has no patch"), std::string::npos);
  }
  EXPECT_THROW((void)patch_template_op(plan, "c", 1, "t.pdf"), std::invalid_argument);
  // A designed patch: its part `patch` has the start.
  plan.steps.push_back({6, "design_patch", {{"op", "design_patch"}, {"object", "c"}, {"patch", {{"start", {3, 2, 1}}}}}, {}});
  plan.applied = 4;
  EXPECT_EQ(patch_template_op(plan, "c", 1, "t.pdf")["proximal"], nlohmann::json({3, 2, 1}));
}

// After a run, what keeps its triangles well shaped: a remesh of each object with a smaller
// angle than the limit, then one settle of those objects; nothing when none is below.
TEST(OpBuilders, KeepingAnglesRemeshesTheObjectsBelowTheLimitAndSettlesThem) {
  const std::vector<SmallestAngle> angles = {{"a", 12.0, {}, 30.0}, {"b", 25.0, {}, 30.0}, {"c", 19.9, {}, 30.0}};
  const std::vector<nlohmann::json> ops = keep_angle_ops(angles, 20.0, 0.6, true, true);
  ASSERT_EQ(ops.size(), 3u);
  EXPECT_EQ(ops[0], remesh_small_angles_op("a", 20.0, 0.6, 0.0, 3));
  EXPECT_EQ(ops[1], remesh_small_angles_op("c", 20.0, 0.6, 0.0, 3));
  EXPECT_EQ(ops[2], (nlohmann::json{{"op", "solve"}, {"objects", {"a", "c"}}, {"minimize", true},
                                    {"check_stability", true}, {"collapse_barrier", true}}));
  for (const auto& op : ops) EXPECT_NO_THROW(parse_action(op, "keep.jsonl", 1)) << op.dump();
  const nlohmann::json newton = keep_angle_ops(angles, 20.0, 0.6, false, false)[2];
  EXPECT_FALSE(newton.contains("collapse_barrier"));
  EXPECT_FALSE(newton.contains("minimize"));
  EXPECT_TRUE(keep_angle_ops(angles, 12.0, 0.6, true, true).empty());  // none below 12
  EXPECT_TRUE(keep_angle_ops({}, 20.0, 0.6, true, true).empty());
}

TEST(OpBuilders, TheStaticRunSolvesEveryLoadInFourSteps) {
  EXPECT_EQ(static_solve_op(true, true), (nlohmann::json{{"op", "solve"}, {"load_steps", 4}, {"check_stability", true},
                                                          {"minimize", true}, {"collapse_barrier", true}}));
  EXPECT_EQ(static_solve_op(false, false),
            (nlohmann::json{{"op", "solve"}, {"load_steps", 4}, {"check_stability", true}}));
  EXPECT_NO_THROW(parse_action(static_solve_op(true, true), "static.jsonl", 1));
}

// On a workspace: the object held and squeezed is remeshed and settled (as a minimisation: it
// has no loads); the same squeeze on an object that nothing holds is left alone (a settle of it
// has no unique equilibrium); an object without a small angle plans nothing.
TEST(OpBuilders, KeepingAnglesOnAWorkspaceLeavesObjectsThatAreNotHeld) {
  Workspace w;
  for (const char* name : {"held", "free", "fine"}) w.add(name, sutura::engine::make_strip({}));
  for (const char* name : {"held", "free"}) {
    SceneObject& o = *w.edit(name);
    const auto v = o.mesh.face_vertices(sutura::engine::FaceId(9));
    const sutura::engine::Vec3 mid = 0.5 * (o.mesh.position(v[0]) + o.mesh.position(v[1]));
    o.mesh.set_position(v[2], mid + 0.05 * (o.mesh.position(v[2]) - mid));
    o.sim.state.x[std::size_t(v[2].index())] = o.mesh.position(v[2]);
  }
  for (const char* name : {"held", "fine"}) {
    SceneObject& o = *w.edit(name);
    std::vector<sutura::engine::VertexId> all;
    for (std::size_t v = 0; v < o.mesh.num_vertices(); ++v) all.emplace_back(int(v));
    o.sim.constraints.fix(all, sutura::engine::kAllDofs, o.mesh.num_vertices());
  }
  const std::vector<nlohmann::json> ops = keep_angle_plan(w, 20.0, 0.6, false);
  ASSERT_EQ(ops.size(), 2u);
  EXPECT_EQ(ops[0], remesh_small_angles_op("held", 20.0, 0.6, 0.0, 3));
  EXPECT_EQ(ops[1], (nlohmann::json{{"op", "solve"}, {"objects", {"held"}}, {"check_stability", true},
                                    {"minimize", true}}));
  const double squeezed = smallest_angles(w)[0].degrees;
  EXPECT_LT(squeezed, 20.0);
  EXPECT_TRUE(keep_angle_plan(w, squeezed, 0.6, false).empty());  // none strictly below
}

// The object form reads the object's mesh, materials by face and name.
TEST(OpBuilders, AMaterialOfAnObjectIsThatOfItsMeshAndFaces) {
  Workspace w;
  w.add("a", sutura::engine::make_strip({}));
  const SceneObject& o = *w.find("a");
  EXPECT_EQ(material_op(o, 0, 2.5, std::nullopt, 1.0),
            material_op(o.mesh, o.sim.face_material, "a", 0, 2.5, std::nullopt, 1.0));
  EXPECT_THROW((void)material_op(o, 1, 2.5, std::nullopt, 1.0), std::invalid_argument);  // no patch
}
