#include "sutura/app/section.hpp"

#include <limits>

namespace sutura::app {

SectionPair measure_section(const SceneObject& object, const engine::Plane& plane, double max_radius) {
  engine::CrossSectionParams p;
  p.max_radius = max_radius > 0.0 ? max_radius : std::numeric_limits<double>::infinity();
  return {engine::cross_section(object.before, plane, p), engine::cross_section(object.mesh, plane, p)};
}

}  // namespace sutura::app
