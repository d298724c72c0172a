#include "vessel_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sutura::engine::anatomy {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Cosine ease from 0 to 1 on [0, 1]: C1 with zero slope at both ends.
double ease(double u) { return 0.5 - 0.5 * std::cos(std::numbers::pi * std::clamp(u, 0.0, 1.0)); }

// Parameter in [0, 1] of the point of segment [a, b] closest to p.
double segment_parameter(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 ab = b - a;
  return std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
}

double max_radius(const Curve& c) {
  return *std::max_element(c.radius.knot_r.begin(), c.radius.knot_r.end());
}

}  // namespace

double RadiusProfile::operator()(double s) const {
  double r = knot_r.front();
  if (s >= knot_s.back()) {
    r = knot_r.back();
  } else if (s > knot_s.front()) {
    const auto it = std::upper_bound(knot_s.begin(), knot_s.end(), s);
    const std::size_t i = static_cast<std::size_t>(it - knot_s.begin());  // knot_s[i-1] <= s < knot_s[i]
    const double u = (s - knot_s[i - 1]) / (knot_s[i] - knot_s[i - 1]);
    r = knot_r[i - 1] + (knot_r[i] - knot_r[i - 1]) * ease(u);
  }
  if (narrowed) {
    const double u = std::abs(s - narrow_centre) / narrow_half_length;
    if (u < 1.0) r -= (r - narrow_radius) * (1.0 - ease(u));
  }
  return r;
}

double Curve::length() const {
  double l = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) l += (points[i] - points[i - 1]).norm();
  return l;
}

Vec3 Curve::point_at(double s) const {
  double acc = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double l = (points[i] - points[i - 1]).norm();
    if (s <= acc + l || i + 1 == points.size())
      return points[i - 1] + (points[i] - points[i - 1]) * std::clamp((s - acc) / l, 0.0, 1.0);
    acc += l;
  }
  return points.back();
}

Foot closest_point(const Curve& curve, const Vec3& p) {
  Foot best{kInf, 0.0};
  double acc = 0.0;
  for (std::size_t i = 1; i < curve.points.size(); ++i) {
    const Vec3& a = curve.points[i - 1];
    const Vec3& b = curve.points[i];
    const double l = (b - a).norm();
    const double t = segment_parameter(a, b, p);
    const double d = (a + t * (b - a) - p).norm();
    if (d < best.distance) best = {d, acc + t * l};
    acc += l;
  }
  return best;
}

double smooth_min(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - 0.25 * h * h * k;
}

VesselField::VesselField(std::vector<Curve> curves, double blend)
    : curves_(std::move(curves)), blend_(blend) {
  for (const Curve& c : curves_) {
    Eigen::AlignedBox3d box;
    for (const Vec3& p : c.points) box.extend(p);
    const double pad = max_radius(c) + blend_;
    curve_boxes_.emplace_back(box.min().array() - pad, box.max().array() + pad);
  }
}

double VesselField::value(const Vec3& p) const {
  double f = kInf;
  for (std::size_t c = 0; c < curves_.size(); ++c) {
    // Outside the inflated box the curve's field exceeds blend: it cannot change the union
    // unless nothing else is near, and then a positive "far" value is all that matters.
    const double box_distance = curve_boxes_[c].exteriorDistance(p);
    if (box_distance > 0.0) {
      f = std::min(f, blend_ + box_distance);
      continue;
    }
    const Foot foot = closest_point(curves_[c], p);
    const double fc = foot.distance - curves_[c].radius(foot.s);
    f = std::isinf(f) ? fc : smooth_min(f, fc, blend_);
  }
  return f;
}

Vec3 VesselField::gradient(const Vec3& p) const {
  constexpr double h = 1e-5;
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 a = p, b = p;
    a[k] += h;
    b[k] -= h;
    g[k] = (value(a) - value(b)) / (2.0 * h);
  }
  return g;
}

Vec3 VesselField::project(const Vec3& p) const {
  Vec3 x = p;
  for (int it = 0; it < 30; ++it) {
    const double f = value(x);
    if (std::abs(f) < 1e-10) break;
    const Vec3 g = gradient(x);
    x -= f * g / g.squaredNorm();
  }
  return x;
}

Vec3 VesselField::project_in_plane(const Vec3& p, const Vec3& centre, const Vec3& normal) const {
  Vec3 x = p - (p - centre).dot(normal) * normal;
  for (int it = 0; it < 30; ++it) {
    const double f = value(x);
    if (std::abs(f) < 1e-10) break;
    Vec3 g = gradient(x);
    g -= g.dot(normal) * normal;
    x -= f * g / g.squaredNorm();
    x -= (x - centre).dot(normal) * normal;
  }
  return x;
}

Eigen::AlignedBox3d VesselField::bounds() const {
  Eigen::AlignedBox3d box;
  for (const auto& b : curve_boxes_) box.extend(b);
  return box;
}

std::vector<double> VesselField::sample(const Vec3& origin, double h,
                                        const std::array<int, 3>& n) const {
  const std::size_t count = static_cast<std::size_t>(n[0]) * n[1] * n[2];
  std::vector<double> field(count, kInf);
  std::vector<double> best_d(count), best_s(count);
  auto node = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(n[0]) * (j + static_cast<std::size_t>(n[1]) * k);
  };
  for (const Curve& curve : curves_) {
    std::fill(best_d.begin(), best_d.end(), kInf);
    const double pad = max_radius(curve) + blend_ + 2.0 * h;
    double acc = 0.0;
    for (std::size_t seg = 1; seg < curve.points.size(); ++seg) {
      const Vec3& a = curve.points[seg - 1];
      const Vec3& b = curve.points[seg];
      const double l = (b - a).norm();
      std::array<int, 3> lo{}, hi{};
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::max(0, static_cast<int>(std::floor((std::min(a[d], b[d]) - pad - origin[d]) / h)));
        hi[d] = std::min(n[d] - 1, static_cast<int>(std::ceil((std::max(a[d], b[d]) + pad - origin[d]) / h)));
      }
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i) {
            const Vec3 p = origin + h * Vec3(i, j, k);
            const double t = segment_parameter(a, b, p);
            const double d = (a + t * (b - a) - p).norm();
            const std::size_t id = node(i, j, k);
            if (d < best_d[id]) {
              best_d[id] = d;
              best_s[id] = acc + t * l;
            }
          }
      acc += l;
    }
    for (std::size_t id = 0; id < count; ++id) {
      if (std::isinf(best_d[id])) continue;
      const double fc = best_d[id] - curve.radius(best_s[id]);
      field[id] = std::isinf(field[id]) ? fc : smooth_min(field[id], fc, blend_);
    }
  }
  for (double& f : field)
    if (std::isinf(f)) f = 2.0 * blend_ + h;
  return field;
}

}  // namespace sutura::engine::anatomy
