#pragma once
// Hinges (interior edges with their two faces) of a face array, for Model 2's bending.
// Built from the faces alone; the model keeps it while the face array is unchanged
// (discrete_rest_cache.hpp). Cost: O(F log F) (one sort of the 3F half-edges).
#include <array>
#include <cstdint>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine::dshell {

/// An interior edge a - b. Face `face[0]` = (a, b, c) holds it as half-edge a -> b, face
/// `face[1]` = (b, a, d) as b -> a (the lower half-edge id is face[0]'s).
struct Hinge {
  std::array<std::int32_t, 4> node;  ///< a, b, c, d
  std::array<std::int32_t, 2> face;
  std::array<int, 2> halfedge;       ///< corner index (0..2) where the edge starts, per face
};

struct HingeTopology {
  std::vector<Hinge> hinges;  ///< ordered by (min vertex, max vertex) of the edge
  /// Per face and half-edge k: the hinge index, or -1 on the boundary.
  std::vector<std::array<std::int32_t, 3>> face_hinge;
};

/// Throws TopologyError if an edge has more than two faces or two faces traverse it in the
/// same direction. Face indices must already be valid.
HingeTopology build_hinge_topology(const std::vector<FaceIndices>& faces);

/// Stencil slots of a face: 0..2 its corners, 3 + k the apex across its half-edge k. Returns
/// the slots of the hinge nodes (a, b, c, d) seen from the face holding the hinge as its
/// half-edge k, on side 0 (the face is hinge.face[0]) or 1.
std::array<int, 4> hinge_slots(int k, int side);

}  // namespace sutura::engine::dshell
