#include "sutura/engine/generators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "generator_checks.hpp"

// Patches: flat ellipse, diamond and triangle meshes (make_patch).
//
// The patch is meshed in rings around a "skeleton": a point or a short segment on the patch's
// symmetry axis. Ring s in (0, 1] is the curve
//     R_s(theta) = anchor(theta) + s * rho(theta) * (cos theta, sin theta),
// anchor(theta) = centre + (cx cos theta, cy sin theta) on the skeleton, rho the distance from the
// anchor to the outline along that ray; R_1 is the outline. For a point skeleton these are the
// classic concentric scaled rings. The segment matters for elongated shapes: scaling a 20 x 8
// ellipse about its centre spaces the rings 2.5 times wider at the tips than at the sides, while
// rays from the segment [-(a-b), a-b] all have length b, so the rings stay evenly spaced. Rays of
// different theta never cross, so the rings are nested. Neighbouring rings (and the innermost ring
// and the skeleton) are zipped together by merging their points in theta order. Lawson edge
// flips then make the triangulation Delaunay, removing the thin triangles the zipping leaves
// where the rings' point counts differ, and a few rounds of Laplacian smoothing (each followed
// by flips) even out the spacing. Everything is planar and deterministic.
namespace sutura::engine {

using detail::format_number;
using detail::require_face_budget;
using detail::require_positive;

namespace {

using Vec2 = Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Convex outline, symmetric about the x axis: an ellipse (no corners) or a polygon.
struct Outline {
  double semi_x = 0.0, semi_y = 0.0;  // ellipse semi-axes
  std::vector<Vec2> corners;          // polygon, counter-clockwise
  Eigen::AlignedBox2d box;
};

Outline make_outline(const PatchParams& p) {
  const double a = 0.5 * p.length;
  const double b = 0.5 * p.width;
  Outline o;
  o.box = Eigen::AlignedBox2d(Vec2(-a, -b), Vec2(a, b));
  switch (p.shape) {
    case PatchShape::Ellipse:
      o.semi_x = a;
      o.semi_y = b;
      break;
    case PatchShape::Diamond:
      o.corners = {Vec2(a, 0.0), Vec2(0.0, b), Vec2(-a, 0.0), Vec2(0.0, -b)};
      break;
    case PatchShape::Triangle:
      o.corners = {Vec2(-a, -b), Vec2(a, 0.0), Vec2(-a, b)};
      break;
  }
  return o;
}

bool strictly_inside(const Outline& o, const Vec2& q) {
  if (o.corners.empty()) return std::pow(q.x() / o.semi_x, 2) + std::pow(q.y() / o.semi_y, 2) < 1.0;
  for (std::size_t k = 0; k < o.corners.size(); ++k) {
    const Vec2 e = o.corners[(k + 1) % o.corners.size()] - o.corners[k];
    const Vec2 outward(e.y(), -e.x());
    if (outward.dot(q - o.corners[k]) >= 0.0) return false;
  }
  return true;
}

// Distance from q (strictly inside) along the unit direction u to the outline.
double exit_distance(const Outline& o, const Vec2& q, const Vec2& u) {
  if (o.corners.empty()) {
    // Positive root of |D(q + t u)|^2 = 1 with D = diag(1/a, 1/b).
    const Vec2 qs(q.x() / o.semi_x, q.y() / o.semi_y);
    const Vec2 us(u.x() / o.semi_x, u.y() / o.semi_y);
    const double A = us.squaredNorm();
    const double B = qs.dot(us);
    const double C = qs.squaredNorm() - 1.0;
    return (-B + std::sqrt(B * B - A * C)) / A;
  }
  double t = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < o.corners.size(); ++k) {
    const Vec2 e = o.corners[(k + 1) % o.corners.size()] - o.corners[k];
    const Vec2 outward(e.y(), -e.x());
    const double speed = outward.dot(u);
    if (speed > 0.0) t = std::min(t, outward.dot(o.corners[k] - q) / speed);
  }
  return t;
}

Vec2 direction(double theta) { return {std::cos(theta), std::sin(theta)}; }

struct Skeleton {
  Vec2 centre = Vec2::Zero();
  Vec2 half_axis = Vec2::Zero();  // (c, 0) or (0, c); zero for a point

