#include <cmath>
#include <numbers>
#include <string>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {

SurfaceMesh make_cylinder_panel(const CylinderPanelParams& p) {
  if (!(p.radius > 0.0)) throw InvalidArgument("cylinder panel: radius must be > 0, got " + std::to_string(p.radius));
  if (!(p.length > 0.0)) throw InvalidArgument("cylinder panel: length must be > 0, got " + std::to_string(p.length));
  const double span = p.angle_end_deg - p.angle_start_deg;
  if (!(span > 0.0 && span < 360.0))
    throw InvalidArgument("cylinder panel: angle_end_deg - angle_start_deg must be in (0, 360), got " +
                          std::to_string(span));
  if (p.segments_around < 1 || p.segments_along < 1)
    throw InvalidArgument("cylinder panel: segments_around and segments_along must be >= 1");
  const int na = p.segments_around, nl = p.segments_along;
  std::vector<Vec3> pos;
  pos.reserve(static_cast<std::size_t>((na + 1) * (nl + 1)));
  for (int j = 0; j <= nl; ++j) {
    const double y = p.length * j / nl;
    for (int i = 0; i <= na; ++i) {
      const double th = (p.angle_start_deg + span * i / na) * std::numbers::pi / 180.0;
      pos.emplace_back(p.radius * std::sin(th), y, p.radius * std::cos(th));
    }
  }
  // Quads split along alternating diagonals (no preferred direction). Corner order gives
  // outward normals: d/dtheta x d/dy points away from the axis.
  std::vector<FaceIndices> faces;
  faces.reserve(static_cast<std::size_t>(2 * na * nl));
  const auto id = [na](int i, int j) { return j * (na + 1) + i; };
  for (int j = 0; j < nl; ++j)
    for (int i = 0; i < na; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        faces.push_back({a, b, c});
        faces.push_back({a, c, d});
      } else {
        faces.push_back({a, b, d});
        faces.push_back({b, c, d});
      }
    }
  return SurfaceMesh(std::move(pos), std::move(faces));
}

}  // namespace sutura::engine
