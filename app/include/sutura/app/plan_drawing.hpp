#pragma once
// What the surgeon planned, drawn on an object: its patches (faces of any material but the
// first, the wall's) tinted, and its incision lips (red) and suture lines (green) over the
// surface. One definition for the snapshots and the planning window, so that both show the
// plan alike.
#include <cstdint>
#include <span>
#include <vector>

#include "sutura/app/workspace.hpp"
#include "sutura/render/scene.hpp"

namespace sutura::app {

/// Patch faces: the colour of pericardium and graft material against the red of the wall.
inline constexpr render::Color kPatchColor = {0.93f, 0.80f, 0.52f};
inline constexpr render::Color kIncisionColor = {0.85f, 0.1f, 0.1f};
inline constexpr render::Color kSutureColor = {0.1f, 0.7f, 0.2f};

struct PlanDrawing {
  std::vector<std::uint32_t> wall_triangles;   ///< flat vertex indices, 3 per face of material 0
  std::vector<std::uint32_t> patch_triangles;  ///< the same for every other material
  std::vector<std::vector<render::Point3>> incisions, sutures;  ///< polylines on the state
};

/// The drawing of `obj` in `state`: its current mesh (faces split by material, marks drawn
/// when `marks`) or its pre-operative mesh `obj.before` (all wall, no marks: the marks and
/// materials belong to the current mesh). O(V + F).
PlanDrawing plan_drawing(const SceneObject& obj, const engine::SurfaceMesh& state, bool marks);

/// Appends the object's surfaces to `scene`: the wall in `wall`, then the patches in
/// kPatchColor when there are any, both over `positions` and coloured by `scalars` when not
/// empty. The scene's spans point into `positions`, `scalars` and `d`.
void add_plan_surfaces(render::Scene& scene, std::span<const float> positions, std::span<const float> scalars,
                       const PlanDrawing& d, render::Color wall, bool wireframe);
/// Appends the incision lips and suture lines (3 px) to `scene`; draw them after the
/// boundary loops, so that they stay on top where they meet an open end.
void add_plan_lines(render::Scene& scene, const PlanDrawing& d);

}  // namespace sutura::app
