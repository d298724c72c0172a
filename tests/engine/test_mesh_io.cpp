// Mesh files: round trips through OBJ, PLY and STL, welding, every kind of bad input, and
// atomic saving. All files are written by the tests into a fresh temporary directory.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <set>

#include "../../engine/src/assimp_library.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/mesh_io.hpp"
#include "temp_dir.hpp"

namespace sutura::engine {
namespace {

using testing::read_bytes;
using testing::TempDir;
using testing::write_bytes;
namespace fs = std::filesystem;
using Kind = MeshIoError::Kind;

SurfaceMesh test_tube() {
  return make_tube({.radius = 5.0, .length = 20.0, .segments_around = 16, .segments_along = 8});
}

void expect_load_error(const fs::path& file, Kind kind, const std::string& phrase,
                       const ImportOptions& options = {}) {
  try {
    const SurfaceMesh mesh = load_mesh(file, options);
    ADD_FAILURE() << file << ": loaded " << mesh.num_faces() << " faces, expected an error";
  } catch (const MeshIoError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.kind(), kind) << message;
    EXPECT_EQ(e.file(), file.string());
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(phrase), std::string::npos)
        << "\"" << message << "\" lacks \"" << phrase << "\"";
  }
}

// Binary STL from explicit triangle corners.
std::string binary_stl(const std::vector<std::array<Vec3, 3>>& triangles) {
  std::string out(80, ' ');
  const auto put = [&out](auto value) {
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);  // the test machine is little-endian like STL
    out.append(bytes, sizeof value);
  };
  put(static_cast<std::uint32_t>(triangles.size()));
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) put(0.0f);
    for (const Vec3& p : t) {
      for (int k = 0; k < 3; ++k) put(static_cast<float>(p[k]));
    }
    put(std::uint16_t{0});
  }
  return out;
}

// Matches every loaded vertex to the original vertex at (float-)equal position.
std::vector<std::int32_t> match_vertices(const SurfaceMesh& original, const SurfaceMesh& loaded) {
  std::vector<std::int32_t> to_original;
  for (const Vec3& p : loaded.positions()) {
    std::int32_t best = -1;
    double best_distance = 1e-5;
    for (std::size_t v = 0; v < original.num_vertices(); ++v) {
      const double d = (original.positions()[v] - p).norm();
      if (d < best_distance) {
        best_distance = d;
        best = static_cast<std::int32_t>(v);
      }
    }
    to_original.push_back(best);
  }
  return to_original;
}

// A cyclic vertex sequence rotated to start at its smallest entry.
std::vector<std::int32_t> canonical(std::vector<std::int32_t> cycle) {
  std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
  return cycle;
}

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, TubeSurvivesSaveAndLoad) {
  const TempDir dir;
  const fs::path file = dir / ("tube" + GetParam());
  const SurfaceMesh original = test_tube();
  save_mesh(original, file);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{file.filename().string()}));

  const SurfaceMesh loaded = load_mesh(file);
  ASSERT_EQ(loaded.num_vertices(), original.num_vertices());
  ASSERT_EQ(loaded.num_faces(), original.num_faces());
  EXPECT_TRUE(loaded.validate().ok()) << loaded.validate().summary();

  const std::vector<std::int32_t> to_original = match_vertices(original, loaded);
  EXPECT_EQ(std::count(to_original.begin(), to_original.end(), -1), 0) << "positions moved";
  EXPECT_EQ(std::set<std::int32_t>(to_original.begin(), to_original.end()).size(),
            original.num_vertices());

  // Same oriented triangles.
  std::set<std::vector<std::int32_t>> original_faces, loaded_faces;
  for (const FaceIndices& f : original.faces())
    original_faces.insert(canonical({f[0], f[1], f[2]}));
  for (const FaceIndices& f : loaded.faces()) {
    loaded_faces.insert(canonical({to_original[f[0]], to_original[f[1]], to_original[f[2]]}));
  }
  EXPECT_EQ(loaded_faces, original_faces);

  // Same boundary loops, same direction.
  std::set<std::vector<std::int32_t>> original_loops, loaded_loops;
  for (const auto& loop : original.boundary_loops()) {
    std::vector<std::int32_t> ids;
    for (VertexId v : loop) ids.push_back(v.value);
    original_loops.insert(canonical(ids));
  }
  for (const auto& loop : loaded.boundary_loops()) {
    std::vector<std::int32_t> ids;
    for (VertexId v : loop) ids.push_back(to_original[v.index()]);
    loaded_loops.insert(canonical(ids));
  }
  EXPECT_EQ(loaded_loops.size(), 2u);
  EXPECT_EQ(loaded_loops, original_loops);
}

