#include "sutura/engine/mesh_io.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <tuple>
#include <type_traits>
#include <unordered_map>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "assimp_library.hpp"
#include "ply_check.hpp"
#include "sutura/engine/atomic_file.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace fs = std::filesystem;
using Kind = MeshIoError::Kind;

namespace {

enum class Format { Obj, Ply, Stl };

std::optional<Format> format_of(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return Format::Obj;
  if (ext == ".ply") return Format::Ply;
  if (ext == ".stl") return Format::Stl;
  return std::nullopt;
}

[[noreturn]] void fail(Kind kind, const fs::path& file, const std::string& problem) {
  throw MeshIoError(kind, file.string(), problem);
}

Format require_format(const fs::path& file) {
  const std::optional<Format> format = format_of(file);
  if (!format) {
    const std::string ext = file.extension().string();
    fail(Kind::UnsupportedFormat, file,
         (ext.empty() ? std::string("file has no extension")
                      : "unsupported format \"" + ext + "\"") +
             "; expected .stl, .obj or .ply");
  }
  return *format;
}

// The triangle count at bytes 80-83 of an STL file of at least 84 bytes (0 when they cannot
// be read). A binary STL's when 84 + 50 n bytes fit in the file; in an ASCII one it is text.
std::uint32_t stl_count_field(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char header[84];
  std::uint32_t n = 0;
  static_assert(std::endian::native == std::endian::little, "STL counts are little-endian");
  if (in.read(header, 84)) std::memcpy(&n, header + 80, 4);
  return n;
}

// Triangles a text file's lines give: `facet` lines (ASCII STL) or `f` lines with k corners,
// k - 2 each (OBJ). Streams the file in 1 MiB blocks; a line is judged by its first two
// tokens only, so a long line costs no memory.
std::uintmax_t count_text_triangles(const fs::path& file, Format format) {
  std::ifstream in(file, std::ios::binary);
  std::vector<char> block(std::size_t(1) << 20);
  std::uintmax_t triangles = 0;
  // Per line: the first token (up to 8 chars), whether it is complete, and for an `f` line
  // the number of corner tokens seen so far.
  std::string first;
  bool in_first = true, leading = true, face = false, in_token = false;
  std::uintmax_t corners = 0;
  const auto end_line = [&] {
    if (face && corners >= 3) triangles += corners - 2;
    first.clear();
    in_first = leading = true;
    face = in_token = false;
    corners = 0;
  };
  while (in) {
    in.read(block.data(), std::streamsize(block.size()));
    const std::streamsize got = in.gcount();
    for (std::streamsize i = 0; i < got; ++i) {
      const char c = block[std::size_t(i)];
      if (c == '\n' || c == '\r') {
        end_line();
        continue;
      }
      const bool space = c == ' ' || c == '\t';
      if (in_first) {
        if (space) {
          if (leading) continue;
          in_first = false;
          if (format == Format::Stl) {
            if (first == "facet") ++triangles;
          } else {
            face = first == "f";
          }
        } else {
          leading = false;
          if (first.size() < 8) first += c;
        }
      } else if (face) {
        if (!space && !in_token) ++corners;
        in_token = !space;
      }
    }
  }
  end_line();
  return triangles;
}

// The triangles `file` holds, from its header or one pass over its text (see
// ImportOptions::max_faces). A PLY's were counted by ply_structure_problem.
std::uintmax_t count_triangles(const fs::path& file, Format format, std::uintmax_t size,
                               std::uint64_t ply_triangles) {
  if (format == Format::Ply) return ply_triangles;
  if (format == Format::Stl && size >= 84) {
    const std::uint32_t n = stl_count_field(file);
    if (n > 0 && 84 + 50 * std::uintmax_t(n) <= size) return n;  // binary, as load_mesh reads it
  }
  return count_text_triangles(file, format);
}

std::string format_point(const Vec3& p) {
  std::ostringstream os;
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

// --- import ---------------------------------------------------------------------------------

// Triangles of every mesh in the scene, concatenated, indexing one concatenated vertex array.
struct Soup {
  std::vector<Vec3> positions;
  std::vector<std::array<std::size_t, 3>> triangles;
};

Soup collect_triangles(const aiScene& scene) {
  Soup soup;
  // Node transforms are ignored: STL, OBJ and PLY carry none, assimp leaves them identity.
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;  // points, lines
    const std::size_t base = soup.positions.size();
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      soup.positions.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      soup.triangles.push_back(
          {base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  return soup;
}

// assimp passes corrupt face data through unchecked (a PLY face can be empty or point past the
// vertices), and its triangulation then reads out of bounds or aborts on an assertion, so the
// raw scene is checked before any post-processing. Triangulating an n-gon costs O(n^2), so the
// polygons' total n^2 is capped too: a single 100000-gon would take minutes.
void check_raw_scene(const aiScene& scene, const fs::path& file) {
  constexpr double kMaxTriangulationWork = 1e8;  // about a second
  double work = 0.0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    unsigned types = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      const std::string name = "corrupt file: face " + std::to_string(f);
      if (face.mNumIndices == 0) fail(Kind::Unreadable, file, name + " has no corners");
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          fail(Kind::Unreadable, file,
               name + " refers to vertex " + std::to_string(face.mIndices[k]) + " of only " +
                   std::to_string(mesh.mNumVertices));
        }
      }
      if (face.mNumIndices > 3) {
        work += static_cast<double>(face.mNumIndices) * face.mNumIndices;
        if (work > kMaxTriangulationWork) {
          fail(Kind::Unreadable, file,
               "polygons too large to triangulate (face " + std::to_string(f) + " has " +
                   std::to_string(face.mNumIndices) + " corners)");
        }
      }
      types |= face.mNumIndices == 1   ? aiPrimitiveType_POINT
               : face.mNumIndices == 2 ? aiPrimitiveType_LINE
               : face.mNumIndices == 3 ? aiPrimitiveType_TRIANGLE
                                       : aiPrimitiveType_POLYGON;
    }
    // Triangulation asserts that a mesh flagged as holding polygons does hold some.
    const unsigned declared =
        mesh.mPrimitiveTypes & (aiPrimitiveType_POINT | aiPrimitiveType_LINE |
                                aiPrimitiveType_TRIANGLE | aiPrimitiveType_POLYGON);
    if (mesh.mNumFaces > 0 && declared != types) {
      fail(Kind::Unreadable, file, "corrupt file: inconsistent face data");
    }
  }
}

