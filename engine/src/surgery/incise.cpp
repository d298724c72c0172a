#include "sutura/engine/surgery/incise.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "mesh_walk.hpp"
#include "surface_path.hpp"
#include "sutura/engine/errors.hpp"
#include "triangle_soup.hpp"

namespace sutura::engine {

IncisionMode parse_incision_mode(const std::string& name) {
  if (name == "snap") return IncisionMode::SnapToEdges;
  if (name == "cut") return IncisionMode::CutThroughFaces;
  throw InvalidArgument("unknown incision mode \"" + name + "\" (expected \"snap\" or \"cut\")");
}

namespace {

using detail::PathEvent;


// Applies the events to a soup: each becomes a soup vertex (existing or inserted).
class EventInserter {
 public:
  explicit EventInserter(detail::TriangleSoup& soup) : soup_(soup) {}

  int insert(const PathEvent& e, int& inserted) {
    switch (e.kind) {
      case PathEvent::Kind::Vertex: return e.vertex.value;
      case PathEvent::Kind::Edge: return insert_on_edge(e, inserted);
      case PathEvent::Kind::Face: {
        Eigen::Vector3d local;
        const int f = soup_.locate(e.face, e.bary, local);
        if (f < 0) throw Error("incise: internal error: curve point not found in its face");
        int kmin = 0;
        for (int k = 1; k < 3; ++k)
          if (local[k] < local[kmin]) kmin = k;
        ++inserted;
        if (local[kmin] > 1e-9) return soup_.split_face(f, local);
        // On an edge of a sub-face (created by an earlier split): split that edge instead.
        const FaceIndices fv = soup_.face(f);
        const int a = fv[(kmin + 1) % 3], b = fv[(kmin + 2) % 3];
        const double t = local[(kmin + 2) % 3] / (local[(kmin + 1) % 3] + local[(kmin + 2) % 3]);
        return soup_.split_edge(a, b, t);
      }
    }
    return -1;
  }

 private:
  int insert_on_edge(const PathEvent& e, int& inserted) {
    const int lo = std::min(e.edge_a.value, e.edge_b.value);
    const int hi = std::max(e.edge_a.value, e.edge_b.value);
    const double t = e.edge_a.value == lo ? e.t : 1.0 - e.t;  // parameter from lo
    auto& points = on_edge_[{lo, hi}];  // sorted (t, soup vertex) already inserted on the edge
    for (const auto& [tp, w] : points)
      if (tp == t) return w;
    double t0 = 0.0, t1 = 1.0;
    int v0 = lo, v1 = hi;
    for (const auto& [tp, w] : points) {
      if (tp < t && tp > t0) t0 = tp, v0 = w;
      if (tp > t && tp < t1) t1 = tp, v1 = w;
    }
    const int w = soup_.split_edge(v0, v1, (t - t0) / (t1 - t0));
    points.emplace_back(t, w);
    ++inserted;
    return w;
  }

