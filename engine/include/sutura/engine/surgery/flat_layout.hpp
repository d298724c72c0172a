#pragma once
// Laying a region's rest shape out flat: the cutting pattern of a patch.
//
// A patch is cut from a flat sheet, so its per-element rest shapes fit together in a plane.
// `unfold_rest` places them there, face after face, and says how far they fail to fit:
// `max_gap_mm` is zero to round-off for a patch whose rest shape is still the cut sheet, and
// grows with the rest shape's Gaussian curvature (a region of a vessel wall cannot be cut
// flat without gaps). Only the in-plane shape (the rest corners X) is used, not the rest
// triads: the pattern is the sheet's outline, not its rest curvature.
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/rest_state.hpp"

namespace sutura::engine {

using Vec2 = Eigen::Vector2d;

struct FlatLayout {
  /// Per vertex of the mesh (NaN for vertices of no region face): its position in the plane,
  /// mm, from the first region face laid out that has it. The faces keep their orientation
  /// (no mirror image): counter-clockwise in the plane is counter-clockwise seen from the
  /// side the face normals point to.
  std::vector<Vec2> position;
  /// The region's one boundary loop, counter-clockwise (region on its left), starting at its
  /// smallest vertex id: the seam of a sewn-in patch.
  std::vector<VertexId> outline;
  /// Largest distance between where a region face puts a vertex and `position` (where the
  /// first face laid out put it), mm; two faces can disagree by up to twice this.
  double max_gap_mm = 0.0;
  double rest_area_mm2 = 0.0;       ///< sum of the region faces' rest areas
  double rest_perimeter_mm = 0.0;   ///< sum of the outline edges' rest lengths (their faces')
};

/// Lays out the rest shape of the faces `region` (any order; repeats ignored) in the plane:
/// the lowest face first, in its own rest frame (corner 0 at the origin, corner 1 on +x), then
/// breadth first across shared edges, each face turned and shifted (never mirrored) so that
/// its copy of the shared edge has the same midpoint and direction as the one laid out.
/// Deterministic. Throws InvalidArgument when the region is empty, has a face out of range,
/// a degenerate rest triangle, is not edge-connected, or its boundary is not exactly one loop
/// (a patch is a disk). Cost O(V + F) for the mesh's arrays, plus O(F_r log F_r) in the
/// region's faces.
FlatLayout unfold_rest(const SurfaceMesh& mesh, const RestState& rest,
                       const std::vector<FaceId>& region);

/// Signed area of a closed polygon (positive counter-clockwise), mm^2.
double polygon_area(const std::vector<Vec2>& polygon);

/// Length of a closed polygon, mm.
double polygon_perimeter(const std::vector<Vec2>& polygon);

}  // namespace sutura::engine
