#include "sutura/engine/measure/cross_section.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "planar_polygon.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

using detail::Vec2;

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

// One face's piece of the section, directed from the crossing of the edge whose corner order
// runs from the positive to the negative side to the crossing of the edge running back. The
// shared edge of two neighbouring faces is traversed in opposite directions by them, so on a
// consistently oriented manifold every crossed edge starts at most one segment and ends at
// most one: the chains follow the face orientation.
struct Segment {
  std::uint64_t from = 0, to = 0;
  std::int32_t face = 0;
};

struct Chain {
  std::vector<Vec3> points;
  bool closed = false;
  std::int32_t first_face = 0;  // smallest face index on the chain (deterministic order)
};

// Orthonormal (u, v) with u x v = n.
std::pair<Vec3, Vec3> plane_basis(const Vec3& n) {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[axis])) axis = k;
  const Vec3 u = n.cross(Vec3::Unit(axis)).normalized();
  return {u, n.cross(u)};
}

// Crossing number test of the origin against the closed polygon.
bool contains_origin(const std::vector<Vec2>& poly) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > 0.0) != (b.y() > 0.0) && 0.0 < a.x() + (0.0 - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside;
}

double distance_to_segment(const Vec3& q, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - q).norm();
}

double distance_to_chain(const Vec3& q, const Chain& c) {
  double best = (c.points.front() - q).norm();
  const std::size_t n = c.points.size();
  const std::size_t segments = c.closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i)
    best = std::min(best, distance_to_segment(q, c.points[i], c.points[(i + 1) % n]));
  return best;
}

std::vector<Chain> trace_chains(std::span<const Vec3> positions, std::span<const FaceIndices> faces,
                                const Vec3& origin, const Vec3& n, double max_radius) {
  const auto nv = static_cast<std::int32_t>(positions.size());
  std::vector<double> s(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) s[v] = (positions[v] - origin).dot(n);
  const auto positive = [&](std::int32_t v) { return s[static_cast<std::size_t>(v)] >= 0.0; };
  // Crossing point of edge {a, b}, computed from the lower id so both faces get the same bits.
  const auto crossing = [&](std::uint64_t key) -> Vec3 {
    const auto a = static_cast<std::size_t>(key >> 32), b = static_cast<std::size_t>(key & 0xffffffffu);
    if (s[a] == 0.0) return positions[a];
    if (s[b] == 0.0) return positions[b];
    const double t = s[a] / (s[a] - s[b]);
    return positions[a] + t * (positions[b] - positions[a]);
  };

  std::vector<Segment> segments;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const FaceIndices& c = faces[f];
    for (std::int32_t v : c)
      if (v < 0 || v >= nv)
        throw InvalidArgument("cross_section: face " + std::to_string(f) + " references vertex " +
                              std::to_string(v) + " of " + std::to_string(nv));
    Segment seg;
    seg.face = static_cast<std::int32_t>(f);
    int found = 0;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = c[k], b = c[(k + 1) % 3];
      if (positive(a) == positive(b)) continue;
      ++found;
      (positive(a) ? seg.from : seg.to) = edge_key(a, b);
    }
    if (found == 0) continue;
    if ((crossing(seg.from) - origin).norm() > max_radius ||
        (crossing(seg.to) - origin).norm() > max_radius)
      continue;
    segments.push_back(seg);
  }

  // Nodes = crossed edges (sorted keys); succ/pred link them through the segments.
  std::vector<std::uint64_t> keys;
  keys.reserve(2 * segments.size());
  for (const Segment& seg : segments) keys.insert(keys.end(), {seg.from, seg.to});
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const auto node = [&](std::uint64_t k) {
    return static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), k) - keys.begin());
  };
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> succ(keys.size(), kNone), pred(keys.size(), kNone);
  std::vector<std::int32_t> succ_face(keys.size(), 0);
  for (const Segment& seg : segments) {
    const std::size_t a = node(seg.from), b = node(seg.to);
    if (succ[a] != kNone || pred[b] != kNone)
      throw InvalidArgument("cross_section: an edge near face " + std::to_string(seg.face) +
                            " is used by more than two faces or the faces are inconsistently "
                            "oriented");
    succ[a] = b, pred[b] = a, succ_face[a] = seg.face;
  }

  std::vector<Chain> chains;
  std::vector<bool> visited(keys.size(), false);
  const auto trace = [&](std::size_t start) {
    Chain c;
    c.first_face = std::numeric_limits<std::int32_t>::max();
    std::size_t k = start;
    while (true) {
      visited[k] = true;
      const Vec3 p = crossing(keys[k]);
      if (c.points.empty() || p != c.points.back()) c.points.push_back(p);
      if (succ[k] == kNone) break;
      c.first_face = std::min(c.first_face, succ_face[k]);
      k = succ[k];
      if (k == start) {
        c.closed = true;
        break;
      }
    }
    if (c.closed && c.points.size() > 1 && c.points.back() == c.points.front()) c.points.pop_back();
    if (c.points.size() >= 2) chains.push_back(std::move(c));
  };
  for (std::size_t k = 0; k < keys.size(); ++k)
    if (pred[k] == kNone) trace(k);  // open chains start where nothing leads in
  for (std::size_t k = 0; k < keys.size(); ++k)
    if (!visited[k]) trace(k);  // the rest are loops
  std::sort(chains.begin(), chains.end(),
            [](const Chain& a, const Chain& b) { return a.first_face < b.first_face; });
  return chains;
}

}  // namespace

