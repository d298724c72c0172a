#include "sutura/engine/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>
#include <utility>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

// Problems found while deriving adjacency. The constructor stops at the first one (throwing
// TopologyError), validate() collects all of them, so both share one derivation and can never
// disagree about what a valid mesh is.
class ProblemSink {
 public:
  explicit ProblemSink(bool throw_first) : throw_first_(throw_first) {}

  void add(std::string problem) {
    if (throw_first_) throw TopologyError(problem);
    // A badly broken mesh can have millions of problems; a few dozen say everything.
    if (problems_.size() < kMaxListed) {
      problems_.push_back(std::move(problem));
    } else {
      ++omitted_;
    }
  }
  [[nodiscard]] std::vector<std::string> take() {
    if (omitted_ > 0) problems_.push_back("... and " + std::to_string(omitted_) + " more problems");
    return std::move(problems_);
  }

 private:
  static constexpr std::size_t kMaxListed = 50;
  bool throw_first_;
  std::vector<std::string> problems_;
  std::size_t omitted_ = 0;
};

std::string edge_name(std::int32_t a, std::int32_t b) {
  return "edge (" + std::to_string(std::min(a, b)) + ", " + std::to_string(std::max(a, b)) + ")";
}

std::string format_position(const Vec3& p) {
  std::ostringstream os;
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

// Adjacency re-derived from the face array alone.
struct Adjacency {
  std::vector<HalfedgeId> twin;
  std::vector<HalfedgeId> vertex_halfedge;
  std::size_t num_edges = 0;
};

std::int32_t corner_vertex(const std::vector<FaceIndices>& faces, std::size_t h) {
  return faces[h / 3][h % 3];
}

HalfedgeId rotate_ccw(const std::vector<HalfedgeId>& twin, HalfedgeId h) {
  // Outgoing half-edge h of v -> the outgoing half-edge of v in the next face counter-clockwise:
  // the twin of the half-edge entering v in h's face.
  return twin[SurfaceMesh::prev(h).index()];
}

// Index ranges and repeated corners. Returns false if any face is unusable, in which case the
// adjacency cannot be derived.
bool check_faces(std::size_t num_vertices, const std::vector<FaceIndices>& faces,
                 ProblemSink& sink) {
  bool ok = true;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const FaceIndices& t = faces[f];
    for (std::int32_t v : t) {
      if (v < 0 || static_cast<std::size_t>(v) >= num_vertices) {
        sink.add("face " + std::to_string(f) + " references vertex " + std::to_string(v) +
                 ", out of range for a mesh with " + std::to_string(num_vertices) + " vertices");
        ok = false;
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      const std::int32_t repeated = t[0] == t[1] || t[0] == t[2] ? t[0] : t[1];
      sink.add("face " + std::to_string(f) + " repeats vertex " + std::to_string(repeated));
      ok = false;
    }
  }
  return ok;
}

// Pairs half-edges into twins by sorting them on their undirected edge: O(H log H) and
// deterministic. Reports edges with more than two faces and pairs running the same direction.
void derive_twins(const std::vector<FaceIndices>& faces, Adjacency& adj, ProblemSink& sink) {
  const std::size_t num_halfedges = 3 * faces.size();
  struct Key {
    std::int32_t lo, hi;
    std::size_t h;
  };
  std::vector<Key> keys(num_halfedges);
  for (std::size_t h = 0; h < num_halfedges; ++h) {
    const std::int32_t a = corner_vertex(faces, h);
    const std::int32_t b = faces[h / 3][(h % 3 + 1) % 3];
    keys[h] = {std::min(a, b), std::max(a, b), h};
  }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    return std::tie(x.lo, x.hi, x.h) < std::tie(y.lo, y.hi, y.h);
  });

  adj.twin.assign(num_halfedges, HalfedgeId());
  adj.num_edges = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].lo == keys[i].lo && keys[j].hi == keys[i].hi) ++j;
    ++adj.num_edges;
    const std::size_t count = j - i;
    if (count > 2) {
      sink.add(edge_name(keys[i].lo, keys[i].hi) + " is shared by " + std::to_string(count) +
               " faces (non-manifold edge; at most two are allowed)");
    } else if (count == 2) {
      const std::size_t h0 = keys[i].h;
      const std::size_t h1 = keys[i + 1].h;
      if (corner_vertex(faces, h0) == corner_vertex(faces, h1)) {
        sink.add("faces " + std::to_string(h0 / 3) + " and " + std::to_string(h1 / 3) +
                 " traverse " + edge_name(keys[i].lo, keys[i].hi) +
                 " in the same direction (inconsistent orientation)");
      } else {
        adj.twin[h0] = HalfedgeId(h1);
        adj.twin[h1] = HalfedgeId(h0);
      }
    }
    i = j;
  }
}

