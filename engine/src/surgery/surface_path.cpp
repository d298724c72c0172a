#include "surface_path.hpp"

#include <algorithm>
#include <limits>
#include <queue>
#include <sstream>

#include "mesh_walk.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

bool PathEvent::same_as(const PathEvent& o) const {
  if (kind != o.kind) return false;
  switch (kind) {
    case Kind::Vertex: return vertex == o.vertex;
    case Kind::Edge:
      return ((edge_a == o.edge_a && edge_b == o.edge_b && t == o.t) ||
              (edge_a == o.edge_b && edge_b == o.edge_a && t == 1.0 - o.t));
    case Kind::Face: return face == o.face && bary == o.bary;
  }
  return false;
}

PathEvent point_event(const SurfaceMesh& mesh, const SurfacePoint& p, double snap) {
  const auto fv = mesh.face_vertices(p.face);
  PathEvent e;
  int kmax = 0, kmin = 0;
  for (int k = 1; k < 3; ++k) {
    if (p.bary[k] > p.bary[kmax]) kmax = k;
    if (p.bary[k] < p.bary[kmin]) kmin = k;
  }
  if (p.bary[kmax] > 1.0 - snap) {
    e.kind = PathEvent::Kind::Vertex;
    e.vertex = fv[kmax];
    return e;
  }
  if (p.bary[kmin] < snap) {
    // Near the edge opposite corner kmin: project onto it.
    const int j = (kmin + 1) % 3, k = (kmin + 2) % 3;
    const double t = p.bary[k] / (p.bary[j] + p.bary[k]);
    if (t < snap || t > 1.0 - snap) {
      e.kind = PathEvent::Kind::Vertex;
      e.vertex = t < 0.5 ? fv[j] : fv[k];
      return e;
    }
    e.kind = PathEvent::Kind::Edge;
    e.edge_a = fv[j];
    e.edge_b = fv[k];
    e.t = t;
    return e;
  }
  e.kind = PathEvent::Kind::Face;
  e.face = p.face;
  e.bary = p.bary;
  return e;
}

std::vector<FaceId> event_faces(const SurfaceMesh& mesh, const PathEvent& e) {
  switch (e.kind) {
    case PathEvent::Kind::Vertex: return mesh.vertex_faces(e.vertex);
    case PathEvent::Kind::Edge: {
      std::vector<FaceId> out;
      for (const FaceId f : mesh.vertex_faces(e.edge_a)) {
        const auto v = mesh.face_vertices(f);
        if (v[0] == e.edge_b || v[1] == e.edge_b || v[2] == e.edge_b) out.push_back(f);
      }
      return out;
    }
    case PathEvent::Kind::Face: return {e.face};
  }
  return {};
}

Eigen::Vector3d event_bary(const SurfaceMesh& mesh, const PathEvent& e, FaceId f) {
  const auto fv = mesh.face_vertices(f);
  auto corner = [&](VertexId v) {
    for (int k = 0; k < 3; ++k)
      if (fv[k] == v) return k;
    throw Error("incise: internal error: a path event is not on the face it is placed in");
  };
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  switch (e.kind) {
    case PathEvent::Kind::Vertex: b[corner(e.vertex)] = 1.0; break;
    case PathEvent::Kind::Edge:
      b[corner(e.edge_a)] = 1.0 - e.t;
      b[corner(e.edge_b)] = e.t;
      break;
    case PathEvent::Kind::Face:
      if (e.face != f)
        throw Error("incise: internal error: a path event is not on the face it is placed in");
      b = e.bary;
      break;
  }
  return b;
}

namespace {

Vec3 event_position(const SurfaceMesh& mesh, const PathEvent& e) {
  switch (e.kind) {
    case PathEvent::Kind::Vertex: return mesh.position(e.vertex);
    case PathEvent::Kind::Edge:
      return (1.0 - e.t) * mesh.position(e.edge_a) + e.t * mesh.position(e.edge_b);
    case PathEvent::Kind::Face: {
      const auto v = mesh.face_vertices(e.face);
      return e.bary[0] * mesh.position(v[0]) + e.bary[1] * mesh.position(v[1]) +
             e.bary[2] * mesh.position(v[2]);
    }
  }
  return Vec3::Zero();
}


}  // namespace

