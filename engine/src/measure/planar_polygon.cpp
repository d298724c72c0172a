#include "planar_polygon.hpp"

#include <algorithm>
#include <limits>

namespace sutura::engine::detail {

namespace {
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
}  // namespace

double signed_area(std::span<const Vec2> polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    twice += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * twice;
}

Vec2 area_centroid(std::span<const Vec2> polygon, double signed_area) {
  Vec2 sum = Vec2::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    sum += (a + b) * cross(a, b);
  }
  return sum / (6.0 * signed_area);
}

std::vector<Vec2> convex_hull(std::span<const Vec2> points) {
  std::vector<Vec2> p(points.begin(), points.end());
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Vec2> hull(2 * p.size());
  std::size_t k = 0;
  // Lower hull left to right, then upper hull right to left; pop while not a left turn.
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], p[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 1] - hull[k - 2], p[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

HullExtents hull_extents(std::span<const Vec2> hull) {
  HullExtents out;
  const std::size_t m = hull.size();
  if (m < 3) {  // collinear: width 0, diameter between the two extreme points
    if (m == 2) out.diameter = (hull[1] - hull[0]).norm();
    return out;
  }
  out.min_width = std::numeric_limits<double>::infinity();
  std::size_t j = 1;
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t i1 = (i + 1) % m;
    const Vec2 edge = hull[i1] - hull[i];
    // Twice the area of (i, i1, j) is proportional to j's distance from the edge line.
    while (cross(edge, hull[(j + 1) % m] - hull[i]) > cross(edge, hull[j] - hull[i]))
      j = (j + 1) % m;
    out.min_width = std::min(out.min_width, cross(edge, hull[j] - hull[i]) / edge.norm());
    out.diameter = std::max({out.diameter, (hull[j] - hull[i]).norm(), (hull[j] - hull[i1]).norm()});
  }
  return out;
}

}  // namespace sutura::engine::detail
