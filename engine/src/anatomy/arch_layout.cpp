#include "arch_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine::anatomy {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kArcSegments = 90;          // 2 degrees per segment of the arch half-circle
constexpr double kLandmarkSpacing = 0.5;  // mm between landmark centreline points

double radians(double deg) { return deg * kPi / 180.0; }

RadiusProfile constant_radius(double r) { return {{0.0}, {r}}; }

// Unit tangent by a central difference over +-0.5 mm, so a point on the arch gets the smooth
// circle tangent rather than the direction of one polyline segment.
Vec3 smooth_tangent(const Curve& c, double s) {
  return (c.point_at(s + 0.5) - c.point_at(s - 0.5)).normalized();
}

Centreline sample(std::string name, const Curve& c, double s0, double s1) {
  Centreline out{std::move(name), {}, {}};
  const int n = std::max(2, static_cast<int>(std::ceil((s1 - s0) / kLandmarkSpacing)) + 1);
  for (int i = 0; i < n; ++i) {
    const double s = s0 + (s1 - s0) * i / (n - 1);
    out.points.push_back(c.point_at(s));
    out.radii.push_back(c.radius(s));
  }
  return out;
}

Vec3 bezier(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double t) {
  const double u = 1.0 - t;
  return u * u * u * a + 3.0 * u * u * t * b + 3.0 * u * t * t * c + t * t * t * d;
}

// Smallest wall-to-wall clearance between two sets of centrelines: min |p - q| - r_p - r_q.
double clearance(const std::vector<Centreline>& a, const std::vector<Centreline>& b) {
  double best = std::numeric_limits<double>::infinity();
  for (const Centreline& ca : a)
    for (const Centreline& cb : b)
      for (std::size_t i = 0; i < ca.points.size(); ++i)
        for (std::size_t j = 0; j < cb.points.size(); ++j)
          best = std::min(best, (ca.points[i] - cb.points[j]).norm() - ca.radii[i] - cb.radii[j]);
  return best;
}

std::string mm(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v << " mm";
  return s.str();
}

struct Branch {
  std::string name;
  double angle_deg, diameter, length;
  Vec3 lateral;  // tilt out of the arch plane, added to the outward direction
};

class Builder {
 public:
  explicit Builder(const ArchParams& p) : p_(p) {
    const double tilt = radians(p.arch_tilt_deg);
    d_ = Vec3(std::sin(tilt), std::cos(tilt), 0.0);  // arch plane, horizontal, posterior-left
    e_ = d_.cross(z_);                               // normal of the arch plane, left-anterior
  }

  ArchLayout run() {
    build_aorta();
    build_pulmonary();
    check_clearances();
    return std::move(out_);
  }

 private:
  // Polyline arc length of the main aortic curve at arch angle theta (radians).
  double arch_s(double theta) const {
    const double chord = 2.0 * p_.arch_radius * std::sin(kPi / kArcSegments / 2.0);
    return kEndExtension + p_.ascending_length + chord * theta / (kPi / kArcSegments);
  }

