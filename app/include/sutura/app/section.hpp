#pragma once
// The lumen cross-section of an object by a plane, before (its pre-operative mesh) and after
// (its current state): what the `measure` op reports for a plane and what the planning
// window draws in its section view. One place, so that both read the same outline.
#include "sutura/app/workspace.hpp"
#include "sutura/engine/measure/cross_section.hpp"

namespace sutura::app {

struct SectionPair {
  engine::CrossSection before;  ///< of SceneObject::before
  engine::CrossSection after;   ///< of SceneObject::mesh
};

/// Both sections by `plane`, each the outline around the plane's origin
/// (engine::cross_section); `max_radius` mm, <= 0: unlimited. Throws engine::InvalidArgument
/// as cross_section does (e.g. a plane that does not cut one of the two shapes). O(F).
SectionPair measure_section(const SceneObject& object, const engine::Plane& plane, double max_radius);

}  // namespace sutura::app