  [[nodiscard]] Vec2 anchor(double theta) const {
    return centre + Vec2(half_axis.x() * std::cos(theta), half_axis.y() * std::sin(theta));
  }
  [[nodiscard]] bool is_point() const { return half_axis.isZero(); }
};

struct RaySpread {
  double min = std::numeric_limits<double>::infinity(), max = 0.0, mean = 0.0;
};

RaySpread ray_spread(const Outline& o, const Skeleton& s) {
  constexpr int kDirections = 64;
  RaySpread r;
  for (int k = 0; k < kDirections; ++k) {
    const double theta = kTwoPi * k / kDirections;
    const double rho = exit_distance(o, s.anchor(theta), direction(theta));
    r.min = std::min(r.min, rho);
    r.max = std::max(r.max, rho);
    r.mean += rho / kDirections;
  }
  return r;
}

// The skeleton whose rays to the outline are most even (largest min/max length ratio), found by
// a small grid search over centres on the x axis, both orientations and half-lengths. Exact
// optimum is not needed; the search is cheap (2 * 32 * 32 * 64 ray casts) and deterministic.
Skeleton choose_skeleton(const Outline& o) {
  constexpr int kGrid = 32;  // even, so that the box centre is a candidate
  Skeleton best;
  double best_ratio = -1.0;
  const Vec2 size = o.box.sizes();
  for (int axis = 0; axis < 2; ++axis) {
    for (int i = 1; i < kGrid; ++i) {
      for (int j = 0; j < kGrid; ++j) {
        Skeleton s;
        s.centre = Vec2(o.box.min().x() + size.x() * i / kGrid, 0.0);
        s.half_axis[axis] = 0.5 * size[axis] * j / kGrid;
        if (!strictly_inside(o, s.centre + s.half_axis) ||
            !strictly_inside(o, s.centre - s.half_axis)) {
          continue;
        }
        const RaySpread r = ray_spread(o, s);
        if (r.min / r.max > best_ratio + 1e-12) {
          best_ratio = r.min / r.max;
          best = s;
        }
      }
    }
  }
  return best;
}

struct RingPoint {
  std::int32_t id;
  double theta;  // in [0, 2 pi)
};

class PatchBuilder {
 public:
  PatchBuilder(const Outline& outline, const Skeleton& skeleton, double h)
      : outline_(outline), skeleton_(skeleton), h_(h) {}

  [[nodiscard]] Vec2 ring_point(double theta, double s) const {
    const Vec2 q = skeleton_.anchor(theta);
    const Vec2 u = direction(theta);
    return q + s * exit_distance(outline_, q, u) * u;
  }

