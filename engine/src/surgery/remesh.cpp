#include "sutura/engine/surgery/remesh.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <string>

#include "cgal_remesh.hpp"
#include "mesh_walk.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

std::vector<FaceId> all_faces(const SurfaceMesh& mesh) {
  std::vector<FaceId> f(mesh.num_faces());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = FaceId(i);
  return f;
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

// Barycentric coordinates of p's projection onto the plane of (a, b, c), not clamped.
Eigen::Vector3d plane_barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double r1 = d.dot(e1), r2 = d.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double u = (d22 * r1 - d12 * r2) / det, v = (d11 * r2 - d12 * r1) / det;
  return {1.0 - u - v, u, v};
}

}  // namespace

namespace {

// Quality of triangles given by `corners(i, p)` (fills p[3] for triangle i), i < n; the
// worst face is FaceId(i) of the smallest angle (the first of equals).
template <class Corners>
MeshQuality triangle_quality(std::size_t n, Corners&& corners) {
  MeshQuality q;
  q.faces = n;
  if (n == 0) return q;
  std::vector<double> smallest;
  smallest.reserve(n);
  q.min_edge = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p[3];
    corners(i, p);
    for (int k = 0; k < 3; ++k) {
      const double edge = (p[(k + 1) % 3] - p[k]).norm();
      q.min_edge = std::min(q.min_edge, edge);
      q.max_edge = std::max(q.max_edge, edge);
    }
    smallest.push_back(smallest_angle_deg(p[0], p[1], p[2]));
    if (i == 0 || smallest.back() < smallest[q.worst_face.index()]) q.worst_face = FaceId(i);
  }
  std::sort(smallest.begin(), smallest.end());
  q.min_angle_deg = smallest.front();
  q.p5_angle_deg = smallest[static_cast<std::size_t>(0.05 * double(smallest.size() - 1))];
  return q;
}

}  // namespace

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::min({angle_deg(b - a, c - a), angle_deg(c - b, a - b), angle_deg(a - c, b - c)});
}

double vertex_angle_sum_deg(const SurfaceMesh& mesh, VertexId v) {
  double sum = 0.0;
  for (const FaceId f : mesh.vertex_faces(v)) {
    const auto c = mesh.face_vertices(f);
    const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    const Vec3 p = mesh.position(c[std::size_t(k)]);
    sum += angle_deg(mesh.position(c[std::size_t((k + 1) % 3)]) - p, mesh.position(c[std::size_t((k + 2) % 3)]) - p);
  }
  return sum;
}

MeshQuality mesh_quality(const SurfaceMesh& mesh, const std::vector<FaceId>& faces) {
  const std::vector<FaceId> set = faces.empty() ? all_faces(mesh) : faces;
  MeshQuality q = triangle_quality(set.size(), [&](std::size_t i, Vec3* p) {
    const auto v = mesh.face_vertices(set[i]);
    for (int k = 0; k < 3; ++k) p[k] = mesh.position(v[k]);
  });
  if (q.worst_face.valid()) q.worst_face = set[q.worst_face.index()];
  return q;
}

MeshQuality rest_quality(const RestState& rest) {
  return triangle_quality(rest.elements.size(), [&](std::size_t i, Vec3* p) {
    for (int k = 0; k < 3; ++k) p[k] = rest.elements[i].X[k];
  });
}

double mean_edge_length(const SurfaceMesh& mesh, const std::vector<FaceId>& faces) {
  const std::vector<FaceId> set = faces.empty() ? all_faces(mesh) : faces;
  double sum = 0.0;
  for (const FaceId f : set) {
    const auto v = mesh.face_vertices(f);
    for (int k = 0; k < 3; ++k) sum += (mesh.position(v[(k + 1) % 3]) - mesh.position(v[k])).norm();
  }
  return set.empty() ? 0.0 : sum / (3.0 * double(set.size()));
}

std::vector<FaceId> faces_near_polyline(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                                        double radius) {
  std::vector<FaceId> out;
  if (points.empty()) return out;
  std::vector<bool> near(mesh.num_vertices(), false);
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.position(VertexId(v));
    if (points.size() == 1) {
      near[v] = (p - points[0]).norm() <= radius;
      continue;
    }
    for (std::size_t i = 0; i + 1 < points.size() && !near[v]; ++i)
      near[v] = segment_distance(p, points[i], points[i + 1]) <= radius;
  }
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto fv = mesh.face_vertices(FaceId(f));
    if (near[fv[0].index()] || near[fv[1].index()] || near[fv[2].index()]) out.emplace_back(f);
  }
  return out;
}