CrossSection cross_section(std::span<const Vec3> positions, std::span<const FaceIndices> faces,
                           const Plane& plane, const CrossSectionParams& params) {
  const double nn = plane.normal.norm();
  if (!(nn > 0.0) || !std::isfinite(nn))
    throw InvalidArgument("cross_section: the plane normal must be finite and non-zero");
  if (!plane.origin.allFinite()) throw InvalidArgument("cross_section: the plane origin must be finite");
  if (!(params.max_radius > 0.0))
    throw InvalidArgument("cross_section: max_radius must be positive");
  const Vec3 n = plane.normal / nn;
  const Vec3& o = plane.origin;
  std::vector<Chain> chains = trace_chains(positions, faces, o, n, params.max_radius);
  if (chains.empty())
    throw InvalidArgument(std::isfinite(params.max_radius)
                              ? "cross_section: the plane does not cut the surface within max_radius " +
                                    std::to_string(params.max_radius) + " of its origin"
                              : std::string("cross_section: the plane does not cut the surface"));

  const auto [u, v] = plane_basis(n);
  const auto project = [&, u = u, v = v](const std::vector<Vec3>& pts) {
    std::vector<Vec2> q;
    q.reserve(pts.size());
    for (const Vec3& p : pts) q.emplace_back((p - o).dot(u), (p - o).dot(v));
    return q;
  };

  // The smallest closed loop around the origin, else the chain nearest to it.
  std::size_t pick = chains.size();
  double pick_area = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < chains.size(); ++i) {
    if (!chains[i].closed || chains[i].points.size() < 3) continue;
    const std::vector<Vec2> q = project(chains[i].points);
    const double a = std::abs(detail::signed_area(q));
    if (contains_origin(q) && a < pick_area) pick = i, pick_area = a;
  }
  if (pick == chains.size()) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < chains.size(); ++i) {
      const double d = distance_to_chain(o, chains[i]);
      if (d < best) pick = i, best = d;
    }
  }

  CrossSection out;
  Chain& c = chains[pick];
  std::vector<Vec2> q = project(c.points);
  double area = detail::signed_area(q);
  if (c.closed && area < 0.0) {
    std::reverse(c.points.begin(), c.points.end());
    std::reverse(q.begin(), q.end());
    area = -area;
  }
  out.closed = c.closed;
  out.area = std::abs(area);
  for (std::size_t i = 0; i + 1 < c.points.size(); ++i)
    out.perimeter += (c.points[i + 1] - c.points[i]).norm();
  if (c.closed) out.perimeter += (c.points.front() - c.points.back()).norm();
  out.equivalent_diameter = std::sqrt(4.0 * out.area / std::numbers::pi);
  if (area != 0.0) {
    const Vec2 g = detail::area_centroid(q, area);
    out.centroid = o + g.x() * u + g.y() * v;
  } else {
    Vec3 sum = Vec3::Zero();
    for (const Vec3& p : c.points) sum += p;
    out.centroid = sum / static_cast<double>(c.points.size());
  }
  const detail::HullExtents ext = detail::hull_extents(detail::convex_hull(q));
  out.min_diameter = ext.min_width;
  out.max_diameter = ext.diameter;
  out.points = std::move(c.points);
  return out;
}

CrossSection cross_section(const SurfaceMesh& mesh, const Plane& plane,
                           const CrossSectionParams& params) {
  return cross_section(mesh.positions(), mesh.faces(), plane, params);
}

}  // namespace sutura::engine
