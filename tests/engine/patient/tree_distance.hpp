#pragma once
// Test helper: the distance from a point to a centreline tree (its nearest edge segment).
#include <algorithm>
#include <limits>

#include "sutura/engine/measure/centreline.hpp"

namespace sutura::engine {

inline double distance_to_tree(const CentrelineTree& t, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : t.edges) {
    const Vec3 d = t.points[b] - t.points[a];
    const double s = d.squaredNorm() > 0 ? std::clamp((p - t.points[a]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (t.points[a] + s * d)).norm());
  }
  return best;
}

}  // namespace sutura::engine