// assimp reads any text without OBJ statements as an empty OBJ scene, so when an OBJ yields
// nothing at all, tell garbage (Unreadable) from a file that is merely empty of geometry.
void explain_empty_obj(const fs::path& file) {
  static const char* const kStatements[] = {
      "v",     "vt",       "vn",       "vp",         "f",         "l",      "p",     "o",
      "g",     "s",        "mtllib",   "usemtl",     "usemap",    "maplib", "mg",    "lod",
      "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech",  "stech", "cstype",
      "deg",   "bmat",     "step",     "curv",       "curv2",     "surf",   "parm",  "trim",
      "hole",  "scrv",     "sp",       "end",        "con",       "call",   "csh"};
  std::ifstream in(file, std::ios::binary);
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    std::string word;
    if (!(words >> word) || word[0] == '#') continue;
    if (std::find(std::begin(kStatements), std::end(kStatements), word) == std::end(kStatements) ||
        line.find('\0') != std::string::npos) {
      fail(Kind::Unreadable, file,
           "not an OBJ file: line " + std::to_string(number) + " is not an OBJ statement");
    }
  }
}

// Disjoint sets whose root is always the lowest index of its set.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i] = i;
  }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

struct Cell {
  std::int64_t x, y, z;
  bool operator==(const Cell&) const = default;
};
struct CellHash {
  std::size_t operator()(const Cell& c) const noexcept {
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ULL;
    h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4FULL + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ULL + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// Welding with a hash grid of cell size eps = tolerance * bounding-box diagonal: every vertex
// joins the clusters of all earlier *kept* vertices within eps, and a vertex that joins none is
// kept (it starts a cluster). Kept vertices are more than eps apart, so a cell holds a bounded
// number of them and the pass stays O(n) even for a file whose vertices all coincide. The grid
// is only looked up, never iterated, and union-find roots are the lowest index, so the result
// does not depend on hashing. Returns each used vertex's representative: the lowest index of
// its cluster.
std::vector<std::size_t> weld(const std::vector<Vec3>& p, const std::vector<char>& used,
                              double tolerance) {
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (used[i]) box.extend(p[i]);
  }
  const double eps = tolerance * box.diagonal().norm();
  UnionFind clusters(p.size());

  // Cell coordinates must fit an int64 comfortably; below ~1e-12 of the diagonal welding by
  // distance is meaningless for float input anyway, so merge exact duplicates only.
  if (!(eps > 0.0) || box.diagonal().norm() / eps > 1e12) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (used[i]) order.push_back(i);
    }
    const auto key = [&](std::size_t i) { return std::tie(p[i].x(), p[i].y(), p[i].z()); };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return key(a) < key(b) || (key(a) == key(b) && a < b);
    });
    for (std::size_t k = 1; k < order.size(); ++k) {
      if (key(order[k]) == key(order[k - 1])) clusters.unite(order[k], order[k - 1]);
    }
  } else {
    // A later exact copy of a kept vertex joins that vertex and nothing else: whatever else
    // lies within eps of the point was either joined by the kept vertex already or, coming
    // later, was within eps of it and so not kept. Such copies (every corner of an STL but
    // the first at each point) skip the grid, which the rest of the pass would look up 27
    // times each; the clusters are the same.
    std::vector<std::size_t> first_copy(p.size());
    {
      std::vector<std::size_t> order;
      for (std::size_t i = 0; i < p.size(); ++i) {
        first_copy[i] = i;
        if (used[i]) order.push_back(i);
      }
      const auto key = [&](std::size_t i) { return std::tie(p[i].x(), p[i].y(), p[i].z()); };
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return key(a) < key(b) || (key(a) == key(b) && a < b);
      });
      for (std::size_t k = 1; k < order.size(); ++k)
        if (key(order[k]) == key(order[k - 1])) first_copy[order[k]] = first_copy[order[k - 1]];
    }
    std::vector<char> kept(p.size(), 0);
    std::unordered_map<Cell, std::vector<std::size_t>, CellHash> grid;
    const auto cell_of = [&](const Vec3& x) {
      const auto coordinate = [&](int k) {
        return static_cast<std::int64_t>(std::floor((x[k] - box.min()[k]) / eps));
      };
      return Cell{coordinate(0), coordinate(1), coordinate(2)};
    };
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!used[i]) continue;
      if (first_copy[i] != i && kept[first_copy[i]]) {
        clusters.unite(i, first_copy[i]);
        continue;
      }
      const Cell c = cell_of(p[i]);
      bool joined = false;
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find(Cell{c.x + dx, c.y + dy, c.z + dz});
            if (it == grid.end()) continue;
            for (std::size_t j : it->second) {
              if ((p[i] - p[j]).norm() <= eps) {
                clusters.unite(i, j);
                joined = true;
              }
            }
          }
        }
      }
      if (!joined) {
        grid[c].push_back(i);
        kept[i] = 1;
      }
    }
  }

  std::vector<std::size_t> representative(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) representative[i] = clusters.find(i);
  return representative;
}

