#include "isotropic_remesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/angle_and_area_smoothing.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <vector>

#include "sutura/engine/surgery/remesh.hpp"

namespace sutura::engine::anatomy {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }
Point to_point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

TriangleMesh isotropic_remesh(const TriangleMesh& input, double target_edge_length, int iterations,
                              const VesselField& field, const std::vector<EndPlane>& ends) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(input.positions.size());
  for (const Vec3& p : input.positions) vertex.push_back(mesh.add_vertex(to_point(p)));
  for (const FaceIndices& f : input.faces) mesh.add_face(vertex[f[0]], vertex[f[1]], vertex[f[2]]);

  const auto project_border = [&](const Vec3& p) {
    const EndPlane* nearest = &ends.front();
    for (const EndPlane& e : ends)
      if ((p - e.centre).norm() < (p - nearest->centre).norm()) nearest = &e;
    return field.project_in_plane(p, nearest->centre, nearest->normal);
  };
  const auto project = [&](Mesh::Vertex_index v) {
    return to_point(field.project(to_vec(mesh.point(v))));
  };
  // CGAL projects only vertices off the mesh border (border vertices move along the border
  // polyline, i.e. onto its chords, so open ends would shrink iteration by iteration). Hence
  // one remeshing iteration at a time, each followed by projecting the border vertices onto
  // their end circle.
  for (int it = 0; it < iterations; ++it) {
    PMP::isotropic_remeshing(faces(mesh), target_edge_length, mesh,
                             CGAL::parameters::number_of_iterations(1)
                                 .relax_constraints(true)
                                 .projection_functor(project));
    for (Mesh::Vertex_index v : mesh.vertices())
      if (mesh.is_border(v)) mesh.point(v) = to_point(project_border(to_vec(mesh.point(v))));
  }
  mesh.collect_garbage();
  // The last border projection can leave a rim vertex with an inner neighbour close by (a
  // short edge and a thin face at an open end). Every face below kRepairBelow degrees and the
  // faces around its corners are smoothed by angle (CGAL's angle smoothing: vertices move,
  // nothing is flipped), the rim held, inner vertices projected back onto the vessel; a mesh without
  // such a face is left bit for bit as it is.
  constexpr double kRepairBelow = 22.0;
  std::vector<Mesh::Face_index> poor;
  for (Mesh::Face_index f : mesh.faces()) {
    std::array<Vec3, 3> p;
    int k = 0;
    for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) p[k++] = to_vec(mesh.point(v));
    if (smallest_angle_deg(p[0], p[1], p[2]) < kRepairBelow) poor.push_back(f);
  }
  if (!poor.empty()) {
    auto held = mesh.add_property_map<Mesh::Vertex_index, bool>("v:held", false).first;
    for (Mesh::Vertex_index v : mesh.vertices()) held[v] = mesh.is_border(v);
    std::vector<Mesh::Face_index> region;
    for (Mesh::Face_index f : poor)
      for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh))
        for (Mesh::Face_index g : faces_around_target(mesh.halfedge(v), mesh))
          if (g != Mesh::null_face()) region.push_back(g);
    std::sort(region.begin(), region.end());
    region.erase(std::unique(region.begin(), region.end()), region.end());
    for (int it = 0; it < 3; ++it) {
      PMP::angle_and_area_smoothing(region, mesh,
                                    CGAL::parameters::number_of_iterations(1)
                                        .use_angle_smoothing(true)
                                        .use_area_smoothing(false)
                                        .do_project(false)
                                        .vertex_is_constrained_map(held));
      for (Mesh::Face_index f : region)
        for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh))
          if (!held[v]) mesh.point(v) = project(v);
    }
    mesh.remove_property_map(held);
  }

  TriangleMesh out;
  out.positions.reserve(mesh.number_of_vertices());
  for (Mesh::Vertex_index v : mesh.vertices()) out.positions.push_back(to_vec(mesh.point(v)));
  out.faces.reserve(mesh.number_of_faces());
  for (Mesh::Face_index f : mesh.faces()) {
    FaceIndices tri{};
    int k = 0;
    for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh))
      tri[k++] = static_cast<std::int32_t>(v.idx());
    out.faces.push_back(tri);
  }
  return out;
}

}  // namespace sutura::engine::anatomy
