#pragma once
// Cutting a vessel end open: local clipping of a closed triangle mesh by a plane.
#include "triangle_soup.hpp"

namespace sutura::engine::anatomy {

/// Removes the part of `mesh` beyond the plane through `centre` with unit `normal` (the side
/// the normal points to) inside the cylinder around the normal axis of radius `reach_radius`
/// and height `reach_depth` beyond the plane; the rest of the object is kept, also on that side
/// of the plane. The cylinder must enclose the tube's part beyond the plane and nothing else.
/// Edges crossing the plane are split at the plane (new vertices shared between the two faces
/// of the edge), faces are clipped Sutherland-Hodgman style with their orientation kept, so the
/// cut is a boundary loop lying exactly in the plane (up to rounding). Vertices within 1e-6 mm
/// of the plane are first moved 2e-6 mm inwards so no vertex lies on it (a vertex on the plane
/// could pinch the new boundary). Unused vertices are dropped, the others keep their relative
/// order. Cost O(F).
void clip_end(TriangleMesh& mesh, const Vec3& centre, const Vec3& normal, double reach_radius,
              double reach_depth);

}  // namespace sutura::engine::anatomy