  detail::TriangleSoup& soup_;
  std::map<std::pair<int, int>, std::vector<std::pair<double, int>>> on_edge_;
};

// Faces on the left of the cut at path vertex i (those that get the new copy).
std::vector<FaceId> left_wedge(const SurfaceMesh& mesh, const std::vector<VertexId>& c,
                               std::size_t i) {
  std::vector<FaceId> wedge;
  const std::size_t m = c.size() - 1;
  if (i < m) {
    HalfedgeId h = detail::find_halfedge(mesh, c[i], c[i + 1]);
    const HalfedgeId stop = i > 0 ? detail::find_halfedge(mesh, c[i], c[i - 1]) : HalfedgeId();
    while (true) {
      wedge.push_back(SurfaceMesh::face(h));
      const HalfedgeId nh = mesh.twin(SurfaceMesh::prev(h));
      if (!nh.valid() || nh == stop) break;
      h = nh;
    }
  } else {
    // Last vertex on the boundary: from the fan start up to the face right of the last edge.
    HalfedgeId h = mesh.vertex_halfedge(c[i]);
    const HalfedgeId stop = detail::find_halfedge(mesh, c[i], c[i - 1]);
    while (h != stop) {
      wedge.push_back(SurfaceMesh::face(h));
      h = mesh.twin(SurfaceMesh::prev(h));
    }
  }
  return wedge;
}

// Remeshes the band around the traced cut `c` of `refined` (an edit of `mesh` by `maps`), the
// cut kept as a constrained polyline; updates all three to the remeshed mesh.
void remesh_band(const SurfaceMesh& mesh, const std::vector<FaceId>& host_faces,
                 const IncisionParams& params, SurfaceMesh& refined, EditMaps& maps,
                 std::vector<VertexId>& c, IncisionResult& result) {
  const double L = params.target_edge_length > 0.0 ? params.target_edge_length
                                                   : mean_edge_length(mesh, host_faces);
  std::vector<Vec3> trace;
  for (const VertexId v : c) trace.push_back(refined.position(v));
  RemeshParams rp;
  rp.target_edge_length = L;
  rp.region = faces_near_polyline(refined, trace, params.band_width * L);
  rp.grading = params.grading;
  if (params.grading > 1.0) rp.grading_curve = trace;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) rp.constrained_edges.emplace_back(c[i], c[i + 1]);
  if (!params.constrained_vertices.empty()) {
    rp.constrained_vertices.assign(refined.num_vertices(), false);
    for (std::size_t v = 0; v < refined.num_vertices(); ++v) {
      const VertexOrigin& o = maps.vertices[v];
      if (o.parents.size() == 1 && o.parents[0].index() < params.constrained_vertices.size())
        rp.constrained_vertices[v] = params.constrained_vertices[o.parents[0].index()];
    }
  }
  RemeshResult r = remesh(refined, rp);
  // The cut again, as the chain of constrained edges from the (kept) first vertex to the last.
  std::vector<VertexId> image(refined.num_vertices());
  for (std::size_t v = 0; v < r.maps.vertices.size(); ++v) {
    const VertexOrigin& o = r.maps.vertices[v];
    if (o.kind == VertexOriginKind::Copy) image[o.parents[0].index()] = VertexId(v);
  }
  const VertexId first = image[c.front().index()], last = image[c.back().index()];
  if (!first.valid() || !last.valid())
    throw Error("incise: internal error: the remesh moved an end of the cut");
  std::vector<std::vector<VertexId>> along(r.mesh.num_vertices());
  for (const auto& [a, b] : r.constrained_edges) {
    along[a.index()].push_back(b);
    along[b.index()].push_back(a);
  }
  std::vector<VertexId> chain{first};
  while (chain.back() != last) {
    const VertexId at = chain.back();
    VertexId next;
    for (const VertexId w : along[at.index()])
      if (chain.size() < 2 || w != chain[chain.size() - 2]) next = w;
    if (!next.valid() || along[at.index()].size() > 2 || chain.size() > r.mesh.num_vertices())
      throw Error("incise: internal error: the remeshed cut is not one polyline");
    chain.push_back(next);
  }
  maps = compose(maps, r.maps);
  refined = std::move(r.mesh);
  c = std::move(chain);
  result.remeshed = true;
  result.band_before = r.before;
  result.band_after = r.after;
}

}  // namespace