// Counts the fans around every vertex by walking the orbits of rotate_ccw: an open fan is a
// chain starting at an outgoing boundary half-edge, a closed fan a cycle. A manifold vertex has
// exactly one fan; zero means unused, more than one means pinched. Also picks each vertex's
// half-edge: its outgoing boundary half-edge if any, else its lowest outgoing half-edge. O(H).
void derive_fans(std::size_t num_vertices, const std::vector<FaceIndices>& faces, Adjacency& adj,
                 ProblemSink& sink) {
  const std::size_t num_halfedges = adj.twin.size();
  std::vector<char> visited(num_halfedges, 0);
  std::vector<int> fans(num_vertices, 0);
  adj.vertex_halfedge.assign(num_vertices, HalfedgeId());

  const auto start_fan = [&](std::size_t h) {
    const auto v = static_cast<std::size_t>(corner_vertex(faces, h));
    ++fans[v];
    if (!adj.vertex_halfedge[v].valid()) adj.vertex_halfedge[v] = HalfedgeId(h);
  };
  for (std::size_t h = 0; h < num_halfedges; ++h) {
    if (adj.twin[h].valid()) continue;
    start_fan(h);
    for (HalfedgeId g(h); g.valid(); g = rotate_ccw(adj.twin, g)) visited[g.index()] = 1;
  }
  for (std::size_t h = 0; h < num_halfedges; ++h) {
    if (visited[h]) continue;
    start_fan(h);
    // Every half-edge not on a chain lies on a cycle (rotation is injective), so this ends.
    HalfedgeId g(h);
    do {
      visited[g.index()] = 1;
      g = rotate_ccw(adj.twin, g);
    } while (g.index() != h);
  }

  for (std::size_t v = 0; v < num_vertices; ++v) {
    if (fans[v] == 0) {
      sink.add("vertex " + std::to_string(v) + " is not used by any face (unused vertex)");
    } else if (fans[v] > 1) {
      sink.add("vertex " + std::to_string(v) +
               " is pinched (non-manifold vertex): its faces form " + std::to_string(fans[v]) +
               " separate fans");
    }
  }
}

void check_positions(const std::vector<Vec3>& positions, ProblemSink& sink) {
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (!positions[v].allFinite()) {
      sink.add("vertex " + std::to_string(v) + " has a non-finite coordinate " +
               format_position(positions[v]));
    }
  }
}

// Everything the constructor checks (positions first: they do not depend on the connectivity).
// Returns false, leaving `adj` unset, when the faces themselves are unusable.
bool derive(const std::vector<Vec3>& positions, const std::vector<FaceIndices>& faces,
            Adjacency& adj, ProblemSink& sink) {
  check_positions(positions, sink);
  if (!check_faces(positions.size(), faces, sink)) return false;
  derive_twins(faces, adj, sink);
  derive_fans(positions.size(), faces, adj, sink);
  return true;
}

}  // namespace

std::string ValidationReport::summary() const {
  std::string out;
  for (const std::string& p : problems) {
    if (!out.empty()) out += "; ";
    out += p;
  }
  return out;
}

SurfaceMesh::SurfaceMesh(std::vector<Vec3> positions, std::vector<FaceIndices> faces)
    : positions_(std::move(positions)), faces_(std::move(faces)) {
  // Half-edge ids are 3f+k in an int32.
  if (faces_.size() > static_cast<std::size_t>(INT32_MAX / 3) ||
      positions_.size() > static_cast<std::size_t>(INT32_MAX)) {
    throw TopologyError("mesh too large: " + std::to_string(faces_.size()) + " faces, " +
                        std::to_string(positions_.size()) + " vertices");
  }
  build_adjacency();
}

void SurfaceMesh::build_adjacency() {
  ProblemSink sink(/*throw_first=*/true);
  Adjacency adj;
  derive(positions_, faces_, adj, sink);
  twin_ = std::move(adj.twin);
  vertex_halfedge_ = std::move(adj.vertex_halfedge);
  num_edges_ = adj.num_edges;
}

std::array<VertexId, 3> SurfaceMesh::face_vertices(FaceId f) const {
  const FaceIndices& t = faces_[f.index()];
  return {VertexId(t[0]), VertexId(t[1]), VertexId(t[2])};
}