TEST_P(RoundTrip, UppercaseExtension) {
  const TempDir dir;
  std::string ext = GetParam();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::toupper(c); });
  const fs::path file = dir / ("TUBE" + ext);
  save_mesh(test_tube(), file);
  const SurfaceMesh loaded = load_mesh(file);
  EXPECT_EQ(loaded.num_faces(), test_tube().num_faces());
  EXPECT_EQ(loaded.num_vertices(), test_tube().num_vertices());
}

TEST_P(RoundTrip, PatchKeepsItsArea) {
  const TempDir dir;
  const fs::path file = dir / ("patch" + GetParam());
  const SurfaceMesh original = make_patch({PatchShape::Triangle, 20.0, 8.0, 1.0});
  save_mesh(original, file);
  const SurfaceMesh loaded = load_mesh(file);
  EXPECT_EQ(loaded.num_vertices(), original.num_vertices());
  EXPECT_NEAR(loaded.total_area(), original.total_area(), 1e-4);
  EXPECT_EQ(loaded.boundary_loops().size(), 1u);
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip, ::testing::Values(".obj", ".ply", ".stl"),
                         [](const auto& info) { return info.param.substr(1); });

TEST(SaveMesh, FileContents) {
  const TempDir dir;
  const SurfaceMesh mesh = test_tube();
  save_mesh(mesh, dir / "a.stl");
  EXPECT_EQ(fs::file_size(dir / "a.stl"), 84u + 50u * mesh.num_faces());
  EXPECT_NE(read_bytes(dir / "a.stl").rfind("solid", 0), 0u)
      << "binary STL must not start with solid";
  save_mesh(mesh, dir / "a.obj");
  const std::string obj = read_bytes(dir / "a.obj");
  EXPECT_EQ(obj.rfind("# Sutura mesh", 0), 0u);
  EXPECT_EQ(static_cast<std::size_t>(std::count(obj.begin(), obj.end(), '\n')),
            1 + mesh.num_vertices() + mesh.num_faces());
  save_mesh(mesh, dir / "a.ply");
  EXPECT_EQ(read_bytes(dir / "a.ply").rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
}

TEST(SaveMesh, ObjKeepsCoincidentVerticesApartAndDoublesExact) {
  // Two triangles whose shared-looking corners are distinct vertices (as after an incision).
  const SurfaceMesh mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.1, 0.7, 0), Vec3(0, 0, 0),
                          Vec3(0.1, 0.7, 0), Vec3(-1, 0, 0)},
                         {{0, 1, 2}, {3, 4, 5}});
  const TempDir dir;
  save_mesh(mesh, dir / "cut.obj");
  const std::string obj = read_bytes(dir / "cut.obj");
  std::size_t vertex_lines = 0;
  for (std::size_t at = obj.find("\nv "); at != std::string::npos; at = obj.find("\nv ", at + 1)) {
    ++vertex_lines;
  }
  EXPECT_EQ(vertex_lines, 6u);
  EXPECT_NE(obj.find("v 0.1 0.7 0\n"), std::string::npos) << obj;
  EXPECT_NE(obj.find("f 4 5 6\n"), std::string::npos) << obj;
}

