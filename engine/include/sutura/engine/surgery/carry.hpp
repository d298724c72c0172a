#pragma once
// Carrying per-vertex and per-element data across a topology edit with its parent maps.
// Each function is pure: old data + maps in, new data out. Cost O(V + F).
#include <vector>

#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/sim/constraints.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"

namespace sutura::engine {

/// Positions by the vertex weights; nodal triads copied (Copy) or averaged (normalised,
/// sign-aligned weighted quaternion mean: exact for one parent, the chordal mean otherwise).
ShellState carry_state(const EditMaps& maps, const ShellState& old);

/// Per-vertex vectors (e.g. the pre-operative reference positions) by the vertex weights.
std::vector<Vec3> carry_points(const EditMaps& maps, const std::vector<Vec3>& old);

/// The current shapes on both sides of an edit: what the rest transfer of Resampled faces
/// needs besides the maps.
struct EditGeometry {
  const std::vector<FaceIndices>& old_faces;
  const ShellState& old_state;
  const std::vector<FaceIndices>& new_faces;
  const ShellState& new_state;  ///< carried (carry_state) onto the new mesh
};

/// Rest geometry per element.
/// - Subface: an untouched face keeps its element bit for bit; a sub-face gets rest corners
///   X_new[k] = sum_j bary(k, j) X_parent[j] (exact: the current-to-rest map of a triangle is
///   affine) and rest triads interpolated from the parent's, re-expressed in the sub-face's own
///   rest frame (sub-faces are coplanar with the parent, so the change of frame is a rotation
///   about the normal).
/// - Resampled (needs `geometry`, else InvalidArgument): strain transfer. The new face's
///   current triangle is turned into the parent's current plane (the smallest rotation between
///   the normals) and pulled back through the parent's in-plane map G (current -> rest, G =
///   [A1 A2][a1 a2]^-1 in the two frames); its rest triads are its current ones (T_e^T D_k)
///   turned by the parent's triad deviation Q_rest Q_congruent^-1, interpolated at the corner
///   (clamped barycentrics). A parent at rest (rest congruent with current) gives G = I and no
///   deviation, so the new element is at rest too: an unstressed body stays unstressed.
RestState carry_rest(const EditMaps& maps, const RestState& old,
                     const EditGeometry* geometry = nullptr);

/// Per-face values (material index, ...): the parent's value.
std::vector<int> carry_face_values(const EditMaps& maps, const std::vector<int>& old);

/// Fixed DOFs: a copy keeps them, an interpolated vertex is fixed in a DOF only when all its
/// parents are, a sutured vertex when any of its copies is.
Constraints carry_constraints(const EditMaps& maps, const Constraints& old);

/// Faces of the new mesh descending from any face in `old_faces` (sorted, unique).
std::vector<FaceId> carry_face_set(const EditMaps& maps, const std::vector<FaceId>& old_faces);

/// First new vertex that is the same material point as `old` (a Copy of it), or invalid when
/// the vertex was merged or removed.
VertexId carry_vertex(const EditMaps& maps, VertexId old);

}  // namespace sutura::engine