VertexId SurfaceMesh::from_vertex(HalfedgeId h) const {
  return VertexId(corner_vertex(faces_, h.index()));
}

VertexId SurfaceMesh::to_vertex(HalfedgeId h) const { return from_vertex(next(h)); }

bool SurfaceMesh::is_boundary(VertexId v) const { return is_boundary(vertex_halfedge(v)); }

std::vector<FaceId> SurfaceMesh::vertex_faces(VertexId v) const {
  std::vector<FaceId> out;
  const HalfedgeId start = vertex_halfedge(v);
  HalfedgeId h = start;
  do {
    out.push_back(face(h));
    h = rotate_ccw(twin_, h);
  } while (h.valid() && h != start);
  return out;
}

std::vector<VertexId> SurfaceMesh::vertex_neighbors(VertexId v) const {
  std::vector<VertexId> out;
  const HalfedgeId start = vertex_halfedge(v);
  HalfedgeId h = start;
  while (true) {
    out.push_back(to_vertex(h));
    const HalfedgeId in = prev(h);
    h = twin(in);
    if (!h.valid()) {
      out.push_back(from_vertex(in));  // end of an open fan: the far end of the incoming boundary
      break;
    }
    if (h == start) break;
  }
  return out;
}

std::vector<HalfedgeId> SurfaceMesh::edges() const {
  std::vector<HalfedgeId> out;
  out.reserve(num_edges_);
  for (std::size_t h = 0; h < twin_.size(); ++h) {
    if (!twin_[h].valid() || h < twin_[h].index()) out.emplace_back(h);
  }
  return out;
}

