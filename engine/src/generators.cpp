#include "sutura/engine/generators.hpp"

#include <cmath>
#include <numbers>

#include "generator_checks.hpp"

namespace sutura::engine {

using detail::require_at_least;
using detail::require_face_budget;
using detail::require_positive;

namespace {

// Splits the counter-clockwise quad (a, b, c, d) along a-c or b-d.
void add_quad(std::vector<FaceIndices>& faces, std::int32_t a, std::int32_t b, std::int32_t c,
              std::int32_t d, bool diagonal_ac) {
  if (diagonal_ac) {
    faces.push_back({a, b, c});
    faces.push_back({a, c, d});
  } else {
    faces.push_back({a, b, d});
    faces.push_back({b, c, d});
  }
}

}  // namespace

SurfaceMesh make_tube(const TubeParams& p) {
  require_positive("make_tube", "radius", p.radius);
  require_positive("make_tube", "length", p.length);
  require_at_least("make_tube", "segments_around", p.segments_around, 3);
  require_at_least("make_tube", "segments_along", p.segments_along, 1);
  require_face_budget("make_tube",
                      "segments_around = " + std::to_string(p.segments_around) +
                          " and segments_along = " + std::to_string(p.segments_along),
                      2.0 * p.segments_around * p.segments_along);

  const int n = p.segments_around;
  const int m = p.segments_along;
  std::vector<Vec3> positions;
  positions.reserve(static_cast<std::size_t>(n) * (m + 1));
  for (int j = 0; j <= m; ++j) {
    const double z = p.length * j / m;
    for (int i = 0; i < n; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / n;
      positions.emplace_back(p.radius * std::cos(angle), p.radius * std::sin(angle), z);
    }
  }
  std::vector<FaceIndices> faces;
  faces.reserve(2 * static_cast<std::size_t>(n) * m);
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      const int i1 = (i + 1) % n;
      // Counter-clockwise seen from outside: around (+angle) then along (+z) gives the outward
      // radial normal. Alternating diagonals avoid a helical bias in the shell model.
      add_quad(faces, j * n + i, j * n + i1, (j + 1) * n + i1, (j + 1) * n + i, (i + j) % 2 == 0);
    }
  }
  return SurfaceMesh(std::move(positions), std::move(faces));
}

SurfaceMesh make_cylinder_panel(const CylinderPanelParams& p) {
  require_positive("make_cylinder_panel", "radius", p.radius);
  require_positive("make_cylinder_panel", "length", p.length);
  const double span = p.angle_end_deg - p.angle_start_deg;
  if (!(span > 0.0 && span < 360.0))
    throw InvalidArgument("make_cylinder_panel: angle_end_deg - angle_start_deg must be in (0, 360) (got " +
                          detail::format_number(span) + ")");
  require_at_least("make_cylinder_panel", "segments_around", p.segments_around, 1);
  require_at_least("make_cylinder_panel", "segments_along", p.segments_along, 1);
  require_face_budget("make_cylinder_panel",
                      "segments_around = " + std::to_string(p.segments_around) +
                          " and segments_along = " + std::to_string(p.segments_along),
                      2.0 * p.segments_around * p.segments_along);

  const int na = p.segments_around;
  const int nl = p.segments_along;
  std::vector<Vec3> positions;
  positions.reserve(static_cast<std::size_t>(na + 1) * (nl + 1));
  for (int j = 0; j <= nl; ++j) {
    const double y = p.length * j / nl;
    for (int i = 0; i <= na; ++i) {
      const double theta = (p.angle_start_deg + span * i / na) * std::numbers::pi / 180.0;
      positions.emplace_back(p.radius * std::sin(theta), y, p.radius * std::cos(theta));
    }
  }
  std::vector<FaceIndices> faces;
  faces.reserve(2 * static_cast<std::size_t>(na) * nl);
  const auto id = [na](int i, int j) { return j * (na + 1) + i; };
  for (int j = 0; j < nl; ++j)
    for (int i = 0; i < na; ++i)
      // Around (+theta) then along (+y) is counter-clockwise seen from outside: d/dtheta x d/dy
      // points away from the axis.
      add_quad(faces, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
  return SurfaceMesh(std::move(positions), std::move(faces));
}

SurfaceMesh make_strip(const StripParams& p) {
  require_positive("make_strip", "length", p.length);
  require_positive("make_strip", "width", p.width);
  require_at_least("make_strip", "segments_length", p.segments_length, 1);
  require_at_least("make_strip", "segments_width", p.segments_width, 1);
  require_face_budget("make_strip",
                      "segments_length = " + std::to_string(p.segments_length) +
                          " and segments_width = " + std::to_string(p.segments_width),
                      2.0 * p.segments_length * p.segments_width);

  const int nx = p.segments_length;
  const int ny = p.segments_width;
  std::vector<Vec3> positions;
  positions.reserve(static_cast<std::size_t>(nx + 1) * (ny + 1));
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      positions.emplace_back(p.length * i / nx, p.width * (static_cast<double>(j) / ny - 0.5), 0.0);
    }
  }
  std::vector<FaceIndices> faces;
  faces.reserve(2 * static_cast<std::size_t>(nx) * ny);
  const auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      add_quad(faces, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
    }
  }
  return SurfaceMesh(std::move(positions), std::move(faces));
}

}  // namespace sutura::engine