  // The ray parameter theta that hits outline point p. The outline point moves monotonically
  // counter-clockwise with theta (rays do not cross), and so does its polar angle about the
  // skeleton centre, so bisection on that angle converges to p.
  [[nodiscard]] double theta_of(const Vec2& p) const {
    const auto polar = [&](const Vec2& x) {
      const Vec2 d = x - skeleton_.centre;
      const double phi = std::atan2(d.y(), d.x());
      return phi < 0.0 ? phi + kTwoPi : phi;
    };
    const double target = polar(p);
    double lo = 0.0, hi = kTwoPi;
    for (int iter = 0; iter < 200 && hi - lo > 1e-15; ++iter) {
      const double mid = 0.5 * (lo + hi);
      (polar(ring_point(mid, 1.0)) < target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

  // Appends the points of ring s: each interval between consecutive features (sorted, starting
  // at 0) is split into pieces of length close to h.
  std::vector<RingPoint> add_ring(double s, const std::vector<double>& features) {
    std::vector<RingPoint> ring;
    const std::size_t intervals = features.size();
    for (std::size_t k = 0; k < intervals; ++k) {
      const double t0 = features[k];
      const double t1 = k + 1 < intervals ? features[k + 1] : kTwoPi;
      // Arc length table over the interval, fine enough to place the points accurately.
      const int samples = table_samples(s, t0, t1);
      std::vector<double> arc(samples + 1, 0.0);
      Vec2 last = ring_point(t0, s);
      for (int j = 1; j <= samples; ++j) {
        const Vec2 x = ring_point(t0 + (t1 - t0) * j / samples, s);
        arc[j] = arc[j - 1] + (x - last).norm();
        last = x;
      }
      const int pieces = std::max(1, static_cast<int>(std::lround(arc.back() / h_)));
      for (int i = 0; i < pieces; ++i) {
        const double target = arc.back() * i / pieces;
        const auto it = std::upper_bound(arc.begin(), arc.end(), target);
        const auto j = static_cast<int>(std::clamp<std::ptrdiff_t>(it - arc.begin(), 1, samples));
        const double span = arc[j] - arc[j - 1];
        const double frac = span > 0.0 ? (target - arc[j - 1]) / span : 0.0;
        const double theta = t0 + (t1 - t0) * (j - 1 + frac) / samples;
        ring.push_back({add_vertex(ring_point(theta, s)), theta});
      }
    }
    return ring;
  }

  // Skeleton points in ray order: a segment is a degenerate loop that visits its interior
  // points twice (once from each side), the same vertex ids both times.
  std::vector<RingPoint> add_skeleton() {
    if (skeleton_.is_point()) return {{add_vertex(skeleton_.centre), 0.0}};
    const double c = skeleton_.half_axis.norm();
    const bool along_x = skeleton_.half_axis.x() != 0.0;
    const int pieces = std::max(1, static_cast<int>(std::lround(2.0 * c / h_)));
    std::vector<RingPoint> loop;
    for (int k = 0; k <= pieces; ++k) {
      const double t = 1.0 - 2.0 * k / pieces;  // position along the skeleton, 1 .. -1
      const std::int32_t id = add_vertex(skeleton_.centre + t * skeleton_.half_axis);
      // anchor(theta) = centre + t * half_axis solves cos(theta) = t (x) or sin(theta) = t (y);
      // the ends have one solution, interior points two.
      const double first = along_x ? std::acos(t) : std::asin(t);
      const double second = along_x ? kTwoPi - first : kPi - first;
      loop.push_back({id, first < 0.0 ? first + kTwoPi : first});
      if (k != 0 && k != pieces) loop.push_back({id, second});
    }
    std::sort(loop.begin(), loop.end(),
              [](const RingPoint& x, const RingPoint& y) { return x.theta < y.theta; });
    return loop;
  }

  // Triangulates the band between two loops sorted by theta. A single inner point gets a fan.
  // Otherwise the loops are merged in theta order (ties advance the inner loop, so that at a
  // skeleton end the tip is passed on the inner side first); a step whose triangle would not be
  // counter-clockwise takes the other loop instead, which only happens where an outer point lies
  // on the skeleton's axis next to a skeleton end.
  void zip(const std::vector<RingPoint>& inner, const std::vector<RingPoint>& outer) {
    const std::size_t ni = inner.size();
    const std::size_t no = outer.size();
    if (ni == 1) {
      for (std::size_t o = 0; o < no; ++o) {
        faces_.push_back({outer[o].id, outer[(o + 1) % no].id, inner[0].id});
      }
      return;
    }
    const auto next_theta = [](const std::vector<RingPoint>& loop, std::size_t k) {
      return k + 1 < loop.size() ? loop[k + 1].theta : loop[0].theta + kTwoPi;
    };
    std::size_t i = 0, o = 0;
    while (i < ni || o < no) {
      const FaceIndices by_outer = {outer[o % no].id, outer[(o + 1) % no].id, inner[i % ni].id};
      const FaceIndices by_inner = {inner[i % ni].id, outer[o % no].id, inner[(i + 1) % ni].id};
      bool advance_outer = i == ni || (o < no && next_theta(outer, o) < next_theta(inner, i));
      if (i < ni && o < no && !counter_clockwise(advance_outer ? by_outer : by_inner)) {
        advance_outer = !advance_outer;
      }
      if (advance_outer) {
        faces_.push_back(by_outer);
        ++o;
      } else {
        faces_.push_back(by_inner);
        ++i;
      }
    }
  }

  // Lawson flips until every interior edge is locally Delaunay (the two angles opposite the
  // edge sum to at most pi). Each pass flips edges whose faces were not touched earlier in the
  // pass, in sorted edge order (deterministic). Flips keep faces counter-clockwise because an
  // edge failing the test always has a convex quad; the check is kept against round-off.
  void make_delaunay() {
    constexpr int kMaxPasses = 200;
    for (int pass = 0; pass < kMaxPasses; ++pass) {
      const std::vector<HalfedgeKey> keys = sorted_halfedges();
      std::vector<char> touched(faces_.size(), 0);
      bool flipped = false;
      for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
        if (keys[k].lo != keys[k + 1].lo || keys[k].hi != keys[k + 1].hi) continue;
        const std::size_t f = keys[k].h / 3, g = keys[k + 1].h / 3;
        if (touched[f] || touched[g]) continue;
        // f = (a, b, c) with the edge a->b, g = (b, a, d).
        const std::size_t cf = keys[k].h % 3, cg = keys[k + 1].h % 3;
        const std::int32_t a = faces_[f][cf], b = faces_[f][(cf + 1) % 3];
        const std::int32_t c = faces_[f][(cf + 2) % 3], d = faces_[g][(cg + 2) % 3];
        if (!should_flip(a, b, c, d)) continue;
        faces_[f] = {a, d, c};
        faces_[g] = {d, b, c};
        touched[f] = touched[g] = 1;
        flipped = true;
      }
      if (!flipped) break;
    }
  }

  // One Gauss-Seidel sweep of Laplacian smoothing: each interior vertex moves to the centroid of
  // its neighbours unless that would turn one of its faces clockwise. Evens out the uneven
  // spacing between rings of different point counts; boundary vertices stay on the outline.
  void smooth() {
    const std::size_t nv = points_.size();
    std::vector<char> on_boundary(nv, 0);
    const std::vector<HalfedgeKey> keys = sorted_halfedges();
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const bool paired =
          (k > 0 && keys[k - 1].lo == keys[k].lo && keys[k - 1].hi == keys[k].hi) ||
          (k + 1 < keys.size() && keys[k + 1].lo == keys[k].lo && keys[k + 1].hi == keys[k].hi);
      if (!paired) on_boundary[keys[k].lo] = on_boundary[keys[k].hi] = 1;
    }
    std::vector<std::vector<std::size_t>> incident(nv);
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      for (std::int32_t v : faces_[f]) incident[v].push_back(f);
    }
    for (std::size_t v = 0; v < nv; ++v) {
      if (on_boundary[v]) continue;
      // Each neighbour of an interior vertex lies in exactly two of its faces.
      Vec2 sum = Vec2::Zero();
      for (std::size_t f : incident[v]) {
        for (std::int32_t u : faces_[f]) {
          if (static_cast<std::size_t>(u) != v) sum += points_[u];
        }
      }
      const Vec2 old = points_[v];
      points_[v] = sum / (2.0 * static_cast<double>(incident[v].size()));
      for (std::size_t f : incident[v]) {
        if (!counter_clockwise(faces_[f])) {
          points_[v] = old;
          break;
        }
      }
    }
  }

