// The ops the GUI records: a loaded mesh inside the recording's directory is named relative to
// it, so that a recording and the meshes beside it can move together; any other mesh by its
// absolute path.
#include <gtest/gtest.h>

#include <fstream>
#include <unistd.h>

#include "../../ui/src/op_builders.hpp"

namespace fs = std::filesystem;
using namespace sutura::ui;

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