std::vector<PathEvent> trace_between(const SurfaceMesh& mesh, const SurfacePoint& p,
                                     const PathEvent& pe, const SurfacePoint& q,
                                     const PathEvent& qe, double snap, int segment) {
  const std::string where = "incision segment " + std::to_string(segment) + " (" +
                            point_text(p.position) + " to " + point_text(q.position) + ")";
  const Vec3 d = q.position - p.position;
  const double len = d.norm();
  Vec3 n = mesh.face_normal(p.face) + mesh.face_normal(q.face);
  if (n.squaredNorm() < 1e-12) n = mesh.face_normal(p.face);
  // The cutting plane contains p, q and the mean normal: its trace on the surface is the
  // "straight" path a surgeon draws between the two points.
  Vec3 m = d.cross(n);
  if (m.norm() < 1e-9 * len * std::max(1.0, n.norm()))
    throw InvalidArgument(where + ": the segment is parallel to the surface normal; add a point "
                                  "in between");
  m.normalize();
  const Vec3 dhat = d / len;
  // Signed distance from the plane; within rounding (1e-12 rad seen from p) of it, on it, so
  // that a trace through a vertex (along a mesh line, say) finds the vertex as a crossing.
  auto side = [&](const Vec3& x) {
    const double s = m.dot(x - p.position);
    return std::abs(s) <= 1e-12 * (x - p.position).norm() ? 0.0 : s;
  };
  auto progress = [&](const Vec3& x) { return dhat.dot(x - p.position); };

  const std::vector<FaceId> goal = event_faces(mesh, qe);
  auto reached = [&](const std::vector<FaceId>& faces) {
    for (const FaceId f : faces)
      if (std::find(goal.begin(), goal.end(), f) != goal.end()) return true;
    return false;
  };

  std::vector<PathEvent> events;
  PathEvent cur = pe;
  std::vector<FaceId> faces = event_faces(mesh, cur);
  double prog = progress(event_position(mesh, cur));
  const double eps = 1e-12 * len;  // rounding only: the edge or vertex stood on is skipped anyway
  const std::size_t max_steps = 4 * mesh.num_faces() + 16;
  for (std::size_t step = 0; !reached(faces); ++step) {
    if (step > max_steps) throw InvalidArgument(where + ": the path could not be traced");
    // Nearest forward crossing of the plane with an edge of the current faces (excluding the
    // edge or vertex we stand on).
    double best_prog = std::numeric_limits<double>::infinity();
    PathEvent next;
    bool found = false;
    for (const FaceId f : faces) {
      const auto fv = mesh.face_vertices(f);
      for (int k = 0; k < 3; ++k) {
        const VertexId a = fv[k], b = fv[(k + 1) % 3];
        if (cur.kind == PathEvent::Kind::Vertex && (a == cur.vertex || b == cur.vertex)) continue;
        if (cur.kind == PathEvent::Kind::Edge &&
            ((a == cur.edge_a && b == cur.edge_b) || (a == cur.edge_b && b == cur.edge_a)))
          continue;
        const double sa = side(mesh.position(a)), sb = side(mesh.position(b));
        if ((sa > 0 && sb > 0) || (sa < 0 && sb < 0) || (sa == 0 && sb == 0)) continue;
        const double t = sa / (sa - sb);
        const Vec3 x = (1.0 - t) * mesh.position(a) + t * mesh.position(b);
        const double px = progress(x);
        if (px <= prog + eps || px >= best_prog) continue;
        best_prog = px;
        found = true;
        if (t < snap || t > 1.0 - snap) {
          next.kind = PathEvent::Kind::Vertex;
          next.vertex = t < 0.5 ? a : b;
        } else {
          next.kind = PathEvent::Kind::Edge;
          next.edge_a = a;
          next.edge_b = b;
          next.t = t;
        }
      }
    }
    if (!found)
      throw InvalidArgument(where + ": the path leaves the surface (it would cross an open "
                                    "boundary or fold back); add points along the intended line");
    if (next.kind == PathEvent::Kind::Edge) {
      const auto ef = event_faces(mesh, next);
      if (ef.size() < 2 && !reached(ef))
        throw InvalidArgument(where + ": the path crosses an open boundary at " +
                              point_text(event_position(mesh, next)));
    }
    // A snapped vertex may lie behind the exact crossing; progress is measured at the event.
    prog = std::max(prog + eps, progress(event_position(mesh, next)));
    events.push_back(next);
    cur = next;
    faces = event_faces(mesh, cur);
  }
  return events;
}

std::vector<VertexId> shortest_edge_path(const SurfaceMesh& mesh, VertexId a, VertexId b) {
  const std::size_t n = mesh.num_vertices();
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<std::int32_t> prev(n, -1);
  using Item = std::pair<double, std::int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[a.index()] = 0.0;
  queue.emplace(0.0, a.value);
  while (!queue.empty()) {
    const auto [du, u] = queue.top();
    queue.pop();
    if (du > dist[u]) continue;
    if (u == b.value) break;
    for (const VertexId v : mesh.vertex_neighbors(VertexId(u))) {
      const double dv = du + (mesh.position(v) - mesh.position(VertexId(u))).norm();
      // Ties broken by vertex id so that the path is deterministic.
      if (dv < dist[v.index()] || (dv == dist[v.index()] && u < prev[v.index()])) {
        dist[v.index()] = dv;
        prev[v.index()] = u;
        queue.emplace(dv, v.value);
      }
    }
  }
  if (!std::isfinite(dist[b.index()]))
    throw InvalidArgument("the incision points lie on parts of the mesh that are not connected");
  std::vector<VertexId> path;
  for (std::int32_t v = b.value; v != -1; v = prev[v]) {
    path.emplace_back(v);
    if (v == a.value) break;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace sutura::engine::detail
