#pragma once
// What a `patch` op would add, before it is added: the planning window draws the outline and
// states the size while the surgeon adjusts shape and width, and says why a patch cannot be
// added before the op is tried.
#include <cstddef>
#include <vector>

#include "sutura/app/session.hpp"
#include "sutura/app/workspace.hpp"

namespace sutura::app {

struct PatchPreview {
  /// The patch's outline at its true size: the patch as cut (its flat rest shape, which
  /// plan_patch places in the tangent plane at the incision's middle, long axis along the
  /// cut), each outline point moved to the closest point of the host's surface. A closed
  /// polyline: the last point repeats the first. (Where the op first lays the patch, over the
  /// slit and as narrow as it, would show nothing the incision does not.)
  std::vector<engine::Vec3> outline;
  double length = 0.0;   ///< mm along the incision (the op's length, or the incision's)
  double width = 0.0;    ///< mm across it
  double area = 0.0;     ///< mm², of the patch as cut (its flat rest shape)
  std::size_t faces = 0; ///< of the patch as first cut, before its seams are matched to the lips
};

/// Plans `op` on `object` as the op first does (engine::plan_patch with the op's parameters,
/// limited to `max_faces` faces) without changing anything. Throws what the op would throw
/// for the same reason (engine::InvalidArgument: no such incision, a shape that does not fit
/// it, bad sizes). Cost: one plan_patch, and O(outline points · host faces) for the
/// projection.
PatchPreview preview_patch(const SceneObject& object, const PatchOp& op, std::size_t max_faces);

}  // namespace sutura::app
