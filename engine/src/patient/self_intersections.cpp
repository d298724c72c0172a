// Self-intersection test of a surface with CGAL (a translation unit of the CGAL object library).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>

#include "sutura/engine/patient/prepare.hpp"

namespace sutura::engine {

std::vector<std::pair<FaceId, FaceId>> self_intersections(const SurfaceMesh& mesh,
                                                          std::size_t max_pairs) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  using FD = Mesh::Face_index;
  Mesh m;
  m.reserve(static_cast<Mesh::size_type>(mesh.num_vertices()), 0,
            static_cast<Mesh::size_type>(mesh.num_faces()));
  for (const Vec3& p : mesh.positions()) m.add_vertex({p.x(), p.y(), p.z()});
  for (const FaceIndices& f : mesh.faces())
    m.add_face(Mesh::Vertex_index(f[0]), Mesh::Vertex_index(f[1]), Mesh::Vertex_index(f[2]));
  std::vector<std::pair<FD, FD>> pairs;
  if (max_pairs > 0)
    CGAL::Polygon_mesh_processing::self_intersections(
        faces(m), m, std::back_inserter(pairs),
        CGAL::parameters::maximum_number(static_cast<unsigned int>(max_pairs)));
  else
    CGAL::Polygon_mesh_processing::self_intersections(faces(m), m, std::back_inserter(pairs));
  std::vector<std::pair<FaceId, FaceId>> out;
  out.reserve(pairs.size());
  for (const auto& [a, b] : pairs) {
    const auto i = static_cast<int>(a.idx()), j = static_cast<int>(b.idx());
    if (i == j) continue;  // CGAL reports a face of zero area as a pair with itself
    out.emplace_back(FaceId(std::min(i, j)), FaceId(std::max(i, j)));
  }
  std::sort(out.begin(), out.end(), [](const auto& p, const auto& q) {
    return p.first.value != q.first.value ? p.first.value < q.first.value : p.second.value < q.second.value;
  });
  return out;
}

}  // namespace sutura::engine
