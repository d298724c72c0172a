#include "sutura/engine/geometry/bvh.hpp"

#include <algorithm>
#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

constexpr std::int32_t kLeafSize = 4;

// Entry distance of the ray into `box` within [t_min, t_max], or +inf when it misses.
double enter_box(const Eigen::AlignedBox3d& box, const Vec3& origin, const Vec3& inv_dir,
                 double t_min, double t_max) {
  for (int k = 0; k < 3; ++k) {
    double t0 = (box.min()[k] - origin[k]) * inv_dir[k];
    double t1 = (box.max()[k] - origin[k]) * inv_dir[k];
    if (t0 > t1) std::swap(t0, t1);
    // NaN (0 * inf for a ray in the slab's plane) must not shrink the interval.
    if (t0 > t_min) t_min = t0;
    if (t1 < t_max) t_max = t1;
    if (t_min > t_max) return std::numeric_limits<double>::infinity();
  }
  return t_min;
}

}  // namespace

std::optional<RayHit> intersect_triangle(const Ray& ray, const Vec3& a, const Vec3& b,
                                         const Vec3& c, double t_min, double t_max) {
  constexpr double kBaryTol = 1e-12;
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = ray.direction.cross(e2);
  const double det = e1.dot(p);
  const double scale = e1.norm() * e2.norm() * ray.direction.norm();
  if (!(std::abs(det) > 1e-14 * scale)) return std::nullopt;  // parallel or degenerate
  const double inv = 1.0 / det;
  const Vec3 s = ray.origin - a;
  const double u = s.dot(p) * inv;
  if (u < -kBaryTol || u > 1.0 + kBaryTol) return std::nullopt;
  const Vec3 q = s.cross(e1);
  const double v = ray.direction.dot(q) * inv;
  if (v < -kBaryTol || u + v > 1.0 + kBaryTol) return std::nullopt;
  const double t = e2.dot(q) * inv;
  if (t < t_min || t > t_max) return std::nullopt;
  RayHit hit;
  hit.face = FaceId(0);
  hit.t = t;
  hit.u = u;
  hit.v = v;
  hit.point = ray.origin + t * ray.direction;
  return hit;
}

TriangleBvh::TriangleBvh(const std::vector<Vec3>& positions, const std::vector<FaceIndices>& faces) {
  triangles_.reserve(faces.size());
  std::vector<Vec3> centroids;
  centroids.reserve(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::array<Vec3, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const auto i = faces[f][k];
      if (i < 0 || static_cast<std::size_t>(i) >= positions.size())
        throw InvalidArgument("TriangleBvh: face " + std::to_string(f) + " references vertex " +
                              std::to_string(i) + " of " + std::to_string(positions.size()));
      tri[k] = positions[static_cast<std::size_t>(i)];
    }
    centroids.push_back((tri[0] + tri[1] + tri[2]) / 3.0);
    triangles_.push_back(tri);
  }
  order_.resize(faces.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<std::int32_t>(i);
  if (faces.empty()) return;
  nodes_.reserve(2 * faces.size() / kLeafSize + 1);
  nodes_.emplace_back();
  build(centroids, 0, 0, static_cast<std::int32_t>(faces.size()));
}

void TriangleBvh::build(const std::vector<Vec3>& centroids, std::int32_t slot,
                        std::int32_t begin, std::int32_t end) {
  Eigen::AlignedBox3d box, centre_box;
  for (std::int32_t i = begin; i < end; ++i) {
    for (const Vec3& p : triangles_[order_[i]]) box.extend(p);
    centre_box.extend(centroids[order_[i]]);
  }
  nodes_[slot].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[slot].first = begin;
    nodes_[slot].count = end - begin;
    return;
  }
  int axis = 0;
  centre_box.sizes().maxCoeff(&axis);
  const std::int32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](std::int32_t a, std::int32_t b) {
                     return centroids[a][axis] < centroids[b][axis] ||
                            (centroids[a][axis] == centroids[b][axis] && a < b);
                   });
  const auto left = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[slot].first = left;
  nodes_[slot].count = 0;
  build(centroids, left, begin, mid);
  build(centroids, left + 1, mid, end);
}

std::optional<RayHit> TriangleBvh::intersect(const Ray& ray, double t_min, double t_max) const {
  if (nodes_.empty()) return std::nullopt;
  const Vec3 inv_dir = ray.direction.cwiseInverse();
  std::optional<RayHit> best;
  std::array<std::int32_t, 128> stack{};
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (enter_box(node.box, ray.origin, inv_dir, t_min, t_max) == std::numeric_limits<double>::infinity())
      continue;
    if (node.count > 0) {
      for (std::int32_t i = node.first; i < node.first + node.count; ++i) {
        const auto& tri = triangles_[order_[i]];
        if (auto hit = intersect_triangle(ray, tri[0], tri[1], tri[2], t_min, t_max)) {
          hit->face = FaceId(order_[i]);
          t_max = hit->t;
          best = hit;
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last) so t_max shrinks early.
    const double tl = enter_box(nodes_[node.first].box, ray.origin, inv_dir, t_min, t_max);
    const double tr = enter_box(nodes_[node.first + 1].box, ray.origin, inv_dir, t_min, t_max);
    const bool left_first = tl <= tr;
    stack[top++] = left_first ? node.first + 1 : node.first;
    stack[top++] = left_first ? node.first : node.first + 1;
  }
  return best;
}

}  // namespace sutura::engine
