#include "sutura/render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sutura::render {
namespace {

class BoundsAccumulator {
 public:
  void add(float x, float y, float z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return;
    const float p[3] = {x, y, z};
    for (int i = 0; i < 3; ++i) {
      bounds_[0][i] = std::min(bounds_[0][i], p[i]);
      bounds_[1][i] = std::max(bounds_[1][i], p[i]);
    }
    empty_ = false;
  }
  void add(const Point3& p) { add(p[0], p[1], p[2]); }

  [[nodiscard]] std::array<Point3, 2> result() const {
    if (empty_) return {Point3{-0.5f, -0.5f, -0.5f}, Point3{0.5f, 0.5f, 0.5f}};
    return bounds_;
  }

 private:
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  std::array<Point3, 2> bounds_ = {Point3{kInf, kInf, kInf}, Point3{-kInf, -kInf, -kInf}};
  bool empty_ = true;
};

}  // namespace

std::array<Point3, 2> scene_bounds(const Scene& scene) {
  BoundsAccumulator acc;
  for (const SurfaceItem& s : scene.surfaces) {
    for (std::size_t i = 0; i + 2 < s.positions.size(); i += 3) {
      acc.add(s.positions[i], s.positions[i + 1], s.positions[i + 2]);
    }
  }
  for (const PolylineItem& l : scene.polylines) {
    for (const Point3& p : l.points) acc.add(p);
  }
  for (const PointsItem& p : scene.points) {
    for (const Point3& q : p.points) acc.add(q);
  }
  return acc.result();
}

}  // namespace sutura::render