std::vector<std::vector<VertexId>> SurfaceMesh::boundary_loops() const {
  // On a manifold every boundary vertex has exactly one outgoing boundary half-edge (its
  // vertex_halfedge), so following them from the smallest unvisited boundary vertex traces each
  // loop once, already in the documented order.
  std::vector<std::vector<VertexId>> loops;
  std::vector<char> visited(num_vertices(), 0);
  for (std::size_t v = 0; v < num_vertices(); ++v) {
    if (visited[v] || !is_boundary(VertexId(v))) continue;
    std::vector<VertexId> loop;
    for (VertexId u(v); !visited[u.index()]; u = to_vertex(vertex_halfedge(u))) {
      visited[u.index()] = 1;
      loop.push_back(u);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

int SurfaceMesh::euler_characteristic() const {
  return static_cast<int>(num_vertices()) - static_cast<int>(num_edges()) +
         static_cast<int>(num_faces());
}

void SurfaceMesh::set_positions(std::vector<Vec3> positions) {
  if (positions.size() != positions_.size()) {
    throw InvalidArgument("set_positions: got " + std::to_string(positions.size()) +
                          " positions for a mesh with " + std::to_string(positions_.size()) +
                          " vertices");
  }
  positions_ = std::move(positions);
}

namespace {
Vec3 area_vector(const std::vector<Vec3>& p, const FaceIndices& t) {  // 2 * area * unit normal
  return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
}
}  // namespace

Vec3 SurfaceMesh::face_normal(FaceId f) const {
  const Vec3 n = area_vector(positions_, faces_[f.index()]);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

double SurfaceMesh::face_area(FaceId f) const {
  return 0.5 * area_vector(positions_, faces_[f.index()]).norm();
}

Vec3 SurfaceMesh::face_centroid(FaceId f) const {
  const FaceIndices& t = faces_[f.index()];
  return (positions_[t[0]] + positions_[t[1]] + positions_[t[2]]) / 3.0;
}

double SurfaceMesh::total_area() const {
  double sum = 0.0;
  for (std::size_t f = 0; f < num_faces(); ++f) sum += face_area(FaceId(f));
  return sum;
}

double SurfaceMesh::mean_edge_length() const {
  if (num_edges_ == 0) return 0.0;
  double sum = 0.0;
  for (HalfedgeId h : edges()) sum += (position(to_vertex(h)) - position(from_vertex(h))).norm();
  return sum / static_cast<double>(num_edges_);
}

std::vector<Vec3> SurfaceMesh::vertex_normals() const {
  std::vector<Vec3> normals(num_vertices(), Vec3::Zero());
  for (const FaceIndices& t : faces_) {
    const Vec3 n = area_vector(positions_, t);  // area weighting comes with the cross product
    for (std::int32_t v : t) normals[v] += n;
  }
  for (Vec3& n : normals) {
    const double len = n.norm();
    if (len > 0.0) n /= len;
  }
  return normals;
}

Eigen::AlignedBox3d SurfaceMesh::bounds() const {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : positions_) box.extend(p);
  return box;
}

std::vector<FaceId> SurfaceMesh::degenerate_faces(double rel_tol) const {
  const double mean = mean_edge_length();
  const double threshold = rel_tol * mean * mean;
  std::vector<FaceId> out;
  for (std::size_t f = 0; f < num_faces(); ++f) {
    const double area = face_area(FaceId(f));
    // Exactly zero area always counts, so that a mesh collapsed to one point is not "fine"
    // merely because its mean edge length (and thus the threshold) is zero too.
    if (area < threshold || area == 0.0) out.emplace_back(f);
  }
  return out;
}

ValidationReport SurfaceMesh::validate() const {
  ProblemSink sink(/*throw_first=*/false);
  const std::size_t nv = num_vertices();
  const std::size_t nh = num_halfedges();

  if (twin_.size() != nh || vertex_halfedge_.size() != nv) {
    sink.add("adjacency arrays have the wrong size (" + std::to_string(twin_.size()) +
             " twins for " + std::to_string(nh) + " half-edges, " +
             std::to_string(vertex_halfedge_.size()) + " vertex half-edges for " +
             std::to_string(nv) + " vertices)");
    return {sink.take()};
  }

  Adjacency derived;
  const bool faces_ok = derive(positions_, faces_, derived, sink);

  // Stored twins on their own: in range, symmetric, and running the opposite way.
  for (std::size_t h = 0; h < nh; ++h) {
    const HalfedgeId t = twin_[h];
    if (!t.valid()) continue;
    const std::string name = "half-edge " + std::to_string(h);
    if (t.index() >= nh) {
      sink.add(name + " has twin " + std::to_string(t.value) + ", out of range");
    } else if (twin_[t.index()] != HalfedgeId(h)) {
      sink.add(name + " has twin " + std::to_string(t.value) + " whose twin is " +
               std::to_string(twin_[t.index()].value) + " (asymmetric twins)");
    } else if (faces_ok && (from_vertex(t) != to_vertex(HalfedgeId(h)) ||
                            to_vertex(t) != from_vertex(HalfedgeId(h)))) {
      sink.add(name + " and its twin " + std::to_string(t.value) +
               " do not run between the same vertices in opposite directions");
    }
  }
  if (faces_ok) {
    for (std::size_t h = 0; h < nh; ++h) {
      if (twin_[h] != derived.twin[h]) {
        sink.add("half-edge " + std::to_string(h) + " stores twin " +
                 std::to_string(twin_[h].value) + " but the faces give " +
                 std::to_string(derived.twin[h].value));
      }
    }
    if (num_edges_ != derived.num_edges) {
      sink.add("stored edge count " + std::to_string(num_edges_) + " differs from the " +
               std::to_string(derived.num_edges) + " edges of the faces");
    }
    for (std::size_t v = 0; v < nv; ++v) {
      const HalfedgeId h = vertex_halfedge_[v];
      const HalfedgeId expected = derived.vertex_halfedge[v];
      if (!h.valid() || h.index() >= nh || from_vertex(h) != VertexId(v)) {
        sink.add("vertex " + std::to_string(v) + " stores half-edge " + std::to_string(h.value) +
                 ", which does not leave it");
      } else if (expected.valid() &&
                 derived.twin[expected.index()].valid() != derived.twin[h.index()].valid()) {
        sink.add("boundary vertex " + std::to_string(v) +
                 " does not store its outgoing boundary half-edge");
      }
    }
  }

  for (FaceId f : degenerate_faces()) {
    sink.add("face " + std::to_string(f.value) + " is degenerate (area " +
             std::to_string(face_area(f)) + ")");
  }
  return {sink.take()};
}

std::vector<float> SurfaceMesh::flat_positions() const {
  std::vector<float> out;
  out.reserve(3 * num_vertices());
  for (const Vec3& p : positions_) {
    out.push_back(static_cast<float>(p.x()));
    out.push_back(static_cast<float>(p.y()));
    out.push_back(static_cast<float>(p.z()));
  }
  return out;
}

std::vector<std::uint32_t> SurfaceMesh::flat_triangles() const {
  std::vector<std::uint32_t> out;
  out.reserve(3 * num_faces());
  for (const FaceIndices& t : faces_) {
    for (std::int32_t v : t) out.push_back(static_cast<std::uint32_t>(v));
  }
  return out;
}

}  // namespace sutura::engine
