#include "sutura/engine/surgery/flat_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

// The rest triangle of one element in its own frame: corner 0 at the origin, corner 1 on +x,
// corner 2 above (the element's own orientation, counter-clockwise).
std::array<Vec2, 3> local_triangle(const ElementRest& e) {
  const Vec3 u = e.X[1] - e.X[0], w = e.X[2] - e.X[0];
  const double lu = u.norm();
  const Vec3 ex = u / lu;
  const double wx = w.dot(ex);
  const double wy = (w - wx * ex).norm();
  return {Vec2::Zero(), Vec2(lu, 0.0), Vec2(wx, wy)};
}

// Rotation by the angle from direction a to direction b (both non-zero).
Eigen::Matrix2d turn(const Vec2& a, const Vec2& b) {
  const double angle = std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x());
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

}  // namespace

double polygon_area(const std::vector<Vec2>& p) {
  double twice = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& a = p[i];
    const Vec2& b = p[(i + 1) % p.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

double polygon_perimeter(const std::vector<Vec2>& p) {
  double length = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) length += (p[(i + 1) % p.size()] - p[i]).norm();
  return length;
}

FlatLayout unfold_rest(const SurfaceMesh& mesh, const RestState& rest,
                       const std::vector<FaceId>& region) {
  const std::size_t nf = mesh.num_faces();
  if (rest.elements.size() != nf)
    throw InvalidArgument("unfold_rest: the rest state has " + std::to_string(rest.elements.size()) +
                          " elements for " + std::to_string(nf) + " faces");
  std::vector<bool> in(nf, false);
  std::vector<FaceId> faces;
  for (FaceId f : region) {
    if (!f.valid() || f.index() >= nf)
      throw InvalidArgument("unfold_rest: face " + std::to_string(f.value) + " is out of range");
    if (!in[f.index()]) faces.push_back(f);
    in[f.index()] = true;
  }
  if (faces.empty()) throw InvalidArgument("unfold_rest: the region has no faces");
  std::sort(faces.begin(), faces.end());

  std::vector<std::array<Vec2, 3>> local(nf);
  double area = 0.0;
  for (FaceId f : faces) {
    const ElementRest& e = rest.elements[f.index()];
    const double a = 0.5 * (e.X[1] - e.X[0]).cross(e.X[2] - e.X[0]).norm();
    const double scale = std::max({(e.X[1] - e.X[0]).squaredNorm(), (e.X[2] - e.X[1]).squaredNorm(),
                                   (e.X[0] - e.X[2]).squaredNorm()});
    if (!(a > 1e-12 * scale) || !std::isfinite(a))
      throw InvalidArgument("unfold_rest: face " + std::to_string(f.value) +
                            " has a degenerate rest triangle");
    local[f.index()] = local_triangle(e);
    area += a;
  }

  // Breadth first from the lowest face; each face placed by the edge it was reached across.
  std::vector<std::array<Vec2, 3>> placed(nf);
  std::vector<bool> done(nf, false);
  std::vector<FaceId> queue{faces.front()};
  placed[faces.front().index()] = local[faces.front().index()];
  done[faces.front().index()] = true;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const FaceId f = queue[head];
    for (int k = 0; k < 3; ++k) {
      const HalfedgeId t = mesh.twin(SurfaceMesh::halfedge(f, k));
      if (!t.valid()) continue;
      const FaceId g = SurfaceMesh::face(t);
      if (!in[g.index()] || done[g.index()]) continue;
      // The shared edge runs corner k -> k+1 in f and corner j -> j+1 in g, the other way.
      const int j = static_cast<int>(t.value % 3);
      const Vec2& pa = placed[f.index()][k];
      const Vec2& pb = placed[f.index()][(k + 1) % 3];
      const Vec2& la = local[g.index()][(j + 1) % 3];  // g's copy of f's corner k
      const Vec2& lb = local[g.index()][j];
      const Eigen::Matrix2d R = turn(lb - la, pb - pa);
      const Vec2 shift = 0.5 * (pa + pb) - R * (0.5 * (la + lb));
      for (int c = 0; c < 3; ++c) placed[g.index()][c] = R * local[g.index()][c] + shift;
      done[g.index()] = true;
      queue.push_back(g);
    }
  }
  if (queue.size() != faces.size())
    throw InvalidArgument("unfold_rest: the region is not edge-connected (" +
                          std::to_string(queue.size()) + " of its " + std::to_string(faces.size()) +
                          " faces reached from face " + std::to_string(faces.front().value) + ")");

  FlatLayout out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.position.assign(mesh.num_vertices(), Vec2(nan, nan));
  std::vector<bool> set(mesh.num_vertices(), false);
  for (FaceId f : queue) {
    const auto fv = mesh.face_vertices(f);
    for (int c = 0; c < 3; ++c) {
      const std::size_t v = fv[c].index();
      if (!set[v]) {
        out.position[v] = placed[f.index()][c];
        set[v] = true;
      } else {
        out.max_gap_mm = std::max(out.max_gap_mm, (placed[f.index()][c] - out.position[v]).norm());
      }
    }
  }
  out.rest_area_mm2 = area;

  // Boundary of the region: half-edges whose other side is outside it.
  std::map<std::int32_t, HalfedgeId> leaving;  // from-vertex -> boundary half-edge
  std::size_t count = 0;
  for (FaceId f : faces)
    for (int k = 0; k < 3; ++k) {
      const HalfedgeId h = SurfaceMesh::halfedge(f, k);
      const HalfedgeId t = mesh.twin(h);
      if (t.valid() && in[SurfaceMesh::face(t).index()]) continue;
      const VertexId from = mesh.from_vertex(h);
      if (!leaving.emplace(from.value, h).second)
        throw InvalidArgument("unfold_rest: the region's boundary passes vertex " +
                              std::to_string(from.value) + " twice (it is not a disk)");
      ++count;
    }
  if (count == 0) throw InvalidArgument("unfold_rest: the region has no boundary (a closed surface)");
  HalfedgeId h = leaving.begin()->second;
  for (std::size_t step = 0; step < count; ++step) {
    out.outline.push_back(mesh.from_vertex(h));
    const ElementRest& e = rest.elements[SurfaceMesh::face(h).index()];
    const int k = static_cast<int>(h.value % 3);
    out.rest_perimeter_mm += (e.X[(k + 1) % 3] - e.X[k]).norm();
    const auto it = leaving.find(mesh.to_vertex(h).value);
    if (it == leaving.end()) break;  // cannot happen on a manifold mesh; the check below names it
    h = it->second;
    if (mesh.from_vertex(h) == out.outline.front()) break;
  }
  if (out.outline.size() != count)
    throw InvalidArgument("unfold_rest: the region's boundary is " + std::string("not one loop (") +
                          std::to_string(out.outline.size()) + " of its " + std::to_string(count) +
                          " edges in the loop through vertex " +
                          std::to_string(out.outline.front().value) + "); a patch is a disk");
  return out;
}

}  // namespace sutura::engine