TEST(SaveMesh, OverwritesAnExistingFile) {
  const TempDir dir;
  save_mesh(test_tube(), dir / "m.ply");
  save_mesh(make_strip({}), dir / "m.ply");
  EXPECT_EQ(load_mesh(dir / "m.ply").num_faces(), make_strip({}).num_faces());
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"m.ply"}));
}

TEST(SaveMesh, UnsupportedExtensionWritesNothing) {
  const TempDir dir;
  try {
    save_mesh(test_tube(), dir / "tube.off");
    ADD_FAILURE() << "expected UnsupportedFormat";
  } catch (const MeshIoError& e) {
    EXPECT_EQ(e.kind(), Kind::UnsupportedFormat);
    EXPECT_NE(std::string(e.what()).find(".off"), std::string::npos);
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(SaveMesh, MissingDirectoryFails) {
  const TempDir dir;
  const fs::path file = dir / "missing" / "tube.obj";
  try {
    save_mesh(test_tube(), file);
    ADD_FAILURE() << "expected WriteFailed";
  } catch (const MeshIoError& e) {
    EXPECT_EQ(e.kind(), Kind::WriteFailed);
    EXPECT_EQ(e.file(), file.string());
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(SaveMesh, FailedRenameLeavesNoTemporaryAndKeepsTheTarget) {
  const TempDir dir;
  fs::create_directory(dir / "tube.stl");  // a directory where the file should go
  write_bytes(dir / "tube.stl" / "inside.txt", "keep");
  try {
    save_mesh(test_tube(), dir / "tube.stl");
    ADD_FAILURE() << "expected WriteFailed";
  } catch (const MeshIoError& e) {
    EXPECT_EQ(e.kind(), Kind::WriteFailed);
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"tube.stl"}));
  EXPECT_EQ(read_bytes(dir / "tube.stl" / "inside.txt"), "keep");
}

// Makes writes beyond `limit` bytes fail (EFBIG) for the lifetime of the object.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t limit) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = signal(SIGXFSZ, SIG_IGN);  // get EFBIG instead of being killed
    rlimit lowered = saved_;
    lowered.rlim_cur = limit;
    setrlimit(RLIMIT_FSIZE, &lowered);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    signal(SIGXFSZ, previous_handler_);
  }

 private:
  rlimit saved_{};
  sighandler_t previous_handler_;
};

TEST(SaveMesh, FailedWriteKeepsThePreviousFileAndNoTemporary) {
  const TempDir dir;
  write_bytes(dir / "tube.obj", "previous version");
  {
    const FileSizeLimit limit(1024);
    try {
      save_mesh(test_tube(), dir / "tube.obj");  // about 8 kB
      ADD_FAILURE() << "expected WriteFailed";
    } catch (const MeshIoError& e) {
      EXPECT_EQ(e.kind(), Kind::WriteFailed);
      EXPECT_NE(std::string(e.what()).find("tube.obj"), std::string::npos);
    }
  }
  EXPECT_EQ(read_bytes(dir / "tube.obj"), "previous version");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"tube.obj"}));
}

// --- welding -------------------------------------------------------------------------------------