IncisionResult incise(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                      const IncisionParams& params) {
  if (points.size() < 2)
    throw InvalidArgument("an incision needs at least 2 points, got " +
                          std::to_string(points.size()));
  if (!(params.sliver_fraction > 0.0 && params.sliver_fraction < 0.5))
    throw InvalidArgument("sliver_fraction must be in (0, 0.5)");
  if (!(params.max_distance > 0.0)) throw InvalidArgument("max_distance must be > 0");
  if (!(params.target_edge_length >= 0.0)) throw InvalidArgument("target_edge_length must be >= 0");
  if (!(params.band_width > 0.0 && params.band_width <= 20.0))
    throw InvalidArgument("band_width must be in (0, 20] target edge lengths");
  if (!params.constrained_vertices.empty() && params.constrained_vertices.size() != mesh.num_vertices())
    throw InvalidArgument("constrained_vertices: one flag per vertex");

  std::vector<SurfacePoint> sp;
  std::vector<PathEvent> pe;
  for (std::size_t i = 0; i < points.size(); ++i) {
    sp.push_back(closest_surface_point(mesh, points[i]));
    if (sp.back().distance > params.max_distance)
      throw InvalidArgument("incision point " + std::to_string(i + 1) + " " +
                            detail::point_text(points[i]) + " is off the surface: " +
                            std::to_string(sp.back().distance) + " mm away (limit " +
                            std::to_string(params.max_distance) + " mm)");
    pe.push_back(detail::point_event(mesh, sp.back(), params.sliver_fraction));
    if (params.mode == IncisionMode::SnapToEdges) {
      // Nearest corner of the face.
      const auto fv = mesh.face_vertices(sp.back().face);
      int k = 0;
      for (int j = 1; j < 3; ++j)
        if (sp.back().bary[j] > sp.back().bary[k]) k = j;
      pe.back() = PathEvent{};
      pe.back().vertex = fv[k];
    }
  }

  IncisionResult result;
  detail::TriangleSoup soup(mesh);
  EventInserter inserter(soup);
  std::vector<int> path;
  auto append = [&](int v) {
    if (path.empty() || path.back() != v) path.push_back(v);
  };
  int snapped = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i > 0) {
      if (params.mode == IncisionMode::SnapToEdges) {
        const auto p = detail::shortest_edge_path(mesh, pe[i - 1].vertex, pe[i].vertex);
        for (std::size_t j = 1; j + 1 < p.size(); ++j) append(p[j].value);
      } else if (!pe[i - 1].same_as(pe[i])) {
        for (const PathEvent& e : detail::trace_between(mesh, sp[i - 1], pe[i - 1], sp[i], pe[i],
                                                        params.sliver_fraction, int(i))) {
          if (e.kind == PathEvent::Kind::Vertex) ++snapped;
          append(inserter.insert(e, result.inserted_vertices));
        }
      }
    }
    append(inserter.insert(pe[i], result.inserted_vertices));
  }
  if (path.size() < 2)
    throw InvalidArgument("the incision is shorter than one mesh edge: its points all snap to "
                          "the vertex at " + detail::point_text(soup.position(path.front())));
  {
    std::set<int> seen;
    for (const int v : path)
      if (!seen.insert(v).second)
        throw InvalidArgument("the incision crosses itself at " + detail::point_text(soup.position(v)));
  }
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
    if (!soup.has_edge(path[i], path[i + 1]))
      throw Error("incise: internal error: consecutive cut vertices are not adjacent");
  // A slit of one edge would re-close (both lips would be the same edge): split it.
  if (path.size() == 2) {
    path.insert(path.begin() + 1, soup.split_edge(path[0], path[1], 0.5));
    ++result.inserted_vertices;
  }

  EditMaps refine_maps;
  SurfaceMesh refined = std::move(soup).build(refine_maps);
  std::vector<VertexId> c;
  for (const int v : path) c.emplace_back(v);
  std::size_t m = c.size() - 1;
  for (std::size_t i = 0; i < m; ++i)
    if (!detail::find_halfedge(refined, c[i], c[i + 1]).valid() ||
        !detail::find_halfedge(refined, c[i + 1], c[i]).valid())
      throw InvalidArgument("the incision runs along the open boundary near " +
                            detail::point_text(refined.position(c[i])));
  for (std::size_t i = 1; i < m; ++i)
    if (refined.is_boundary(c[i]))
      throw InvalidArgument("the incision touches the open boundary at " +
                            detail::point_text(refined.position(c[i])) +
                            " between its ends; end it there or keep it away from the boundary");

  if (params.mode == IncisionMode::CutThroughFaces && params.remesh) {
    std::vector<FaceId> host;
    for (const SurfacePoint& p : sp) host.push_back(p.face);
    remesh_band(mesh, host, params, refined, refine_maps, c, result);
    m = c.size() - 1;
  }

  // Duplicate path vertices: interior path vertices always, ends only on the boundary (an
  // interior end stays shared by both lips: the end of a slit).
  std::vector<FaceIndices> faces = refined.faces();
  std::vector<Vec3> positions = refined.positions();
  EditMaps cut_maps = EditMaps::identity(refined.num_vertices(), refined.num_faces());
  result.starts_on_boundary = refined.is_boundary(c.front());
  result.ends_on_boundary = refined.is_boundary(c.back());
  result.right = c;
  result.left = c;
  for (std::size_t i = 0; i <= m; ++i) {
    if ((i == 0 || i == m) && !refined.is_boundary(c[i])) continue;
    const VertexId copy(positions.size());
    positions.push_back(refined.position(c[i]));
    cut_maps.vertices.push_back(VertexOrigin{VertexOriginKind::Copy, {c[i]}, {1.0}});
    for (const FaceId f : left_wedge(refined, c, i))
      for (auto& corner : faces[f.index()])
        if (corner == c[i].value) corner = copy.value;
    result.left[i] = copy;
  }
  result.mesh = SurfaceMesh(std::move(positions), std::move(faces));
  result.maps = compose(refine_maps, cut_maps);
  result.snapped_points = snapped;
  for (std::size_t i = 0; i < m; ++i)
    result.length += (result.mesh.position(c[i + 1]) - result.mesh.position(c[i])).norm();
  return result;
}

}  // namespace sutura::engine
