#pragma once
// One path from workspace objects to a render::Scene, for snapshots and the planning window
// alike, so that a snapshot of the window's view shows what the window shows: per object and
// state (current or pre-operative) the arrays the scene's spans point into, the per-vertex
// field, and the scene built from them. The window keeps the views between frames (rebuilt
// when the workspace changes); a snapshot builds them once.
#include <optional>
#include <string>
#include <vector>

#include "sutura/app/plan_drawing.hpp"
#include "sutura/app/session.hpp"
#include "sutura/app/workspace.hpp"
#include "sutura/render/scene.hpp"

namespace sutura::app {

/// Background of the 3-D view and of snapshots.
inline constexpr render::Color kViewBackground = {1.0f, 1.0f, 1.0f};
/// Vertices with a fixed DOF (the held ends), drawn as dots over the current state.
inline constexpr render::Color kHeldColor = {0.95f, 0.75f, 0.05f};

/// What is drawn of an object besides its surface.
struct ViewContent {
  bool marks = true;       ///< patches tinted, incisions, sutures (current state), held vertices
  bool boundaries = true;  ///< open boundary loops as dark lines
  Field field = Field::None;
};

/// One object in one state. The scene built by scene_of points into these arrays.
struct ObjectView {
  std::string name;
  std::vector<float> positions;  ///< flat x, y, z per vertex of the state
  PlanDrawing plan;              ///< faces (wall and patches), incisions and sutures
  std::vector<float> scalars;    ///< per vertex; empty without a field
  std::vector<std::vector<render::Point3>> loops;
  std::vector<render::Point3> held;  ///< with marks: in the before state at their pre-operative positions
  render::Color color{};
};

/// `obj` in `state`, its current mesh or its pre-operative `obj.before` (the plan belongs to
/// the current mesh: the before state's only marks are the held vertices). O(V + F), plus
/// the field's cost: Model 1's measures for the current state's element fields (one pass over
/// the elements).
ObjectView object_view(const SceneObject& obj, const engine::SurfaceMesh& state, render::Color color,
                       const ViewContent& content);

/// Per-vertex values of `field` in `state`. Displacement: from each vertex's pre-operative
/// position (carried across edits; zero in the before state or without reference positions).
/// Membrane strain, bending, energy density: Model 1's per-element measures averaged to the
/// vertices by face area (the before state's are those `unload` kept, or zero).
std::vector<float> field_values(Field field, const SceneObject& obj, const engine::SurfaceMesh& state);
/// The legend's label of `field`, with its unit.
std::string field_label(Field field);

/// The scene of `views` on kViewBackground: surfaces (wireframe optional), boundary loops,
/// held vertices, then the plan lines on top; `color_map` colours the surfaces that have
/// scalars. Its spans point into `views`.
render::Scene scene_of(const std::vector<ObjectView>& views, const std::optional<render::ColorMap>& color_map,
                       bool wireframe);

}  // namespace sutura::app