std::vector<FaceId> faces_near_small_angles(const SurfaceMesh& mesh, double below_deg,
                                            double radius) {
  if (!(below_deg > 0.0 && below_deg <= 60.0))
    throw InvalidArgument("below_angle must be in (0, 60] degrees, got " + std::to_string(below_deg));
  if (!(std::isfinite(radius) && radius >= 0.0))
    throw InvalidArgument("radius must be a finite length >= 0 mm, got " + std::to_string(radius));
  const std::size_t nv = mesh.num_vertices(), nf = mesh.num_faces();
  // Edge-path distance from the small-angled faces' corners (multi-source Dijkstra).
  std::vector<std::vector<std::pair<std::size_t, double>>> adjacent(nv);
  std::vector<double> distance(nv, std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto v = mesh.face_vertices(FaceId(f));
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = v[k].index(), b = v[(k + 1) % 3].index();
      const double l = (mesh.position(v[k]) - mesh.position(v[(k + 1) % 3])).norm();
      adjacent[a].emplace_back(b, l);
      adjacent[b].emplace_back(a, l);
    }
    if (smallest_angle_deg(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2])) < below_deg)
      for (int k = 0; k < 3; ++k)
        if (distance[v[k].index()] > 0.0) {
          distance[v[k].index()] = 0.0;
          queue.emplace(0.0, v[k].index());
        }
  }
  while (!queue.empty()) {
    const auto [d, a] = queue.top();
    queue.pop();
    if (d > distance[a]) continue;
    for (const auto& [b, l] : adjacent[a])
      if (d + l <= radius && d + l < distance[b]) {
        distance[b] = d + l;
        queue.emplace(d + l, b);
      }
  }
  std::vector<FaceId> out;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto v = mesh.face_vertices(FaceId(f));
    if (std::isfinite(distance[v[0].index()]) || std::isfinite(distance[v[1].index()]) ||
        std::isfinite(distance[v[2].index()]))
      out.emplace_back(f);
  }
  return out;
}

