#include "sutura/engine/measure/vertex_fields.hpp"

#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

std::vector<double> displacement_magnitude(std::span<const Vec3> before, std::span<const Vec3> after) {
  if (before.size() != after.size())
    throw InvalidArgument("displacement_magnitude: " + std::to_string(before.size()) +
                          " positions before but " + std::to_string(after.size()) + " after");
  std::vector<double> d(before.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = (after[i] - before[i]).norm();
  return d;
}

std::vector<double> face_to_vertex(const SurfaceMesh& mesh, std::span<const double> per_face) {
  if (per_face.size() != mesh.num_faces())
    throw InvalidArgument("face_to_vertex: " + std::to_string(per_face.size()) + " values for " +
                          std::to_string(mesh.num_faces()) + " faces");
  std::vector<double> sum(mesh.num_vertices(), 0.0), weight(mesh.num_vertices(), 0.0);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const double a = mesh.face_area(FaceId(f));
    for (std::int32_t v : mesh.faces()[f]) {
      sum[static_cast<std::size_t>(v)] += a * per_face[f];
      weight[static_cast<std::size_t>(v)] += a;
    }
  }
  for (std::size_t i = 0; i < sum.size(); ++i) sum[i] = weight[i] > 0.0 ? sum[i] / weight[i] : 0.0;
  return sum;
}

VertexMeasures face_to_vertex(const SurfaceMesh& mesh, const ElementMeasures& measures) {
  return {face_to_vertex(mesh, measures.membrane_strain),
          face_to_vertex(mesh, measures.bending_curvature),
          face_to_vertex(mesh, measures.energy_density)};
}

}  // namespace sutura::engine