  SurfaceMesh finish() {
    std::vector<Vec3> positions;
    positions.reserve(points_.size());
    for (const Vec2& p : points_) positions.emplace_back(p.x(), p.y(), 0.0);
    return SurfaceMesh(std::move(positions), std::move(faces_));
  }

 private:
  struct HalfedgeKey {
    std::int32_t lo, hi;  // the undirected edge
    std::size_t h;
  };

  // Half-edges sorted by undirected edge: a pair of equal neighbours is an interior edge.
  [[nodiscard]] std::vector<HalfedgeKey> sorted_halfedges() const {
    std::vector<HalfedgeKey> keys;
    keys.reserve(3 * faces_.size());
    for (std::size_t h = 0; h < 3 * faces_.size(); ++h) {
      const std::int32_t a = faces_[h / 3][h % 3];
      const std::int32_t b = faces_[h / 3][(h % 3 + 1) % 3];
      keys.push_back({std::min(a, b), std::max(a, b), h});
    }
    std::sort(keys.begin(), keys.end(), [](const HalfedgeKey& x, const HalfedgeKey& y) {
      return std::tie(x.lo, x.hi, x.h) < std::tie(y.lo, y.hi, y.h);
    });
    return keys;
  }

  std::int32_t add_vertex(const Vec2& p) {
    points_.push_back(p);
    return static_cast<std::int32_t>(points_.size() - 1);
  }

  [[nodiscard]] double cross(std::int32_t o, std::int32_t a, std::int32_t b) const {
    const Vec2 u = points_[a] - points_[o];
    const Vec2 v = points_[b] - points_[o];
    return u.x() * v.y() - u.y() * v.x();
  }

  [[nodiscard]] bool counter_clockwise(const FaceIndices& t) const {
    return cross(t[0], t[1], t[2]) > 0.0;
  }

  // Edge a-b with c on its left and d on its right.
  [[nodiscard]] bool should_flip(std::int32_t a, std::int32_t b, std::int32_t c,
                                 std::int32_t d) const {
    const auto cot = [&](std::int32_t apex, std::int32_t p, std::int32_t q) {
      return (points_[p] - points_[apex]).dot(points_[q] - points_[apex]) / cross(apex, p, q);
    };
    // Opposite angles sum above pi <=> their cotangents sum below 0; the margin stops
    // co-circular quads from flipping back and forth.
    if (cot(c, a, b) + cot(d, b, a) >= -1e-9) return false;
    return cross(a, d, c) > 0.0 && cross(d, b, c) > 0.0;
  }