  void build_aorta() {
    const double ha = p_.ascending_length, ra = p_.arch_radius;
    const Vec3 top = ha * z_;
    const Vec3 centre = top + ra * d_;
    Curve main;
    main.points = {-kEndExtension * z_, Vec3::Zero(), top};
    for (int i = 1; i <= kArcSegments; ++i) {
      const double t = kPi * i / kArcSegments;
      main.points.push_back(centre - ra * std::cos(t) * d_ + ra * std::sin(t) * z_);
    }
    const Vec3 arch_end = main.points.back();
    const Vec3 end = arch_end - p_.descending_length * z_;
    main.points.push_back(end);
    main.points.push_back(end - kEndExtension * z_);

    const double s_root = kEndExtension;
    const double s_end = arch_s(kPi) + p_.descending_length;
    const double s_lsa = arch_s(radians(p_.subclavian_angle_deg));
    const double s_coarct = s_lsa + p_.coarctation_offset;
    const double half = 0.5 * p_.coarctation_length;
    main.radius.knot_s = {s_root + ha, arch_s(radians(p_.carotid_angle_deg)), s_lsa,
                          s_coarct - half, s_coarct + half + 3.0};
    main.radius.knot_r = {p_.ascending_diameter / 2, p_.proximal_arch_diameter / 2,
                          p_.distal_arch_diameter / 2, p_.isthmus_diameter / 2,
                          p_.descending_diameter / 2};
    main.radius.narrowed = p_.coarctation_fraction < 1.0;
    main.radius.narrow_centre = s_coarct;
    main.radius.narrow_half_length = half;
    main.radius.narrow_radius = p_.coarctation_fraction * p_.descending_diameter / 2;

    VesselLayout& a = out_.aorta;
    a.centrelines.push_back(sample("aorta", main, s_root, s_end));
    a.ends.push_back({"ascending_root", Vec3::Zero(), -z_, main.radius(s_root)});
    a.ends.push_back({"descending", end, -z_, main.radius(s_end)});

    ArchLandmarks& l = out_.landmarks;
    l.coarctation_centre = main.point_at(s_coarct);
    l.coarctation_axis = smooth_tangent(main, s_coarct);
    l.coarctation_min_radius = main.radius(s_coarct);
    l.coarctation_length = p_.coarctation_length;

    // Branches leave the arch along its outward radial direction tilted upwards, fanned
    // out of the arch plane: innominate to the patient's right, subclavian to the left.
    const Vec3 x(1.0, 0.0, 0.0);
    std::vector<Branch> branches;
    if (p_.head_neck_branches) {
      branches.push_back({"innominate", p_.innominate_angle_deg, p_.innominate_diameter,
                          p_.innominate_length, -0.4 * x});
      branches.push_back({"left_common_carotid", p_.carotid_angle_deg, p_.carotid_diameter,
                          p_.carotid_length, Vec3::Zero()});
    }
    branches.push_back({"left_subclavian", p_.subclavian_angle_deg, p_.lsa_diameter,
                        p_.lsa_length, 0.5 * x});
    a.curves.push_back(main);
    for (const Branch& b : branches) {
      const double theta = radians(b.angle_deg);
      const double s0 = arch_s(theta);
      const Vec3 origin = main.point_at(s0);
      const Vec3 radial = -std::cos(theta) * d_ + std::sin(theta) * z_;
      const Vec3 dir = (radial + z_ + b.lateral).normalized();
      const Vec3 tip = origin + b.length * dir;
      const double r = b.diameter / 2;
      a.curves.push_back({{origin, tip + kEndExtension * dir}, constant_radius(r)});
      a.centrelines.push_back(sample(b.name, a.curves.back(), 0.0, b.length));
      a.ends.push_back({b.name, tip, dir, r});
      ostia_.push_back(ostium(main, origin, dir, b.length));
      if (b.name == "left_subclavian") {
        l.lsa_origin = origin + ostia_.back() * dir;
        l.lsa_axis = dir;
        l.lsa_tip = tip;
        l.lsa_radius = r;
      }
    }
  }

