#include "markers.hpp"

namespace sutura::render {
namespace {

// Two triangles covering the quad's four corners.
constexpr float kSegmentCorners[6][2] = {{0, -1}, {0, 1}, {1, -1}, {0, 1}, {1, 1}, {1, -1}};
constexpr float kDiscCorners[6][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, -1}, {1, 1}, {-1, 1}};

void add_quad(std::vector<MarkerVertex>& out, const Point3& from, const Point3& to,
              const float (&corners)[6][2], const Color& color, float size_px, float disc) {
  for (const auto& c : corners) {
    out.push_back({{from[0], from[1], from[2]},
                   {to[0], to[1], to[2]},
                   {c[0], c[1]},
                   {color[0], color[1], color[2]},
                   size_px,
                   disc});
  }
}

}  // namespace

void build_marker_vertices(const Scene& scene, std::vector<MarkerVertex>& out) {
  out.clear();
  const auto drawn = [](const PolylineItem& l) {
    return l.points.size() >= 2 && l.width_px > 0.0f;
  };
  for (const PolylineItem& l : scene.polylines) {
    if (!drawn(l)) continue;
    const std::size_t n = l.points.size();
    for (std::size_t i = 0; i + 1 < n; ++i) {
      add_quad(out, l.points[i], l.points[i + 1], kSegmentCorners, l.color, l.width_px, 0.0f);
    }
    if (l.closed)
      add_quad(out, l.points[n - 1], l.points[0], kSegmentCorners, l.color, l.width_px, 0.0f);
  }
  for (const PolylineItem& l : scene.polylines) {
    if (!drawn(l)) continue;
    for (const Point3& p : l.points) add_quad(out, p, p, kDiscCorners, l.color, l.width_px, 1.0f);
  }
  for (const PointsItem& item : scene.points) {
    if (!(item.size_px > 0.0f)) continue;
    for (const Point3& p : item.points)
      add_quad(out, p, p, kDiscCorners, item.color, item.size_px, 1.0f);
  }
}

}  // namespace sutura::render
