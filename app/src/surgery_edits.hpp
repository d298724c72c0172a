#pragma once
// Applying engine topology edits to a workspace object: everything the object holds (state,
// per-element rest shape and pending y0, materials, constraints, loads, reference positions,
// drawn marks) is carried across with the edit's parent maps.
#include <vector>

#include "sutura/app/workspace.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"

namespace sutura::app::detail {

/// Replaces obj.mesh by `mesh` (the result of an edit of obj.mesh with `maps`) and carries all
/// simulation data across. Velocities are dropped: edits happen between runs, at rest.
void apply_edit(SceneObject& obj, engine::SurfaceMesh mesh, const engine::EditMaps& maps);

/// Appends a separate component (a patch) placed at `placed` whose stress-free shape is
/// `rest_shape` (same faces), made of `material`. Returns the vertex offset of the new part.
std::size_t append_component(SceneObject& obj, const engine::SurfaceMesh& placed,
                             const engine::SurfaceMesh& rest_shape,
                             const engine::ShellMaterial& material);

/// After a suture: y0 becomes congruent with the current shape on every face touching a
/// merged vertex or flagged in `also` (may be empty), keeping a pending y0 elsewhere.
void start_relaxation(SceneObject& obj, const std::vector<engine::VertexId>& merged,
                      const std::vector<bool>& also);

}  // namespace sutura::app::detail