  [[nodiscard]] int table_samples(double s, double t0, double t1) const {
    constexpr int kCoarse = 64;
    double length = 0.0;
    for (int j = 0; j < kCoarse; ++j) {
      length += (ring_point(t0 + (t1 - t0) * (j + 1) / kCoarse, s) -
                 ring_point(t0 + (t1 - t0) * j / kCoarse, s))
                    .norm();
    }
    return kCoarse + 16 * static_cast<int>(std::ceil(length / h_));
  }

  const Outline& outline_;
  Skeleton skeleton_;
  double h_;
  std::vector<Vec2> points_;
  std::vector<FaceIndices> faces_;
};

double patch_area(const PatchParams& p) {
  return p.shape == PatchShape::Ellipse ? kPi * p.length * p.width / 4.0 : p.length * p.width / 2.0;
}

}  // namespace

SurfaceMesh make_patch(const PatchParams& p) {
  require_positive("make_patch", "length", p.length);
  require_positive("make_patch", "width", p.width);
  require_positive("make_patch", "target_edge_length", p.target_edge_length);
  // An equilateral mesh of edge h has 4 / (sqrt(3) h^2) triangles per unit area.
  require_face_budget("make_patch", "target_edge_length = " + format_number(p.target_edge_length),
                      2.31 * patch_area(p) / (p.target_edge_length * p.target_edge_length), p.max_faces);

  const Outline outline = make_outline(p);
  Skeleton skeleton = choose_skeleton(outline);
  RaySpread spread = ray_spread(outline, skeleton);
  // A segment skeleton needs at least two rings (see below), a point one. When the patch is
  // too narrow for that at the requested spacing, the spacing shrinks to fit: edges longer than
  // the rings' spacing across a narrow patch only make flat, badly shaped triangles.
  double h = std::min(p.target_edge_length, spread.mean / 2.0);
  // A skeleton shorter than about half an edge is just its centre point.
  if (std::lround(2.0 * skeleton.half_axis.norm() / h) == 0) {
    skeleton.half_axis.setZero();
    spread = ray_spread(outline, skeleton);
    h = std::min(p.target_edge_length, spread.mean);
  }
  const int min_rings = skeleton.is_point() ? 1 : 2;
  // The spacing may have shrunk to fit a narrow patch: the budget again, at the spacing used
  // (a diamond 1e-5 mm long and 2 mm wide meshed ring after ring for minutes).
  if (h < p.target_edge_length)
    require_face_budget("make_patch", "a patch of " + format_number(p.length) + " x " + format_number(p.width) +
                                          " mm, narrowed to a spacing of " + format_number(h) + " mm,",
                        2.31 * patch_area(p) / (h * h), p.max_faces);

  PatchBuilder builder(outline, skeleton, h);
  constexpr int kSmoothingRounds = 4;

  // Ring features: the rays along the axes and through the outline's corners. Every ring has a
  // point on each, so corners are kept exactly, the mesh is as symmetric as the shape, and no
  // ring chord cuts the skeleton (whose ends lie on the axis rays).
  std::vector<double> features = {0.0, 0.5 * kPi, kPi, 1.5 * kPi};
  for (const Vec2& corner : outline.corners) features.push_back(builder.theta_of(corner));
  for (double& t : features) {
    if (t >= kTwoPi - 1e-9) t = 0.0;
  }
  std::sort(features.begin(), features.end());
  features.erase(std::unique(features.begin(), features.end(),
                             [](double x, double y) { return y - x < 1e-9; }),
                 features.end());

  // A segment skeleton needs at least one ring strictly inside the outline: the outline's
  // feature points on the skeleton's axis would otherwise be zipped against the skeleton.
  const int rings = std::max(min_rings, static_cast<int>(std::lround(spread.mean / h)));

  std::vector<RingPoint> inner = builder.add_skeleton();
  for (int k = 1; k <= rings; ++k) {
    std::vector<RingPoint> outer = builder.add_ring(static_cast<double>(k) / rings, features);
    builder.zip(inner, outer);
    inner = std::move(outer);
  }
  builder.make_delaunay();
  for (int round = 0; round < kSmoothingRounds; ++round) {
    builder.smooth();
    builder.make_delaunay();
  }
  return builder.finish();
}

PatchShape parse_patch_shape(const std::string& name) {
  if (name == "ellipse") return PatchShape::Ellipse;
  if (name == "diamond") return PatchShape::Diamond;
  if (name == "triangle") return PatchShape::Triangle;
  throw InvalidArgument("unknown patch shape \"" + name +
                        "\" (expected \"ellipse\", \"diamond\" or \"triangle\")");
}

}  // namespace sutura::engine