RemeshResult remesh(const SurfaceMesh& mesh, const RemeshParams& params) {
  const std::size_t nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<bool> region(nf, !params.region.has_value());
  for (const FaceId f : params.region.value_or(std::vector<FaceId>{})) {
    if (!f.valid() || f.index() >= nf)
      throw InvalidArgument("region: face " + std::to_string(f.value) + " is not a face of the mesh (" +
                            std::to_string(nf) + " faces)");
    region[f.index()] = true;
  }
  std::vector<FaceId> region_faces;
  for (std::size_t f = 0; f < nf; ++f)
    if (region[f]) region_faces.emplace_back(f);
  if (region_faces.empty()) throw InvalidArgument("region: no faces to remesh");
  const double L = params.target_edge_length;
  if (!(std::isfinite(L) && L > 0.0))
    throw InvalidArgument("target_edge_length must be a finite length > 0 mm, got " +
                          std::to_string(L));
  const double host = mean_edge_length(mesh, region_faces);  // the region's own spacing
  {
    Eigen::AlignedBox3d box;
    for (const FaceId f : region_faces)
      for (const VertexId v : mesh.face_vertices(f)) box.extend(mesh.position(v));
    const double extent = box.diagonal().norm();
    if (L > extent)
      throw InvalidArgument("target_edge_length " + std::to_string(L) +
                            " mm is larger than the region (" + std::to_string(extent) +
                            " mm across)");
    // Bound the work by the input: a target far below the region's spacing would make
    // (extent / L)^2 faces.
    const double growth = (host / L) * (host / L) * double(region_faces.size());
    if (growth > 2.0e6)
      throw InvalidArgument("target_edge_length " + std::to_string(L) +
                            " mm would make about " + std::to_string(static_cast<long long>(growth)) +
                            " faces from " + std::to_string(region_faces.size()) +
                            " (limit 2000000)");
  }
  if (!(std::isfinite(params.grading) && params.grading >= 1.0 && params.grading <= 10.0))
    throw InvalidArgument("grading must be in [1, 10], got " + std::to_string(params.grading));
  if (!(params.passes.raise_angles_below_deg >= 0.0 && params.passes.raise_angles_below_deg <= 40.0))
    throw InvalidArgument("raise_angles_below_deg must be in [0, 40], got " +
                          std::to_string(params.passes.raise_angles_below_deg));
  if (params.passes.iterations < 1 || params.passes.iterations > 100)
    throw InvalidArgument("iterations must be in [1, 100], got " +
                          std::to_string(params.passes.iterations));
  if (!params.constrained_vertices.empty() && params.constrained_vertices.size() != nv)
    throw InvalidArgument("constrained_vertices: " + std::to_string(params.constrained_vertices.size()) +
                          " flags for " + std::to_string(nv) + " vertices");

  if (!params.removed_boundary_vertices.empty() && params.removed_boundary_vertices.size() != nv)
    throw InvalidArgument("removed_boundary_vertices: " +
                          std::to_string(params.removed_boundary_vertices.size()) + " flags for " +
                          std::to_string(nv) + " vertices");

  detail::CgalRemeshInput in;
  in.removed_boundary_vertices = params.removed_boundary_vertices;
  in.removed_boundary_vertices.resize(nv, false);
  in.positions = &mesh.positions();
  in.faces = &mesh.faces();
  in.region = region;
  in.iterations = params.passes.iterations;
  in.raise_angles_below_deg = params.passes.raise_angles_below_deg;
  in.rim_faces_in_region = params.passes.rim_faces_in_region;
  in.constrained_vertices = params.constrained_vertices;
  in.constrained_vertices.resize(nv, false);
  // Ends and junctions of constrained polylines stay put: a vertex with other than two
  // constrained edges (open boundary edges count).
  std::vector<int> degree(nv, 0);
  std::vector<std::pair<VertexId, VertexId>> constrained;
  for (const auto& [a, b] : params.constrained_edges)
    constrained.push_back(a.value < b.value ? std::pair{a, b} : std::pair{b, a});
  std::sort(constrained.begin(), constrained.end());
  constrained.erase(std::unique(constrained.begin(), constrained.end()), constrained.end());
  for (const auto& [a, b] : constrained) {
    if (!a.valid() || !b.valid() || a.index() >= nv || b.index() >= nv ||
        (!detail::find_halfedge(mesh, a, b).valid() && !detail::find_halfedge(mesh, b, a).valid()))
      throw InvalidArgument("constrained_edges: " + std::to_string(a.value) + "-" +
                            std::to_string(b.value) + " is not an edge of the mesh");
    in.constrained_edges.emplace_back(a.value, b.value);
  }
  // Degrees over the union of the constrained and the open boundary edges (a constrained
  // edge on the boundary counts once).
  for (std::size_t h = 0; h < 3 * nf; ++h)
    if (!mesh.twin(HalfedgeId(h)).valid()) {
      const auto fv = mesh.face_vertices(SurfaceMesh::face(HalfedgeId(h)));
      const int k = static_cast<int>(h % 3);
      const VertexId a = fv[k], b = fv[(k + 1) % 3];
      constrained.push_back(a.value < b.value ? std::pair{a, b} : std::pair{b, a});
    }
  std::sort(constrained.begin(), constrained.end());
  constrained.erase(std::unique(constrained.begin(), constrained.end()), constrained.end());
  for (const auto& [a, b] : constrained) {
    ++degree[a.index()];
    ++degree[b.index()];
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (degree[v] != 0 && degree[v] != 2) in.constrained_vertices[v] = true;

  // Bands: the outermost first. Band i has edge length L g^i (L / g^i where the region is
  // finer than L: a seam at a patch's spacing in a finer host) and reaches twice that beyond
  // band i-1, until the length reaches the region's own.
  const double step = host > L ? params.grading : 1.0 / params.grading;
  if (params.grading > 1.0 && !params.grading_curve.empty() && std::abs(host - L) > 1e-3 * L) {
    std::vector<detail::RemeshBand> bands;
    double length = L, reach = 0.0;
    while ((host > L ? length < host : length > host) && bands.size() < 32) {
      reach += 2.0 * length;
      bands.push_back({length, reach});
      length *= step;
    }
    in.bands.assign(bands.rbegin(), bands.rend());
    in.band_curve = params.grading_curve;
  } else {
    in.bands.push_back({L, -1.0});
  }

  const detail::CgalRemeshOutput out = detail::cgal_remesh(in);

  RemeshResult r;
  r.before = mesh_quality(mesh, region_faces);
  const std::size_t nv2 = out.positions.size();
  r.maps.vertices.resize(nv2);
  std::vector<Vec3> x(nv2);
  for (std::size_t v = 0; v < nv2; ++v) {
    VertexOrigin& o = r.maps.vertices[v];
    if (!out.moved[v]) {
      o = VertexOrigin{VertexOriginKind::Copy, {VertexId(out.old_vertex[v])}, {1.0}};
      x[v] = mesh.position(VertexId(out.old_vertex[v]));
      continue;
    }
    const detail::SurfaceLocation& loc = out.vertex_location[v];
    const auto fv = mesh.face_vertices(FaceId(loc.face));
    o.kind = VertexOriginKind::Interpolated;
    double sum = 0.0;
    for (int k = 0; k < 3; ++k)
      if (loc.bary[k] > 1e-12) sum += loc.bary[k];
    x[v] = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (loc.bary[k] > 1e-12) {
        o.parents.push_back(fv[k]);
        o.weights.push_back(loc.bary[k] / sum);
        x[v] += o.weights.back() * mesh.position(fv[k]);
      }
    if (o.parents.size() == 1) o.kind = VertexOriginKind::Copy;  // landed on an old vertex
  }
  r.maps.faces.resize(out.faces.size());
  for (std::size_t f = 0; f < out.faces.size(); ++f) {
    FaceOrigin& o = r.maps.faces[f];
    if (out.old_face[f] >= 0) {
      o.parent = FaceId(out.old_face[f]);
      continue;
    }
    o.parent = FaceId(out.face_location[f].face);
    o.kind = FaceOriginKind::Resampled;
    const auto pv = mesh.face_vertices(o.parent);
    for (int k = 0; k < 3; ++k)
      o.bary.row(k) = plane_barycentric(x[out.faces[f][k]], mesh.position(pv[0]),
                                        mesh.position(pv[1]), mesh.position(pv[2]))
                          .transpose();
  }
  r.mesh = SurfaceMesh(std::move(x), out.faces);
  for (std::size_t f = 0; f < out.faces.size(); ++f)
    if (out.region[f]) r.region.emplace_back(f);
  r.after = mesh_quality(r.mesh, r.region);
  for (const auto& [a, b] : out.constrained_edges) r.constrained_edges.emplace_back(VertexId(a), VertexId(b));
  return r;
}

}  // namespace sutura::engine

