#pragma once
// Per-vertex scalar fields for colour maps: displacement magnitude and per-element shell
// measures averaged to the vertices.
#include <span>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine {

/// |after[i] - before[i]| per vertex, mm. Throws InvalidArgument when the sizes differ. O(V).
std::vector<double> displacement_magnitude(std::span<const Vec3> before, std::span<const Vec3> after);

/// Area-weighted average of a per-face value at every vertex: sum_f A_f x_f / sum_f A_f over
/// the faces around the vertex, with the mesh's current face areas (0 where every adjacent
/// face is degenerate). Throws InvalidArgument when per_face.size() != mesh.num_faces(). O(F).
std::vector<double> face_to_vertex(const SurfaceMesh& mesh, std::span<const double> per_face);

/// ElementMeasures averaged to the vertices, field by field, as face_to_vertex.
struct VertexMeasures {
  std::vector<double> membrane_strain;    ///< -
  std::vector<double> bending_curvature;  ///< 1/mm
  std::vector<double> energy_density;     ///< N/mm
};
VertexMeasures face_to_vertex(const SurfaceMesh& mesh, const ElementMeasures& measures);

}  // namespace sutura::engine
