#pragma once
// Planar polygon measures used by the cross-section (internal): shoelace area and centroid,
// convex hull, and the rotating-calipers width and diameter of a convex polygon.
#include <span>
#include <vector>

#include <Eigen/Core>

namespace sutura::engine::detail {

using Vec2 = Eigen::Vector2d;

/// Signed shoelace area of the closed polygon (implicit closing edge); > 0 counter-clockwise.
double signed_area(std::span<const Vec2> polygon);

/// Area centroid of the closed polygon with the given non-zero signed area:
/// c = 1/(6A) sum (p_i + p_{i+1}) (p_i x p_{i+1}).
Vec2 area_centroid(std::span<const Vec2> polygon, double signed_area);

/// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
/// Fewer than three points come back when all points are collinear. O(n log n).
std::vector<Vec2> convex_hull(std::span<const Vec2> points);

struct HullExtents {
  double min_width = 0.0;  ///< smallest distance between two parallel supporting lines
  double diameter = 0.0;   ///< largest distance between two points
};

/// Rotating calipers over a convex hull from convex_hull(): for every hull edge the
/// antipodal vertex j (farthest from the edge's line) is advanced monotonically; the width in
/// the edge's normal direction is the distance of j from the line, and the minimum width of
/// a convex polygon is attained perpendicular to one of its edges. Every antipodal vertex
/// pair appears as (i, j) or (i + 1, j), and the diameter is attained at one of them. O(n).
HullExtents hull_extents(std::span<const Vec2> hull);

}  // namespace sutura::engine::detail
