#include "sutura/engine/surgery/resect.hpp"

#include <algorithm>
#include <sstream>

#include "mesh_walk.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/surgery/surface_point.hpp"
#include "triangle_soup.hpp"

namespace sutura::engine {

namespace {

// Splits every edge near the plane that it crosses; returns the refined mesh, the maps and a
// per-vertex flag "on this cut".
SurfaceMesh cut_plane(const SurfaceMesh& mesh, const CutPlane& plane, const Vec3& n,
                      const ResectionParams& p, EditMaps& maps, std::vector<bool>& on_cut) {
  const auto& X = mesh.positions();
  std::vector<double> s(X.size());
  std::vector<bool> near(X.size());
  for (std::size_t v = 0; v < X.size(); ++v) {
    s[v] = n.dot(X[v] - plane.origin);
    near[v] = (X[v] - plane.origin).norm() <= p.radius;
  }
  // Sliver guard: a vertex very close to the plane relative to its crossing edges becomes a
  // cut point itself (s = 0).
  std::vector<bool> snapped(X.size(), false);
  for (const HalfedgeId h : mesh.edges()) {
    const VertexId a = mesh.from_vertex(h), b = mesh.to_vertex(h);
    if (!near[a.index()] && !near[b.index()]) continue;
    const double sa = s[a.index()], sb = s[b.index()];
    if (sa * sb >= 0) continue;
    const double t = sa / (sa - sb);
    if (t < p.sliver_fraction) snapped[a.index()] = true;
    if (t > 1.0 - p.sliver_fraction) snapped[b.index()] = true;
  }
  for (std::size_t v = 0; v < X.size(); ++v)
    if (snapped[v]) s[v] = 0.0;
  detail::TriangleSoup soup(mesh);
  for (const HalfedgeId h : mesh.edges()) {
    const VertexId a = mesh.from_vertex(h), b = mesh.to_vertex(h);
    if (!near[a.index()] && !near[b.index()]) continue;
    const double sa = s[a.index()], sb = s[b.index()];
    if (!(sa * sb < 0)) continue;
    soup.split_edge(a.value, b.value, sa / (sa - sb));
  }
  on_cut.assign(soup.num_vertices(), false);
  for (std::size_t v = 0; v < soup.num_vertices(); ++v)
    on_cut[v] = v >= X.size() ? true : (near[v] && s[v] == 0.0);
  return std::move(soup).build(maps);
}

}  // namespace

ResectionResult resect(const SurfaceMesh& mesh, const std::vector<CutPlane>& planes,
                       const Vec3& seed, const ResectionParams& params) {
  if (planes.empty() || planes.size() > 2)
    throw InvalidArgument("a resection needs 1 or 2 planes, got " + std::to_string(planes.size()));
  if (!(params.radius > 0)) throw InvalidArgument("radius must be > 0");
  if (!(params.sliver_fraction > 0 && params.sliver_fraction < 0.5))
    throw InvalidArgument("sliver_fraction must be in (0, 0.5)");
  std::vector<Vec3> normals;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    if (!(planes[i].normal.norm() > 0) || !planes[i].normal.allFinite() ||
        !planes[i].origin.allFinite())
      throw InvalidArgument("plane " + std::to_string(i + 1) + " has a zero or non-finite normal");
    normals.push_back(planes[i].normal.normalized());
  }
  // Cut along each plane in turn.
  SurfaceMesh current = mesh;
  EditMaps maps = EditMaps::identity(mesh.num_vertices(), mesh.num_faces());
  std::vector<std::vector<bool>> on_cut(planes.size());
  for (std::size_t i = 0; i < planes.size(); ++i) {
    EditMaps step;
    current = cut_plane(current, planes[i], normals[i], params, step, on_cut[i]);
    for (std::size_t j = 0; j < i; ++j) {  // carry earlier flags (copies keep theirs)
      std::vector<bool> carried(current.num_vertices(), false);
      for (std::size_t v = 0; v < current.num_vertices(); ++v) {
        bool all = true;
        for (const VertexId p : step.vertices[v].parents) all = all && on_cut[j][p.index()];
        carried[v] = all;
      }
      on_cut[j] = std::move(carried);
    }
    maps = compose(maps, step);
  }

