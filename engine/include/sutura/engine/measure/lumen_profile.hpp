#pragma once
// Lumen profile along a vessel: cross-sections at stations along a centreline, and the
// narrowest station (a residual coarctation, a stenosed anastomosis).
#include <optional>
#include <vector>

#include "sutura/engine/measure/cross_section.hpp"

namespace sutura::engine {

struct LumenProfileParams {
  int stations = 20;  ///< >= 1; station k sits at arc length (k + 1/2) / stations * length
  /// mm, > 0: passed to every cross-section (keeps other branches out). Default: no limit.
  double max_radius = std::numeric_limits<double>::infinity();
};

struct LumenStation {
  double arc_length = 0.0;  ///< mm from the first centreline point
  Plane plane;              ///< origin on the centreline, unit normal = centreline tangent
  /// The station's section; empty when the plane does not cut the surface there (the
  /// centreline left the vessel).
  std::optional<CrossSection> section;
};

struct LumenProfile {
  std::vector<LumenStation> stations;
  /// Station with the smallest lumen area among those with a closed section; empty when no
  /// station has one.
  std::optional<std::size_t> min_area_station;
};

/// Samples `params.stations` planes perpendicular to the centreline polyline (>= 2 points,
/// consecutive points distinct) at equal arc-length spacing, cell-centred so that no plane
/// sits on the ends of an open vessel. The tangent at arc length s is the central difference
/// c(s + h) - c(s - h) of the polyline with h = half the station spacing (one-sided at the
/// ends), so it turns smoothly across polyline corners. Throws InvalidArgument for fewer than
/// two points, a repeated or non-finite point, or stations < 1. Cost: stations cross-sections.
LumenProfile lumen_profile(const SurfaceMesh& mesh, const std::vector<Vec3>& centreline,
                           const LumenProfileParams& params = {});

}  // namespace sutura::engine