  // Distance along the branch axis from the aortic centreline to the (unblended) aortic wall.
  static double ostium(const Curve& main, const Vec3& origin, const Vec3& dir, double length) {
    double lo = 0.0, hi = length;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      const Foot f = closest_point(main, origin + mid * dir);
      (f.distance < main.radius(f.s) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

  // Trunk from the pulmonary root, left-anterior of the aortic root, up and back to a
  // bifurcation under the arch beside the arch plane; the right branch passes under the arch
  // midway between the ascending and descending aorta, the left one runs posterior-left.
  // With the default dimensions the closest approach is the right branch to the ascending
  // aorta, 2.5 mm wall to wall.
  void build_pulmonary() {
    const double r_trunk = p_.pulmonary_trunk_diameter / 2;
    const double r_branch = p_.pulmonary_branch_diameter / 2;
    const double offset = p_.ascending_diameter / 2 + r_trunk + p_.pulmonary_gap;
    const Vec3 root = (offset + 2.5) * e_ - 2.0 * z_;
    const Vec3 bifurcation = p_.ascending_length * z_ + p_.arch_radius * d_ +
                             (r_trunk + p_.pulmonary_gap + 1.5) * e_ - 3.0 * z_;
    // Straight for the first 3 mm, so the open end is an exact circle in its plane.
    const Vec3 start = root + 3.0 * z_;
    const Vec3 c1 = root + 10.0 * z_;
    const Vec3 c2 = bifurcation - 6.0 * d_ + 3.0 * e_;
    Curve trunk;
    trunk.points.push_back(root - kEndExtension * z_);
    trunk.points.push_back(root);
    for (int i = 0; i <= 64; ++i) trunk.points.push_back(bezier(start, c1, c2, bifurcation, i / 64.0));
    const double len = trunk.length();
    trunk.radius.knot_s = {len - 4.0, len};
    trunk.radius.knot_r = {r_trunk, 0.8 * r_trunk};

    VesselLayout& pa = out_.pulmonary;
    pa.curves.push_back(trunk);
    pa.centrelines.push_back(sample("pulmonary_trunk", trunk, kEndExtension, len));
    pa.ends.push_back({"pulmonary_root", root, -z_, r_trunk});
    const std::vector<std::pair<std::string, Vec3>> branches = {
        {"left_pulmonary", (0.6 * d_ + 0.8 * e_ - 0.2 * z_).normalized()},
        {"right_pulmonary", (-e_ - 0.1 * z_).normalized()}};
    for (const auto& [name, dir] : branches) {
      const Vec3 tip = bifurcation + p_.pulmonary_branch_length * dir;
      pa.curves.push_back({{bifurcation, tip + kEndExtension * dir}, constant_radius(r_branch)});
      pa.centrelines.push_back(sample(name, pa.curves.back(), 0.0, p_.pulmonary_branch_length));
      pa.ends.push_back({name, tip, dir, r_branch});
    }
  }

  void check_clearances() {
    const VesselLayout& a = out_.aorta;
    const double gap = clearance(out_.pulmonary.centrelines, a.centrelines);
    if (gap < p_.pulmonary_gap)
      throw InvalidArgument("arch: pulmonary_gap: the pulmonary artery comes within " + mm(gap) +
                            " of the aorta (required " + mm(p_.pulmonary_gap) +
                            "); reduce pulmonary_branch_diameter or pulmonary_gap, or enlarge "
                            "arch_radius");
    // Branch centrelines 1..n of the aorta, only outside the aortic wall (beyond the ostium).
    for (std::size_t i = 1; i < a.centrelines.size(); ++i)
      for (std::size_t j = i + 1; j < a.centrelines.size(); ++j) {
        auto outside = [&](std::size_t k) {
          const Centreline& c = a.centrelines[k];
          Centreline part{c.name, {}, {}};
          for (std::size_t m = 0; m < c.points.size(); ++m)
            if ((c.points[m] - c.points.front()).norm() >= ostia_[k - 1]) {
              part.points.push_back(c.points[m]);
              part.radii.push_back(c.radii[m]);
            }
          return std::vector<Centreline>{part};
        };
        const double g = clearance(outside(i), outside(j));
        if (g < 0.5)
          throw InvalidArgument("arch: " + a.centrelines[i].name + " and " +
                                a.centrelines[j].name + " come within " + mm(g) +
                                " of each other; spread their *_angle_deg further apart");
      }
  }

  const ArchParams& p_;
  const Vec3 z_{0.0, 0.0, 1.0};
  Vec3 d_, e_;
  std::vector<double> ostia_;  // per branch, centreline-to-wall distance along its axis
  ArchLayout out_;
};

}  // namespace

ArchLayout layout_arch(const ArchParams& p) { return Builder(p).run(); }

}  // namespace sutura::engine::anatomy