namespace sutura::engine {

namespace {

std::pair<VertexId, VertexId> ordered(VertexId a, VertexId b) {
  return a.value < b.value ? std::pair{a, b} : std::pair{b, a};
}

bool is_edge(const SurfaceMesh& mesh, VertexId a, VertexId b) {
  return detail::find_halfedge(mesh, a, b).valid() || detail::find_halfedge(mesh, b, a).valid();
}

void sort_unique(std::vector<std::pair<VertexId, VertexId>>& e) {
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
}

}  // namespace

std::vector<std::pair<VertexId, VertexId>> chain_edges(
    const SurfaceMesh& mesh, const std::vector<std::vector<VertexId>>& chains) {
  std::vector<std::pair<VertexId, VertexId>> out;
  for (auto c : chains) {
    // A closed chain (its ends adjacent, at least three vertices) closes with that edge.
    if (c.size() >= 3 && c.front().valid() && c.back().valid() &&
        c.front().index() < mesh.num_vertices() && c.back().index() < mesh.num_vertices() &&
        is_edge(mesh, c.front(), c.back()))
      c.push_back(c.front());
    for (std::size_t i = 0; i + 1 < c.size(); ++i)
      if (c[i].valid() && c[i + 1].valid() && c[i].index() < mesh.num_vertices() &&
          c[i + 1].index() < mesh.num_vertices() && c[i] != c[i + 1] && is_edge(mesh, c[i], c[i + 1]))
        out.push_back(ordered(c[i], c[i + 1]));
  }
  sort_unique(out);
  return out;
}

std::vector<std::pair<VertexId, VertexId>> value_border_edges(const SurfaceMesh& mesh,
                                                              const std::vector<int>& face_value) {
  std::vector<std::pair<VertexId, VertexId>> out;
  for (std::size_t h = 0; h < 3 * mesh.num_faces() && face_value.size() >= mesh.num_faces(); ++h) {
    const HalfedgeId t = mesh.twin(HalfedgeId(h));
    if (!t.valid()) continue;
    if (face_value[SurfaceMesh::face(HalfedgeId(h)).index()] != face_value[SurfaceMesh::face(t).index()])
      out.push_back(ordered(mesh.from_vertex(HalfedgeId(h)), mesh.to_vertex(HalfedgeId(h))));
  }
  sort_unique(out);
  return out;
}

std::vector<std::pair<VertexId, VertexId>> carry_edges(
    const EditMaps& maps, const SurfaceMesh& after,
    const std::vector<std::pair<VertexId, VertexId>>& edges) {
  std::vector<std::pair<VertexId, VertexId>> out;
  if (edges.empty()) return out;
  // Old vertex -> the given edges at it; new vertex -> the given edges it lies on.
  std::map<std::int32_t, std::vector<std::size_t>> at;
  std::map<std::pair<std::int32_t, std::int32_t>, std::size_t> index;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = ordered(edges[e].first, edges[e].second);
    at[a.value].push_back(e);
    at[b.value].push_back(e);
    index.emplace(std::pair{a.value, b.value}, e);
  }
  std::vector<std::vector<std::size_t>> on(maps.vertices.size());
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    if (o.parents.size() == 1) {
      if (const auto it = at.find(o.parents[0].value); it != at.end()) on[v] = it->second;
    } else if (o.parents.size() == 2 && o.kind == VertexOriginKind::Interpolated) {
      const auto [a, b] = ordered(o.parents[0], o.parents[1]);
      if (const auto it = index.find({a.value, b.value}); it != index.end()) on[v] = {it->second};
    }
  }
  for (std::size_t h = 0; h < 3 * after.num_faces(); ++h) {
    const VertexId u = after.from_vertex(HalfedgeId(h)), w = after.to_vertex(HalfedgeId(h));
    for (const std::size_t e : on[u.index()])
      if (std::find(on[w.index()].begin(), on[w.index()].end(), e) != on[w.index()].end()) {
        out.push_back(ordered(u, w));
        break;
      }
  }
  sort_unique(out);
  return out;
}

