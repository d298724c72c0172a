#include "cgal_remesh.hpp"

#include <algorithm>
#include <array>
#include <map>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/Surface_mesh.h>

#include "sutura/engine/surgery/surface_point.hpp"

namespace sutura::engine::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VI = Mesh::Vertex_index;
using FI = Mesh::Face_index;
using EI = Mesh::Edge_index;
namespace PMP = CGAL::Polygon_mesh_processing;

using FacePrimitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using FaceTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, FacePrimitive>>;
using SegmentIt = std::vector<Segment>::const_iterator;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, SegmentIt>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }
Point to_point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

double distance_to_polyline(const Vec3& p, const std::vector<Vec3>& curve) {
  if (curve.size() == 1) return (p - curve[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const Vec3 d = curve[i + 1] - curve[i];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - curve[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (curve[i] + t * d)).norm());
  }
  return best;
}

}  // namespace

CgalRemeshOutput cgal_remesh(const CgalRemeshInput& in) {
  const std::vector<Vec3>& X = *in.positions;
  const std::vector<FaceIndices>& F = *in.faces;
  Mesh mesh;
  for (const Vec3& p : X) mesh.add_vertex(to_point(p));
  for (const FaceIndices& f : F) mesh.add_face(VI(f[0]), VI(f[1]), VI(f[2]));

  auto old_id = mesh.add_property_map<VI, int>("v:old", -1).first;
  auto vfixed = mesh.add_property_map<VI, bool>("v:fixed", false).first;
  auto econ = mesh.add_property_map<EI, bool>("e:constrained", false).first;
  auto in_region = mesh.add_property_map<FI, bool>("f:region", false).first;
  auto patch = mesh.add_property_map<FI, int>("f:patch", 0).first;
  for (VI v : mesh.vertices()) {
    old_id[v] = static_cast<int>(v.idx());
    vfixed[v] = v.idx() < in.constrained_vertices.size() && in.constrained_vertices[v.idx()];
  }
  for (FI f : mesh.faces()) in_region[f] = in.region[f.idx()];

  // The input polylines (constraints and open boundaries) for the projection of the vertices
  // that lie on them; the input surface for all others.
  std::vector<Segment> segments;
  for (const auto& [a, b] : in.constrained_edges) {
    const auto h = mesh.halfedge(VI(a), VI(b));
    econ[mesh.edge(h)] = true;
  }
  for (EI e : mesh.edges()) {
    if (mesh.is_border(e)) econ[e] = true;
    if (econ[e])
      segments.emplace_back(mesh.point(mesh.vertex(e, 0)), mesh.point(mesh.vertex(e, 1)));
  }
  const Mesh original = mesh;
  FaceTree surface(faces(original).first, faces(original).second, original);
  surface.accelerate_distance_queries();
  SegmentTree polylines(segments.cbegin(), segments.cend());
  if (!segments.empty()) polylines.accelerate_distance_queries();

  const auto on_polyline = [&](VI v) {
    for (auto h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh))
      if (econ[mesh.edge(h)]) return true;
    return false;
  };
  const auto project = [&](VI v) {
    const Point& p = mesh.point(v);
    if (!segments.empty() && on_polyline(v)) return polylines.closest_point(p);
    return surface.closest_point(p);
  };

  for (const RemeshBand& band : in.bands) {
    std::vector<FI> range;
    for (FI f : mesh.faces()) {
      patch[f] = 0;
      if (!in_region[f]) continue;
      if (band.reach >= 0.0) {
        Vec3 c = Vec3::Zero();
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) c += to_vec(mesh.point(v));
        if (distance_to_polyline(c / 3.0, in.band_curve) > band.reach) continue;
      }
      patch[f] = 1;
      range.push_back(f);
    }
    if (range.empty()) continue;
    for (int it = 0; it < in.iterations; ++it) {
      // Split, collapse, flip and project; the tangential relaxation is run below instead of
      // CGAL's own, which in CGAL 5.5 ignores vertex_is_constrained_map and moves fixed
      // vertices.
      PMP::isotropic_remeshing(range, band.target_edge_length, mesh,
                               CGAL::parameters::number_of_iterations(1)
                                   .number_of_relaxation_steps(0)
                                   .edge_is_constrained_map(econ)
                                   .vertex_is_constrained_map(vfixed)
                                   .face_patch_map(patch)
                                   .protect_constraints(false)
                                   .collapse_constraints(true)
                                   .relax_constraints(false)
                                   .projection_functor(project));
      range.clear();
      for (FI f : mesh.faces())
        if (patch[f] == 1) range.push_back(f);
      // Vertices that may move: inside the band, off every constrained polyline, not fixed.
      std::vector<VI> inner;
      for (FI f : range)
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) inner.push_back(v);
      std::sort(inner.begin(), inner.end());
      inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
      auto held = mesh.add_property_map<VI, bool>("v:held", false).first;
      for (VI v : inner) {
        bool h = vfixed[v] || on_polyline(v);
        for (FI f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
          h = h || f == Mesh::null_face() || patch[f] != 1;
        held[v] = h;
      }
      PMP::tangential_relaxation(inner, mesh,
                                 CGAL::parameters::number_of_iterations(1)
                                     .edge_is_constrained_map(econ)
                                     .vertex_is_constrained_map(held)
                                     .relax_constraints(false));
      for (VI v : inner)
        if (!held[v]) mesh.point(v) = project(v);
      mesh.remove_property_map(held);
    }
    for (FI f : mesh.faces())
      if (patch[f] == 1) in_region[f] = true;
  }

  // Old faces by their vertex triple, to recognise faces the remesh left alone.
  std::map<std::array<int, 3>, int> old_face;
  for (std::size_t f = 0; f < F.size(); ++f) {
    std::array<int, 3> key{F[f][0], F[f][1], F[f][2]};
    std::sort(key.begin(), key.end());
    old_face.emplace(key, static_cast<int>(f));
  }
  const auto locate = [&](const Vec3& p) {
    const auto [q, face] = surface.closest_point_and_primitive(to_point(p));
    SurfaceLocation loc;
    loc.face = static_cast<int>(face.idx());
    const FaceIndices& t = F[face.idx()];
    loc.bary = closest_point_barycentric(p, X[t[0]], X[t[1]], X[t[2]]);
    return loc;
  };

  CgalRemeshOutput out;
  std::vector<int> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), -1);
  for (VI v : mesh.vertices()) {
    index[v.idx()] = static_cast<int>(out.positions.size());
    const Vec3 p = to_vec(mesh.point(v));
    const int o = old_id[v];
    const bool moved = o < 0 || p != X[static_cast<std::size_t>(o)];
    out.positions.push_back(p);
    out.old_vertex.push_back(o);
    out.moved.push_back(moved);
    out.vertex_location.push_back(moved ? locate(p) : SurfaceLocation{});
  }
  for (FI f : mesh.faces()) {
    FaceIndices t{};
    int k = 0;
    for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t[k++] = index[v.idx()];
    int same = -1;
    const int a = out.old_vertex[t[0]], b = out.old_vertex[t[1]], c = out.old_vertex[t[2]];
    if (!out.moved[t[0]] && !out.moved[t[1]] && !out.moved[t[2]]) {
      std::array<int, 3> key{a, b, c};
      std::sort(key.begin(), key.end());
      if (const auto it = old_face.find(key); it != old_face.end()) {
        // Same corners; keep the old face's corner order (same orientation in a manifold).
        const FaceIndices& of = F[static_cast<std::size_t>(it->second)];
        for (int r = 0; r < 3; ++r)
          if (out.old_vertex[t[r]] == of[0]) {
            const FaceIndices turned{t[r], t[(r + 1) % 3], t[(r + 2) % 3]};
            if (out.old_vertex[turned[1]] == of[1]) {
              t = turned;
              same = it->second;
            }
          }
      }
    }
    out.faces.push_back(t);
    out.region.push_back(in_region[f]);
    out.old_face.push_back(same);
    out.face_location.push_back(
        same >= 0 ? SurfaceLocation{}
                  : locate((out.positions[t[0]] + out.positions[t[1]] + out.positions[t[2]]) / 3.0));
  }
  for (EI e : mesh.edges())
    if (econ[e] && !mesh.is_border(e))
      out.constrained_edges.emplace_back(index[mesh.vertex(e, 0).idx()],
                                         index[mesh.vertex(e, 1).idx()]);
  return out;
}

}  // namespace sutura::engine::detail
