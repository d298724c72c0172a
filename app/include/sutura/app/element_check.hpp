#pragma once
// Element quality checked before a run: rest triangles (each face's stress-free shape, the x0
// a relaxation pulls towards) so thin that the run cannot stretch them. Below kRefuseDeg the
// window refuses to start; below kWarnDeg it starts but says the run may fail. The limits and
// the runs they come from: docs/gui.md (Simulate).
#include <optional>
#include <string>
#include <vector>

#include "sutura/app/workspace.hpp"

namespace sutura::app {

struct ThinElements {
  std::string object;
  std::size_t count = 0;              ///< rest triangles below the limit
  double smallest_deg = 0.0;          ///< smallest rest angle among them
  std::vector<engine::Vec3> where;    ///< centroids (current positions), at most kMaxMarkers
};

struct ElementCheck {
  static constexpr double kRefuseDeg = 3.0;
  static constexpr double kWarnDeg = 10.0;
  static constexpr std::size_t kMaxMarkers = 500;
  std::vector<ThinElements> refused;  ///< per object with rest angles below kRefuseDeg
  std::vector<ThinElements> warned;   ///< per object with rest angles in [kRefuseDeg, kWarnDeg)
  /// The reason a run is refused, with advice; nullopt when none is.
  [[nodiscard]] std::optional<std::string> refusal() const;
  /// The warning for thin but not refused triangles; nullopt when none.
  [[nodiscard]] std::optional<std::string> warning() const;
};

/// Checks every object's rest triangles. O(total faces).
ElementCheck check_elements(const Workspace& workspace);

/// The smallest interior angle of one object's triangles in the shape shown (its current
/// positions, not the rest shape), degrees, and where it is.
struct SmallestAngle {
  std::string object;
  double degrees = 0.0;
  engine::Vec3 where = engine::Vec3::Zero();  ///< the face's centroid, mm
  double rest_degrees = 0.0;                  ///< the smallest angle of that face's rest shape
};

/// SmallestAngle of every object with faces, in workspace order. O(total faces).
std::vector<SmallestAngle> smallest_angles(const Workspace& workspace);

/// The smallest of `angles` (the first of equals), or nullopt when it is empty. O(n).
std::optional<SmallestAngle> worst_angle(const std::vector<SmallestAngle>& angles);

}  // namespace sutura::app