RemeshParams band_around(const SurfaceMesh& mesh, const std::vector<std::vector<VertexId>>& chains,
                         double band_width, double target_edge_length) {
  RemeshParams p;
  p.constrained_edges = chain_edges(mesh, chains);
  if (p.constrained_edges.empty()) throw InvalidArgument("band_around: no chain has an edge");
  double L = target_edge_length;
  if (!(L > 0.0)) {
    // Median edge length around the chains.
    std::vector<bool> near(mesh.num_vertices(), false);
    for (const auto& [a, b] : p.constrained_edges) near[a.index()] = near[b.index()] = true;
    for (int ring = 0; ring < 2; ++ring) {
      std::vector<bool> grown = near;
      for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
        const auto v = mesh.face_vertices(FaceId(f));
        if (near[v[0].index()] || near[v[1].index()] || near[v[2].index()])
          for (const VertexId w : v) grown[w.index()] = true;
      }
      near = std::move(grown);
    }
    std::vector<double> lengths;
    for (std::size_t h = 0; h < 3 * mesh.num_faces(); ++h) {
      const VertexId u = mesh.from_vertex(HalfedgeId(h)), w = mesh.to_vertex(HalfedgeId(h));
      if (near[u.index()] && near[w.index()]) lengths.push_back((mesh.position(u) - mesh.position(w)).norm());
    }
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    L = lengths[lengths.size() / 2];
  }
  p.target_edge_length = L;
  std::vector<Vec3> points;
  std::vector<FaceId> region;
  for (const auto& c : chains) {
    std::vector<Vec3> line;
    for (const VertexId v : c)
      if (v.valid() && v.index() < mesh.num_vertices()) line.push_back(mesh.position(v));
    if (line.size() < 2) continue;
    for (const FaceId f : faces_near_polyline(mesh, line, band_width * L)) region.push_back(f);
  }
  std::sort(region.begin(), region.end());
  region.erase(std::unique(region.begin(), region.end()), region.end());
  p.region = std::move(region);
  return p;
}

}  // namespace sutura::engine
