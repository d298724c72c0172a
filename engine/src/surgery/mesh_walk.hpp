#pragma once
// Small adjacency queries and message helpers shared by the surgery edits.
#include <sstream>
#include <string>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine::detail {

/// The half-edge u -> v, or an invalid id when u and v are not adjacent in that direction.
/// O(valence of u).
inline HalfedgeId find_halfedge(const SurfaceMesh& mesh, VertexId u, VertexId v) {
  for (const FaceId f : mesh.vertex_faces(u))
    for (int k = 0; k < 3; ++k) {
      const HalfedgeId h = SurfaceMesh::halfedge(f, k);
      if (mesh.from_vertex(h) == u && mesh.to_vertex(h) == v) return h;
    }
  return HalfedgeId();
}

/// "(x, y, z)" for error messages.
// A length for a message: 6 significant digits ("396", "0.25").
inline std::string number_text(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

inline std::string point_text(const Vec3& x) {
  std::ostringstream os;
  os << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return os.str();
}

}  // namespace sutura::engine::detail
