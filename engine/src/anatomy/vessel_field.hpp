#pragma once
// Implicit vessel surfaces (internal to the anatomy generators).
//
// A vessel object is a set of centreline curves, each a polyline with a radius profile
// r(s) over its arc length s. One curve's field is the "generalised tube" function
//     f_c(p) = |p - c(s*)| - r(s*),   c(s*) = closest point of the polyline to p,
// whose zero set is the circle of radius r(s) in the normal plane at s. Unlike a swept sphere
// (min over s of |p - c(s)| - r(s)), it keeps a sharp narrowing such as a coarctation at its
// true radius even where r'' > 1/r. The object's field is the smooth union (polynomial smooth
// minimum, Quilez) of its curves' fields, in curve order, so that branches meet their parent
// with a fillet of about `blend` mm instead of a crease. Negative inside, positive outside;
// the gradient is not unit length (|grad f| ~ sqrt(1 + r'^2) near the wall), so projections
// use Newton steps rather than f * grad f.
#include <array>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine::anatomy {

/// Piecewise radius profile over arc length: knots (s, r) joined by cosine ease (C1, flat at
/// every knot), constant before the first and after the last knot, optionally times a local
/// narrowing that reaches `narrow_radius` at `narrow_centre` and blends back over
/// `narrow_half_length` on each side (raised-cosine shape).
struct RadiusProfile {
  std::vector<double> knot_s;  ///< mm, increasing
  std::vector<double> knot_r;  ///< mm, > 0
  bool narrowed = false;
  double narrow_centre = 0.0;       ///< mm of arc length
  double narrow_half_length = 1.0;  ///< mm, > 0
  double narrow_radius = 1.0;       ///< mm, the radius at narrow_centre

  [[nodiscard]] double operator()(double s) const;
};

/// One centreline: polyline points with cumulative arc length, and its radius profile.
struct Curve {
  std::vector<Vec3> points;  ///< >= 2 points, consecutive points distinct
  RadiusProfile radius;

  [[nodiscard]] double length() const;
  /// Point at arc length s (clamped to [0, length]).
  [[nodiscard]] Vec3 point_at(double s) const;
};

/// Closest point of a polyline to p: distance and arc length of the foot point. O(points).
struct Foot {
  double distance;
  double s;
};
Foot closest_point(const Curve& curve, const Vec3& p);

/// Polynomial smooth minimum with blend width k (mm): equals min(a, b) when |a - b| >= k.
double smooth_min(double a, double b, double k);

/// A vessel object's implicit field. Cost per evaluation O(total polyline points).
class VesselField {
 public:
  VesselField(std::vector<Curve> curves, double blend);

  [[nodiscard]] double blend() const { return blend_; }
  [[nodiscard]] double value(const Vec3& p) const;
  /// Central-difference gradient (step 1e-5 mm).
  [[nodiscard]] Vec3 gradient(const Vec3& p) const;
  /// Newton projection onto f = 0 (at most 30 steps, |f| < 1e-10 mm). Stays within about one
  /// radius of p for points near the wall.
  [[nodiscard]] Vec3 project(const Vec3& p) const;
  /// Projection onto the curve {f = 0} ∩ {(x - centre) . normal = 0}: alternates the exact
  /// plane projection with Newton steps along the in-plane gradient.
  [[nodiscard]] Vec3 project_in_plane(const Vec3& p, const Vec3& centre, const Vec3& normal) const;
  /// Bounding box of every curve's tube (points inflated by their largest radius + blend).
  [[nodiscard]] Eigen::AlignedBox3d bounds() const;
  /// The field at the nodes origin + h * (i, j, k) of an n[0] x n[1] x n[2] grid, node index
  /// i + n0 * (j + n1 * k). Each polyline segment scatters its distance into the nodes of its
  /// inflated box only, so the cost is O(segments * (tube box / h)^3), not O(nodes * segments).
  /// Far from every tube the value is a positive number (> blend), not the true field.
  [[nodiscard]] std::vector<double> sample(const Vec3& origin, double h,
                                           const std::array<int, 3>& n) const;

 private:
  std::vector<Curve> curves_;
  std::vector<Eigen::AlignedBox3d> curve_boxes_;  // polyline box inflated by max radius + blend
  double blend_;
};

}  // namespace sutura::engine::anatomy
