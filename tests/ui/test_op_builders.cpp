// The ops the GUI records: a loaded mesh is named relative to the recording, so that a
// recording and the meshes beside it can move together.
#include <gtest/gtest.h>

#include "../../ui/src/op_builders.hpp"

namespace fs = std::filesystem;
using namespace sutura::ui;

TEST(OpBuilders, ALoadedMeshIsNamedRelativeToTheRecording) {
  EXPECT_EQ(load_op("a", "/data/patient/vessel.ply", "/data/patient/plan.jsonl")["file"], "vessel.ply");
  EXPECT_EQ(load_op("a", "/data/patient/scans/v.stl", "/data/patient/out/plan.jsonl")["file"], "../scans/v.stl");
  EXPECT_EQ(load_op("a", "/data/./patient/../patient/v.ply", "/data/patient/plan.jsonl")["file"], "v.ply");
  // A relative file is relative to the working directory, as typed.
  const nlohmann::json typed = load_op("a", "in.ply", fs::current_path() / "out" / "plan.jsonl");
  EXPECT_EQ(typed["file"], "../in.ply");
  EXPECT_EQ(typed["op"], "load");
  EXPECT_EQ(typed["object"], "a");
  EXPECT_FALSE(typed.contains("prepare"));
  const nlohmann::json prepared = load_op("a", "/d/v.stl", "/d/plan.jsonl", true, 0.5);
  EXPECT_EQ(prepared["prepare"]["smoothing"], 10);
  EXPECT_EQ(prepared["prepare"]["edge_length"], 0.5);
}
