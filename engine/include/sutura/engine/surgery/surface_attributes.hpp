#pragma once
// Everything a simulated surface carries besides its topology, as channels that every edit
// moves across with its parent maps (geometry-central's MeshData, made explicit).
//
// Contract: `SurfaceAttributes` is an aggregate whose every member is a channel. The two
// functions that build new attributes from old ones (`carry_attributes` for an edit,
// `append_component` for a disjoint union) unpack the aggregate with one structured binding
// of all its members, so a channel added here and not handled there is a compile error:
// a new channel cannot be forgotten after an edit. `check_attributes` says whether every
// per-vertex and per-face channel has the mesh's size.
//
// Per vertex: state (x, D), velocity, reference, constraints, nodal loads, marks (chains).
// Per face: rest, relax_from, face_material, pressure face sets.
// Per surface: materials, relax_s, pending_factor, state_model, body force.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/material.hpp"
#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/sim/constraints.hpp"
#include "sutura/engine/sim/loads.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"

namespace sutura::engine {

/// What the surgeon did, for drawing: vertex chains of the current mesh.
struct SurfaceMarks {
  std::vector<std::vector<VertexId>> incisions;  ///< both lips of each cut
  std::vector<std::vector<VertexId>> sutures;    ///< merged vertices of each seam
};

struct SurfaceAttributes {
  ShellState state;  ///< per vertex: position (mm) and nodal triad; mirrors the mesh positions
  RestState rest;    ///< per face: stress-free reference (x0 of a relaxation)
  /// Per face: y0 of the sutures made since the last relaxation (paper, Sec. 2.3), the rest
  /// shape the next relaxing run starts from. Empty = nothing to relax.
  std::optional<RestState> relax_from;
  double relax_s = 0.0;  ///< how far a part-way relaxation got, [0, 1)
  std::vector<ShellMaterial> materials{ShellMaterial{}};
  std::vector<int> face_material;  ///< per face, index into materials
  Constraints constraints;         ///< per vertex fixed-DOF masks (empty = all free)
  Loads applied_loads;             ///< loads already brought to equilibrium by a solve
  Loads pending_loads;             ///< loads defined since; ramped in by the next solve
  double pending_factor = 0.0;     ///< fraction of pending_loads in equilibrium now, [0, 1)
  /// Per DOF of the last dynamics run (dofs_per_node blocks per vertex, in vertex order);
  /// empty = at rest.
  Eigen::VectorXd velocity;
  /// Name of the shell model whose run produced `state` and `velocity` ("" = none yet); it
  /// says how many DOFs per vertex `velocity` has.
  std::string state_model;
  /// Per vertex: where its material point was before the operation, for displacement fields.
  std::vector<Vec3> reference;
  SurfaceMarks marks;
};

/// The attributes of a fresh surface at rest: state = positions with identity triads, rest
/// congruent with it, one default material, no constraints, loads or marks. Cost O(V + F).
SurfaceAttributes attributes_at_rest(const SurfaceMesh& mesh);

/// Every channel of `old` (on `old_mesh`) carried across an edit with `maps` onto a mesh with
/// the faces `new_faces` (carry.hpp gives each channel's rule; loads and marks follow each old
/// vertex to its image, the new vertex with the largest weight on it, and are dropped where it
/// was removed; velocity blocks by the vertex weights). Pure; cost O(V + F + loads).
SurfaceAttributes carry_attributes(const EditMaps& maps, const SurfaceMesh& old_mesh,
                                   const SurfaceAttributes& old,
                                   const std::vector<FaceIndices>& new_faces);

/// Replaces `mesh` by `edited` (an edit of `mesh` described by `maps`) and carries `attrs`
/// across; the new mesh's positions are the carried state.
void apply_edit(SurfaceMesh& mesh, SurfaceAttributes& attrs, SurfaceMesh edited,
                const EditMaps& maps);

/// Appends a separate component (a patch) placed at `placed` whose stress-free shape is
/// `rest_shape` (same faces), made of `material`, at rest. Loads of `attrs` that act on every
/// face (a pressure without a face list, the body force) then act on the new part too.
/// Returns the vertex offset of the new part. Throws InvalidArgument if the two meshes differ
/// in faces or vertex count.
std::size_t append_component(SurfaceMesh& mesh, SurfaceAttributes& attrs,
                             const SurfaceMesh& placed, const SurfaceMesh& rest_shape,
                             const ShellMaterial& material);

/// After a suture: y0 becomes congruent with the current shape on every face touching a
/// vertex of `merged` or flagged in `also` (may be empty or shorter than the face count),
/// keeping a pending y0 elsewhere (a part-way relaxation is folded in first).
void start_relaxation(const SurfaceMesh& mesh, SurfaceAttributes& attrs,
                      const std::vector<VertexId>& merged, const std::vector<bool>& also);

/// Throws Error naming the first channel whose size does not match `mesh` (per-vertex
/// channels: V entries, per-face channels: F entries, velocity: V * dofs, loads and marks:
/// ids in range). For tests and for checking after every edit.
void check_attributes(const SurfaceMesh& mesh, const SurfaceAttributes& attrs);

}  // namespace sutura::engine