  // Flood the region from the seed face, never crossing an edge lying on a cut.
  const SurfacePoint start = closest_surface_point(current, seed);
  // A seed far from the surface picks whatever part happens to be nearest it (400 mm away, a
  // resection "succeeded" on a tube end): it must lie on or near the part to remove.
  if (const double off = (start.position - seed).norm(); !(off <= params.radius))
    throw InvalidArgument("the seed " + detail::point_text(seed) + " lies " + detail::number_text(off) +
                          " mm from the surface (nearest point " + detail::point_text(start.position) +
                          "); it must lie within radius " + detail::number_text(params.radius) +
                          " mm of the part to remove");
  auto barrier = [&](HalfedgeId h) {
    const VertexId a = current.from_vertex(h), b = current.to_vertex(h);
    for (const auto& cut : on_cut)
      if (cut[a.index()] && cut[b.index()]) return true;
    return false;
  };
  std::vector<bool> removed(current.num_faces(), false);
  std::vector<FaceId> stack{start.face};
  removed[start.face.index()] = true;
  while (!stack.empty()) {
    const FaceId f = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k) {
      const HalfedgeId h = SurfaceMesh::halfedge(f, k);
      const HalfedgeId t = current.twin(h);
      if (!t.valid() || barrier(h)) continue;
      const FaceId g = SurfaceMesh::face(t);
      if (removed[g.index()]) continue;
      removed[g.index()] = true;
      stack.push_back(g);
    }
  }
  // Every removed face must lie on the seed's side of every plane; otherwise a cut did not go
  // all the way round and the region leaked past it.
  const double tol = 1e-6 * current.mean_edge_length();
  for (std::size_t f = 0; f < current.num_faces(); ++f) {
    if (!removed[f]) continue;
    const Vec3 c = current.face_centroid(FaceId(f));
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const double side_seed = normals[i].dot(start.position - planes[i].origin);
      const double side_face = normals[i].dot(c - planes[i].origin);
      if (side_seed * side_face < 0 && std::abs(side_face) > tol)
        throw InvalidArgument("plane " + std::to_string(i + 1) + " through " +
                              detail::point_text(planes[i].origin) +
                              " does not cut the surface all the way round within radius " +
                              std::to_string(params.radius) +
                              " mm (the removed region would extend past it, e.g. at " +
                              detail::point_text(c) + ")");
    }
  }
  ResectionResult result;
  std::vector<FaceIndices> faces;
  std::vector<int> new_id(current.num_vertices(), -1);
  std::vector<Vec3> positions;
  EditMaps keep;
  for (std::size_t f = 0; f < current.num_faces(); ++f) {
    if (removed[f]) {
      ++result.removed_faces;
      result.removed_area += current.face_area(FaceId(f));
      continue;
    }
    FaceIndices idx = current.faces()[f];
    for (auto& v : idx) {
      if (new_id[v] < 0) {
        new_id[v] = int(positions.size());
        positions.push_back(current.positions()[v]);
        keep.vertices.push_back(VertexOrigin{VertexOriginKind::Copy, {VertexId(v)}, {1.0}});
      }
      v = new_id[v];
    }
    faces.push_back(idx);
    keep.faces.push_back(FaceOrigin{FaceId(f), Eigen::Matrix3d::Identity()});
  }
  if (faces.empty()) throw InvalidArgument("the resection would remove the whole object");
  // Keep vertex order stable: renumber by old id so untouched parts keep their order.
  {
    std::vector<int> order(positions.size());
    for (std::size_t v = 0; v < current.num_vertices(); ++v)
      if (new_id[v] >= 0) order[new_id[v]] = int(v);
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> remap(current.num_vertices(), -1);
    for (std::size_t i = 0; i < sorted.size(); ++i) remap[sorted[i]] = int(i);
    std::vector<Vec3> pos2(positions.size());
    std::vector<VertexOrigin> vo(positions.size());
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      pos2[i] = current.positions()[sorted[i]];
      vo[i] = VertexOrigin{VertexOriginKind::Copy, {VertexId(sorted[i])}, {1.0}};
    }
    for (auto& f : faces)
      for (auto& v : f) v = remap[order[v]];
    positions = std::move(pos2);
    keep.vertices = std::move(vo);
    for (std::size_t v = 0; v < current.num_vertices(); ++v) new_id[v] = remap[v];
  }
  result.mesh = SurfaceMesh(std::move(positions), std::move(faces));
  result.maps = compose(maps, keep);
  // The loops left by each cut: boundary loops made only of that cut's vertices.
  for (std::size_t i = 0; i < planes.size(); ++i) {
    BoundaryChain found;
    for (const auto& loop : result.mesh.boundary_loops()) {
      bool all = true;
      for (const VertexId v : loop) all = all && on_cut[i][keep.vertices[v.index()].parents[0].index()];
      if (all) {
        found.vertices = loop;
        found.closed = true;
        break;
      }
    }
    if (found.vertices.empty())
      throw InvalidArgument("plane " + std::to_string(i + 1) + " through " +
                            detail::point_text(planes[i].origin) +
                            " does not leave a closed cut loop (does it cross the removed region?)");
    result.loops.push_back(std::move(found));
  }
  return result;
}

}  // namespace sutura::engine
