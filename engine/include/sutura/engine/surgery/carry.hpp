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

/// Rest geometry per element: an untouched face keeps its element bit for bit; a sub-face
/// gets rest corners X_new[k] = sum_j bary(k, j) X_parent[j] (exact: the current-to-rest map
/// of a triangle is affine) and rest triads interpolated from the parent's, re-expressed in
/// the sub-face's own rest frame (sub-faces are coplanar with the parent, so the change of
/// frame is a rotation about the normal).
RestState carry_rest(const EditMaps& maps, const RestState& old);

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