// A tetrahedron as a triangle soup whose 12 corner copies are all slightly apart.
std::string jittered_tetrahedron_stl() {
  const std::array<Vec3, 4> p = {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(0, 0, 10)};
  const std::array<std::array<int, 3>, 4> faces = {{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
  std::vector<std::array<Vec3, 3>> soup;
  int copy = 0;
  for (const auto& f : faces) {
    std::array<Vec3, 3> t;
    for (int k = 0; k < 3; ++k) {
      // Several float steps apart (float spacing near 10 is about 1e-6), well below 1e-5 * diag.
      t[k] = p[f[k]] + 4e-6 * (++copy) * Vec3(1.0, -1.0, 1.0);
    }
    soup.push_back(t);
  }
  return binary_stl(soup);
}

TEST(Welding, JitteredDuplicatesAreWeldedWithinTolerance) {
  const TempDir dir;
  write_bytes(dir / "tetra.stl", jittered_tetrahedron_stl());
  const SurfaceMesh mesh = load_mesh(dir / "tetra.stl", {.weld_tolerance = 1e-5});
  EXPECT_EQ(mesh.num_vertices(), 4u);
  EXPECT_EQ(mesh.num_faces(), 4u);
  EXPECT_EQ(mesh.euler_characteristic(), 2);
  EXPECT_TRUE(mesh.boundary_loops().empty());
  EXPECT_TRUE(mesh.validate().ok()) << mesh.validate().summary();
  // Representative = first corner in the file: vertex 0 is corner 0 of triangle 0.
  EXPECT_EQ(mesh.position(VertexId(0)).cast<float>(), (Vec3(4e-6, -4e-6, 4e-6)).cast<float>());
}

TEST(Welding, ZeroToleranceMergesExactDuplicatesOnly) {
  const TempDir dir;
  write_bytes(dir / "tetra.stl", jittered_tetrahedron_stl());
  const SurfaceMesh mesh = load_mesh(dir / "tetra.stl", {.weld_tolerance = 0.0});
  EXPECT_EQ(mesh.num_vertices(), 12u);
  EXPECT_EQ(mesh.num_faces(), 4u);
  EXPECT_EQ(mesh.boundary_loops().size(), 4u);

  write_bytes(dir / "exact.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n");
  EXPECT_EQ(load_mesh(dir / "exact.obj", {.weld_tolerance = 0.0}).num_vertices(), 4u);
}

TEST(Welding, NegativeToleranceIsRejected) {
  const TempDir dir;
  write_bytes(dir / "tetra.stl", jittered_tetrahedron_stl());
  EXPECT_THROW(load_mesh(dir / "tetra.stl", {.weld_tolerance = -1.0}), InvalidArgument);
}

TEST(Welding, PolygonsAreTriangulatedAndPointsAndLinesIgnored) {
  const TempDir dir;
  write_bytes(dir / "mixed.obj",
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nl 1 5\np 5\nf 1 2 3 4\n");
  const SurfaceMesh mesh = load_mesh(dir / "mixed.obj");
  EXPECT_EQ(mesh.num_faces(), 2u);
  EXPECT_EQ(mesh.num_vertices(), 4u);  // vertex 5 only used by the line and the point
  EXPECT_NEAR(mesh.total_area(), 1.0, 1e-12);
}

TEST(Welding, AllMeshesOfAFileAreMerged) {
  const TempDir dir;
  // Two OBJ objects sharing an edge by position.
  write_bytes(dir / "two.obj",
              "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
              "o second\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 4 5 6\n");
  const SurfaceMesh mesh = load_mesh(dir / "two.obj");
  EXPECT_EQ(mesh.num_vertices(), 4u);
  EXPECT_EQ(mesh.num_edges(), 5u);
}

// --- bad input
// -------------------------------------------------------------------------------------

TEST(LoadErrors, MissingFile) {
  const TempDir dir;
  expect_load_error(dir / "nope.obj", Kind::Missing, "not found");
}

TEST(LoadErrors, DirectoryIsUnreadable) {
  const TempDir dir;
  fs::create_directory(dir / "folder.obj");
  expect_load_error(dir / "folder.obj", Kind::Unreadable, "directory");
}

TEST(LoadErrors, UnsupportedExtension) {
  const TempDir dir;
  write_bytes(dir / "mesh.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "mesh.off", Kind::UnsupportedFormat, "\".off\"");
  write_bytes(dir / "mesh", "v 0 0 0\n");
  expect_load_error(dir / "mesh", Kind::UnsupportedFormat, "no extension");
}

TEST(LoadErrors, EmptyFile) {
  const TempDir dir;
  for (const char* name : {"empty.stl", "empty.obj", "empty.ply"}) {
    write_bytes(dir / name, "");
    expect_load_error(dir / name, Kind::Empty, "empty");
  }
}

TEST(LoadErrors, GarbageIsUnreadable) {
  const TempDir dir;
  std::string garbage;
  std::uint32_t state = 12345;
  for (int i = 0; i < 4000; ++i) {
    state = state * 1664525u + 1013904223u;
    garbage.push_back(static_cast<char>(state >> 24));
  }
  for (const char* name : {"garbage.stl", "garbage.ply", "garbage.obj"}) {
    write_bytes(dir / name, garbage);
    expect_load_error(dir / name, Kind::Unreadable, "");
  }
  write_bytes(dir / "text.obj", "this is not a mesh\nat all\n");
  expect_load_error(dir / "text.obj", Kind::Unreadable, "line 1 is not an OBJ statement");
  write_bytes(dir / "tiny.obj", "v 0 0 0\nhi\n");
  expect_load_error(dir / "tiny.obj", Kind::Unreadable, "line 2 is not an OBJ statement");
  write_bytes(dir / "text.stl", "solid broken\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n");
  expect_load_error(dir / "text.stl", Kind::Unreadable, "cannot be read");
}

TEST(LoadErrors, TruncatedBinaryStl) {
  const TempDir dir;
  std::string stl = binary_stl({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}});
  stl[80] = 10;  // claims 10 triangles, holds one
  write_bytes(dir / "short.stl", stl);
  expect_load_error(dir / "short.stl", Kind::Unreadable, "cannot be read");
}

// Trailing bytes after a binary STL's triangles (some exporters pad) are ignored: assimp took
// such a file for ASCII and refused it (issue 27).
TEST(LoadMesh, BinaryStlWithTrailingBytesLoads) {
  const TempDir dir;
  const std::string stl = binary_stl({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                                      {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}});
  write_bytes(dir / "exact.stl", stl);
  write_bytes(dir / "padded.stl", stl + std::string("\n\0\0trailing", 12));
  const SurfaceMesh exact = load_mesh(dir / "exact.stl"), padded = load_mesh(dir / "padded.stl");
  EXPECT_EQ(padded.num_faces(), 2u);
  EXPECT_EQ(padded.positions(), exact.positions());
  EXPECT_EQ(padded.faces(), exact.faces());
}

// The limit is checked from the file before it is parsed, in every format: a mesh of exactly
// max_faces triangles loads, one more is refused with the count.
TEST(LoadMesh, MaxFacesIsCountedBeforeParsingInEveryFormat) {
  const TempDir dir;
  const SurfaceMesh tube = test_tube();
  const std::size_t n = tube.num_faces();
  std::string ascii = "solid tube\n";
  for (const auto& f : tube.faces()) {
    ascii += "  facet normal 0 0 0\n    outer loop\n";
    for (const auto v : f) {
      const Vec3& p = tube.position(VertexId(v));
      ascii += "      vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
               std::to_string(p.z()) + "\n";
    }
    ascii += "    endloop\n  endfacet\n";
  }
  write_bytes(dir / "ascii.stl", ascii + "endsolid tube\n");
  for (const char* name : {"t.obj", "t.ply", "t.stl"}) save_mesh(tube, dir / name);
  for (const char* name : {"t.obj", "t.ply", "t.stl", "ascii.stl"}) {
    SCOPED_TRACE(name);
    ImportOptions options;
    options.max_faces = n;
    EXPECT_EQ(load_mesh(dir / name, options).num_faces(), n);
    options.max_faces = n - 1;
    expect_load_error(dir / name, Kind::TooLarge,
                      "holds " + std::to_string(n) + " triangles, more than the limit of " +
                          std::to_string(n - 1),
                      options);
  }
  // A polygon of k corners counts as the k - 2 triangles it becomes, in OBJ and PLY.
  write_bytes(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\tf  1 2 3 4 \r\n");
  write_bytes(dir / "quad.ply",
              "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  for (const char* name : {"quad.obj", "quad.ply"}) {
    ImportOptions options;
    options.max_faces = 1;
    expect_load_error(dir / name, Kind::TooLarge, "holds 2 triangles", options);
  }
}

TEST(LoadErrors, PlyHeaderCutShort) {
  // assimp itself would never return on these.
  const TempDir dir;
  write_bytes(dir / "cut.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nprop");
  expect_load_error(dir / "cut.ply", Kind::Unreadable, "no end_header");
  write_bytes(dir / "bare.ply", "ply\nformat ascii 1.0\n");
  expect_load_error(dir / "bare.ply", Kind::Unreadable, "no end_header");
}

TEST(LoadErrors, PlyHeaderAnnouncingMoreThanTheFileHolds) {
  // assimp would loop over the announced entries for minutes.
  const TempDir dir;
  const std::string properties =
      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  write_bytes(dir / "many.ply", "ply\nformat ascii 1.0\nelement vertex 99999999\n" + properties +
                                    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "many.ply", Kind::Unreadable, "announces 99999999 vertex entries");
  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 4\n" + properties;
  binary.append(4 * 12, '\0');  // the vertices, but no room left for the face
  write_bytes(dir / "short.ply", binary);
  expect_load_error(dir / "short.ply", Kind::Unreadable, "face entry 0 of 1");
  write_bytes(dir / "odd.ply", "ply\nformat ascii 1.0\nelement 99999999face 2\n" + properties);
  expect_load_error(dir / "odd.ply", Kind::Unreadable, "corrupt PLY header line");
  write_bytes(dir / "list.ply", "ply\nformat ascii 1.0\nelement vertex 3\n" + properties +
                                    "0 0 0\n1 0 0\n0 1 0\n999999993 0 1 2\n");
  expect_load_error(dir / "list.ply", Kind::Unreadable, "list of 999999993 values but holds fewer");
}

TEST(LoadPly, BigEndianBinary) {
  // Checks that the structure check reads big-endian list lengths right.
  std::string ply =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list ushort int vertex_indices\nend_header\n";
  const auto put_big_endian = [&ply](std::uint32_t bits, int bytes) {
    for (int k = bytes - 1; k >= 0; --k) ply.push_back(static_cast<char>((bits >> (8 * k)) & 0xFF));
  };
  for (float value : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) {
    put_big_endian(std::bit_cast<std::uint32_t>(value), 4);
  }
  put_big_endian(3, 2);
  for (std::uint32_t v : {0u, 1u, 2u}) put_big_endian(v, 4);
  const TempDir dir;
  write_bytes(dir / "be.ply", ply);
  const SurfaceMesh mesh = load_mesh(dir / "be.ply");
  EXPECT_EQ(mesh.num_faces(), 1u);
  EXPECT_DOUBLE_EQ(mesh.total_area(), 0.5);
}

TEST(LoadErrors, PlyIndexOutOfRange) {
  const TempDir dir;
  write_bytes(dir / "bad.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expect_load_error(dir / "bad.ply", Kind::Unreadable, "face 0 refers to vertex 7 of only 3");
  // A polygon pointing far past the vertices: assimp's triangulation would read out of bounds.
  write_bytes(dir / "far.ply",
              "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 2000000000\n");
  expect_load_error(dir / "far.ply", Kind::Unreadable, "refers to vertex 2000000000");
  // An empty face: assimp's triangulation would abort on an assertion.
  write_bytes(dir / "hollow.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0\n");
  expect_load_error(dir / "hollow.ply", Kind::Unreadable, "face 1 has no corners");
}

TEST(LoadErrors, NoTriangles) {
  const TempDir dir;
  write_bytes(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_load_error(dir / "points.obj", Kind::Empty, "no triangles");
  write_bytes(dir / "comments.obj", "# exported by nothing\n\n");
  expect_load_error(dir / "comments.obj", Kind::Empty, "no triangles");
  write_bytes(dir / "tiny.obj", "v 0 0 0\n");  // assimp refuses OBJ files this small
  expect_load_error(dir / "tiny.obj", Kind::Empty, "no triangles");
  write_bytes(dir / "points.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n");
  expect_load_error(dir / "points.ply", Kind::Empty, "no triangles");
}

TEST(LoadErrors, NonFiniteCoordinates) {
  const TempDir dir;
  write_bytes(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_load_error(dir / "nan.obj", Kind::NonFinite, "non-finite coordinate (nan, 0, 0)");
  write_bytes(
      dir / "inf.stl",
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 inf 0\n"
      "endloop\nendfacet\nendsolid t\n");
  expect_load_error(dir / "inf.stl", Kind::NonFinite, "triangle 0");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  write_bytes(dir / "nan.stl", binary_stl({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                                           {Vec3(1, 0, 0), Vec3(1, 1, nan), Vec3(0, 1, 0)}}));
  expect_load_error(dir / "nan.stl", Kind::NonFinite, "triangle 1");
}

TEST(LoadErrors, DegenerateTriangles) {
  const TempDir dir;
  // Triangle 1 is flat: its corners lie on the x axis.
  write_bytes(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 2 1 4\n");
  expect_load_error(dir / "flat.obj", Kind::Degenerate, "triangle 1 is degenerate");
  // A triangle that repeats a corner.
  write_bytes(dir / "collapsed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n");
  expect_load_error(dir / "collapsed.obj", Kind::Degenerate, "two of its corners coincide");
  // Corners 1e-9 apart collapse only once welded.
  write_bytes(dir / "welded.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1.000000001 0 0\nf 1 2 3\nf 1 2 4\n");
  expect_load_error(dir / "welded.obj", Kind::Degenerate, "triangle 1");
}

TEST(LoadErrors, HugePolygonIsRefusedRatherThanTriangulatedForMinutes) {
  const TempDir dir;
  std::string obj;
  constexpr int kCorners = 20000;
  for (int i = 0; i < kCorners; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / kCorners;
    obj += "v " + std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0\n";
  }
  obj += "f";
  for (int i = 1; i <= kCorners; ++i) obj += ' ', obj += std::to_string(i);  // not " " + ...: GCC 12 -Wrestrict
  write_bytes(dir / "disk.obj", obj + "\n");
  expect_load_error(dir / "disk.obj", Kind::Unreadable, "20000 corners");
}

TEST(LoadErrors, ThreeFacesOnOneEdge) {
  const TempDir dir;
  write_bytes(dir / "fin.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  expect_load_error(dir / "fin.obj", Kind::NonManifold, "shared by 3 faces");
}

TEST(LoadErrors, BowTieVertex) {
  const TempDir dir;
  write_bytes(dir / "bowtie.obj",
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n");
  expect_load_error(dir / "bowtie.obj", Kind::NonManifold, "pinched");
}

TEST(LoadErrors, FlippedNeighbour) {
  const TempDir dir;
  write_bytes(dir / "flipped.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 4 3\n");
  expect_load_error(dir / "flipped.obj", Kind::NonManifold, "inconsistent orientation");
}

}  // namespace
}  // namespace sutura::engine

// assimp is loaded at the first mesh file it reads; without it, the error names the library
// and the Debian package, and a library without its entry points is refused by name.
TEST(MeshIoAssimp, AMissingLibraryIsNamedWithItsPackage) {
  try {
    (void)sutura::engine::detail::load_assimp("libassimp-not-here.so.5");
    ADD_FAILURE() << "a missing library loaded";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("libassimp-not-here.so.5"), std::string::npos) << m;
    EXPECT_NE(m.find("libassimp5"), std::string::npos) << m;
  }
  try {
    (void)sutura::engine::detail::load_assimp("libm.so.6");
    ADD_FAILURE() << "libm was taken for assimp";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("aiImportFile"), std::string::npos) << e.what();
  }
  EXPECT_NE(sutura::engine::detail::assimp().import_file, nullptr);  // the real one
}