SurfaceMesh build_mesh(const Soup& soup, const ImportOptions& options, const fs::path& file) {
  std::vector<char> used(soup.positions.size(), 0);
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    for (std::size_t v : soup.triangles[t]) {
      used[v] = 1;
      // Checked before welding: NaN would poison the bounding box and the grid.
      if (!soup.positions[v].allFinite()) {
        fail(Kind::NonFinite, file,
             "triangle " + std::to_string(t) + " has a corner with a non-finite coordinate " +
                 format_point(soup.positions[v]));
      }
    }
  }

  const std::vector<std::size_t> representative =
      weld(soup.positions, used, options.weld_tolerance);
  // Welded vertices in order of their representative, i.e. of first appearance in the file.
  std::vector<std::int32_t> new_id(soup.positions.size(), -1);
  std::vector<Vec3> positions;
  for (std::size_t i = 0; i < soup.positions.size(); ++i) {
    if (used[i] && representative[i] == i) {
      new_id[i] = static_cast<std::int32_t>(positions.size());
      positions.push_back(soup.positions[i]);
    }
  }
  std::vector<FaceIndices> faces;
  faces.reserve(soup.triangles.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    FaceIndices face{};
    for (int k = 0; k < 3; ++k) face[k] = new_id[representative[soup.triangles[t][k]]];
    if (face[0] == face[1] || face[1] == face[2] || face[2] == face[0]) {
      fail(Kind::Degenerate, file,
           "triangle " + std::to_string(t) +
               " is degenerate: two of its corners coincide (or lie within the weld tolerance)");
    }
    faces.push_back(face);
  }

  SurfaceMesh mesh;
  try {
    mesh = SurfaceMesh(std::move(positions), std::move(faces));
  } catch (const TopologyError& e) {
    fail(Kind::NonManifold, file,
         std::string("not a manifold surface: ") + e.what() +
             " (vertices numbered from 0 in order of first use, triangles in file order)");
  }
  // Same criterion as SurfaceMesh::validate(), so an imported mesh always validates clean.
  const std::vector<FaceId> degenerate = mesh.degenerate_faces();
  if (!degenerate.empty()) {
    fail(Kind::Degenerate, file,
         "triangle " + std::to_string(degenerate.front().value) +
             " is degenerate: it has (almost) zero area" +
             (degenerate.size() > 1
                  ? " (" + std::to_string(degenerate.size()) + " degenerate triangles in total)"
                  : std::string()));
  }
  return mesh;
}

