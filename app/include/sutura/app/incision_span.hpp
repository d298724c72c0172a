#pragma once
// The stretch of a vessel's lumen that an incision runs along, on its automatic centreline:
// what the planning window's patch design measures.
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::app {

struct IncisionSpan {
  /// A piece of the centreline, from before `start` to past `end` (mm), as a polyline: the
  /// `centreline` of a lumen profile (MeasureOp), whose planes stay put while candidates vary.
  std::vector<engine::Vec3> centreline;
  double length_mm = 0.0;
  /// Twice the largest inscribed radius along it (mm): a section's `max_radius`, so that a
  /// plane near a branch does not take the branch's lumen in.
  double max_radius_mm = 0.0;
};

/// The automatic centreline of `mesh` (engine::extract_centreline, one end per open end, the
/// root the end of largest vector area, so never an incision's flat slit)
/// between where `start` and `end` (points on the wall, e.g. an incision's ends, in that
/// order) project onto the path between two open ends that runs along both, moved
/// `margin_mm` (>= 0) further out along it, within the path. A path runs along a point within
/// 1.5 lumen radii + 0.5 mm of it; of those the longest (the trunk, not a branch that leaves
/// beside the incision), and when none does, the path closest to both. Open ends whose centre lies on
/// the wall (an incision's slit: inscribed radius under a quarter of the median end's) are
/// not path ends. Throws std::invalid_argument when no two open ends are left, when both points
/// project to the same place, or a negative margin; engine::InvalidArgument as
/// extract_centreline does. Cost: the centreline (about 0.2 s at 19k faces) and a path per
/// pair of open ends.
IncisionSpan incision_span(const engine::SurfaceMesh& mesh, const engine::Vec3& start, const engine::Vec3& end,
                           double margin_mm);

}  // namespace sutura::app
