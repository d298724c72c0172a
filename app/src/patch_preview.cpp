#include "sutura/app/patch_preview.hpp"

#include "sutura/engine/surgery/patch_plan.hpp"
#include "sutura/engine/surgery/surface_point.hpp"

namespace sutura::app {

PatchPreview preview_patch(const SceneObject& object, const PatchOp& op, std::size_t max_faces) {
  engine::PatchPlanParams params = op.params;
  params.max_faces = static_cast<double>(max_faces);
  const engine::PatchPlan plan = engine::plan_patch(object.mesh, op.start, op.end, params);
  PatchPreview p;
  const auto loops = plan.rest.boundary_loops();
  if (!loops.empty()) {
    for (const engine::VertexId v : loops.front())
      p.outline.push_back(engine::closest_surface_point(object.mesh, plan.rest.position(v)).position);
    p.outline.push_back(p.outline.front());
  }
  p.length = params.length > 0.0 ? params.length : plan.incision_length;
  p.width = params.width;
  p.area = plan.rest.total_area();
  p.faces = plan.rest.num_faces();
  return p;
}

}  // namespace sutura::app