// --- export ---------------------------------------------------------------------------------
// Written directly rather than through assimp's Exporter: its OBJ exporter merges vertices with
// equal positions (which would silently close an incision whose two sides coincide) and all of
// its exporters go through single-precision aiVector3D.

void append_number(std::string& out, double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);  // shortest round-trip
  out.append(buffer, result.ptr);
}

template <class T>
void append_le(std::string& out, T value) {
  using U = std::conditional_t<sizeof(T) == 8, std::uint64_t,
                               std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint16_t>>;
  const auto bits = std::bit_cast<U>(value);
  for (std::size_t k = 0; k < sizeof(T); ++k)
    out.push_back(static_cast<char>((bits >> (8 * k)) & 0xFF));
}

std::string obj_bytes(const SurfaceMesh& mesh) {
  std::string out = "# Sutura mesh: " + std::to_string(mesh.num_vertices()) + " vertices, " +
                    std::to_string(mesh.num_faces()) + " triangles\n";
  for (const Vec3& p : mesh.positions()) {
    out += "v ";
    append_number(out, p.x());
    out += ' ';
    append_number(out, p.y());
    out += ' ';
    append_number(out, p.z());
    out += '\n';
  }
  for (const FaceIndices& f : mesh.faces()) {
    out += "f " + std::to_string(f[0] + 1) + ' ' + std::to_string(f[1] + 1) + ' ' +
           std::to_string(f[2] + 1) + '\n';
  }
  return out;
}

std::string ply_bytes(const SurfaceMesh& mesh) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment Sutura mesh\nelement vertex " +
                    std::to_string(mesh.num_vertices()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(mesh.num_faces()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : mesh.positions()) {
    for (int k = 0; k < 3; ++k) append_le(out, p[k]);
  }
  for (const FaceIndices& f : mesh.faces()) {
    out.push_back(3);
    for (std::int32_t v : f) append_le(out, v);
  }
  return out;
}

std::string stl_bytes(const SurfaceMesh& mesh) {
  // The header must not start with "solid", or readers take the file for ASCII STL.
  std::string out = "Sutura binary STL";
  out.resize(80, ' ');
  append_le(out, static_cast<std::uint32_t>(mesh.num_faces()));
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 n = mesh.face_normal(FaceId(f));
    for (int k = 0; k < 3; ++k) append_le(out, static_cast<float>(n[k]));
    for (VertexId v : mesh.face_vertices(FaceId(f))) {
      for (int k = 0; k < 3; ++k) append_le(out, static_cast<float>(mesh.position(v)[k]));
    }
    append_le(out, std::uint16_t{0});  // attribute byte count
  }
  return out;
}

}  // namespace

namespace {

// The triangles of `file` (or of `stl_body`, when not empty: an STL read without its trailing
// bytes) through assimp, and whether the scene had no meshes at all. The raw scene is checked
// (check_raw_scene) before any post-processing: assimp's triangulation trusts its input, and
// its C interface mishandles a post-processing step that fails (it releases the scene a second
// time), so nothing that could make one fail may reach it. The library's lock (its last error
// is global) is held only while assimp works; the scene is gone when this returns.
Soup read_with_assimp(const fs::path& file, const std::string& stl_body, bool& no_meshes) {
  const detail::AssimpLibrary* ai = nullptr;
  try {
    ai = &detail::assimp();
  } catch (const std::exception& e) {
    fail(Kind::Unreadable, file, e.what());
  }
  const std::lock_guard<std::mutex> lock(*ai->lock);
  const auto release = [ai](const aiScene* scene) { ai->release(scene); };
  std::unique_ptr<const aiScene, decltype(release)> owned(nullptr, release);
  try {
    owned.reset(stl_body.empty()
                    ? ai->import_file(file.c_str(), 0)
                    : ai->import_memory(stl_body.data(), static_cast<unsigned int>(stl_body.size()), 0, "stl"));
  } catch (const std::exception& e) {  // assimp reports through nullptr; this is a safety net
    fail(Kind::Unreadable, file, std::string("cannot be read: ") + e.what());
  }
  if (!owned) {
    const char* why = ai->error_string();
    fail(Kind::Unreadable, file, std::string("cannot be read: ") + (why != nullptr ? why : "assimp gave no reason"));
  }
  check_raw_scene(*owned, file);
  // No aiProcess_JoinIdenticalVertices: it merges exact duplicates only; weld() does both. A
  // failed post-processing releases the scene itself, and sets no error of its own.
  const aiScene* processed = ai->apply_post_processing(owned.release(), aiProcess_Triangulate | aiProcess_SortByPType);
  if (processed == nullptr) fail(Kind::Unreadable, file, "cannot be triangulated (assimp's post-processing failed)");
  owned.reset(processed);
  no_meshes = owned->mNumMeshes == 0;
  return collect_triangles(*owned);
}

}  // namespace

SurfaceMesh load_mesh(const fs::path& file, const ImportOptions& options) {
  if (!(options.weld_tolerance >= 0.0) || !std::isfinite(options.weld_tolerance)) {
    std::ostringstream os;
    os << "load_mesh: weld_tolerance must be a finite number >= 0 (got " << options.weld_tolerance
       << ")";
    throw InvalidArgument(os.str());
  }

  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (status.type() == fs::file_type::not_found) fail(Kind::Missing, file, "file not found");
  if (error) fail(Kind::Unreadable, file, "cannot access the file: " + error.message());
  if (fs::is_directory(status)) fail(Kind::Unreadable, file, "is a directory, not a mesh file");
  const Format format = require_format(file);
  // A FIFO or device would block the importer forever.
  if (!fs::is_regular_file(status)) fail(Kind::Unreadable, file, "not a regular file");
  const std::uintmax_t size = fs::file_size(file, error);
  if (error) fail(Kind::Unreadable, file, "cannot access the file: " + error.message());
  if (size == 0) fail(Kind::Empty, file, "the file is empty (0 bytes)");
  const std::string no_triangles = "the file contains no triangles";
  // assimp rejects OBJ files under 16 bytes as "too small"; none of them can hold a triangle.
  if (format == Format::Obj && size < 16) {
    explain_empty_obj(file);
    fail(Kind::Empty, file, no_triangles);
  }

  std::uint64_t ply_triangles = 0;
  if (format == Format::Ply) {  // see ply_check.hpp: assimp's PLY reader can hang or crash
    std::ifstream in(file, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (const auto problem = detail::ply_structure_problem(bytes, &ply_triangles)) {
      fail(Kind::Unreadable, file, *problem);
    }
  }
  if (options.max_faces > 0) {
    const std::uintmax_t n = count_triangles(file, format, size, ply_triangles);
    if (n > options.max_faces)
      fail(Kind::TooLarge, file,
           "holds " + std::to_string(n) + " triangles, more than the limit of " +
               std::to_string(options.max_faces));
  }

  // A binary STL whose size is more than its 84 + 50 n bytes (trailing bytes, which some
  // exporters write) is taken by assimp for ASCII and refused: it is read without the tail.
  // An ASCII file's "count" (text at bytes 80-83) asks for far more bytes than it has.
  std::string stl_body;
  if (format == Format::Stl && size >= 84) {
    const std::uint32_t n = stl_count_field(file);
    const std::uintmax_t expected = 84 + 50 * std::uintmax_t(n);
    if (n > 0 && expected < size) {
      std::ifstream in(file, std::ios::binary);
      stl_body.resize(std::size_t(expected));
      if (!in.read(stl_body.data(), std::streamsize(expected)))
        fail(Kind::Unreadable, file, "cannot read its triangles");
    }
  }

  if (stl_body.size() > std::numeric_limits<unsigned int>::max())
    fail(Kind::TooLarge, file, "is too large to be read from memory");
  bool no_meshes = false;
  const Soup soup = read_with_assimp(file, stl_body, no_meshes);
  if (soup.triangles.empty()) {
    if (format == Format::Obj && no_meshes) explain_empty_obj(file);
    fail(Kind::Empty, file, no_triangles);
  }
  return build_mesh(soup, options, file);
}

void save_mesh(const SurfaceMesh& mesh, const fs::path& file) {
  const Format format = require_format(file);
  const std::string bytes = format == Format::Obj   ? obj_bytes(mesh)
                            : format == Format::Ply ? ply_bytes(mesh)
                                                    : stl_bytes(mesh);
  try {
    write_file_atomically(file, bytes);
  } catch (const std::exception& e) {
    fail(Kind::WriteFailed, file, std::string("saving failed: ") + e.what());
  }
}

}  // namespace sutura::engine
