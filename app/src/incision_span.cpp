#include "sutura/app/incision_span.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sutura/engine/measure/centreline.hpp"

namespace sutura::app {

namespace {

using engine::Vec3;

// The arc length along `path` of the point nearest `p`, and its distance.
std::pair<double, double> project(const std::vector<Vec3>& path, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity(), at = 0.0, walked = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Vec3 d = path[k] - path[k - 1];
    const double len = d.norm();
    const double t = len > 0.0 ? std::clamp((p - path[k - 1]).dot(d) / (len * len), 0.0, 1.0) : 0.0;
    const double dist = (path[k - 1] + t * d - p).norm();
    if (dist < best) best = dist, at = walked + t * len;
    walked += len;
  }
  return {at, best};
}

Vec3 point_at(const std::vector<Vec3>& path, double s) {
  double walked = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double len = (path[k] - path[k - 1]).norm();
    if (walked + len >= s && len > 0.0) return path[k - 1] + (s - walked) / len * (path[k] - path[k - 1]);
    walked += len;
  }
  return path.back();
}

}  // namespace

IncisionSpan incision_span(const engine::SurfaceMesh& mesh, const Vec3& start, const Vec3& end, double margin_mm) {
  if (!(margin_mm >= 0.0)) throw std::invalid_argument("incision span: the margin must be >= 0 mm");
  // One end per open end, the widest (largest vector area) first: the root of the tree. By
  // default the longest loop would be, and an incision's slit, flat, can be longer than any
  // end's circumference; the tree would then grow from the slit.
  const auto loops = mesh.boundary_loops();
  std::vector<std::pair<double, engine::VesselEnd>> by_area;
  for (const auto& loop : loops) {
    Vec3 centre = Vec3::Zero();
    for (const auto v : loop) centre += mesh.position(v);
    centre /= static_cast<double>(std::max<std::size_t>(1, loop.size()));
    Vec3 area = Vec3::Zero();
    for (std::size_t k = 0; k < loop.size(); ++k)
      area += 0.5 * (mesh.position(loop[k]) - centre).cross(mesh.position(loop[(k + 1) % loop.size()]) - centre);
    const double a = area.norm();
    by_area.push_back({a, {"", centre, a > 0.0 ? Vec3(area / a) : Vec3::UnitZ(), std::sqrt(a / std::numbers::pi)}});
  }
  std::stable_sort(by_area.begin(), by_area.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<engine::VesselEnd> given;
  for (auto& [a, end] : by_area) given.push_back(std::move(end));
  const engine::CentrelineTree tree = engine::extract_centreline(mesh, given);
  std::vector<double> radii;
  for (int n : tree.end_nodes) radii.push_back(tree.radii[static_cast<std::size_t>(n)]);
  std::vector<double> sorted = radii;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
  const double median = sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
  std::vector<int> ends;
  for (std::size_t i = 0; i < tree.end_nodes.size(); ++i)
    if (radii[i] >= 0.25 * median) ends.push_back(tree.end_nodes[i]);
  if (ends.size() < 2) throw std::invalid_argument("the vessel needs two open ends for its centreline");
  // The path between two ends that runs along both points: each within 1.5 lumen radii (plus
  // 0.5 mm) of it, a point on the wall being about one radius from the centreline. The longest
  // such path (the trunk rather than a branch beside the incision); when none runs along both,
  // the one closest to both (the sum of the distances).
  const auto along = [&tree](const std::vector<Vec3>& path, const Vec3& p, double distance) {
    const Vec3 q = point_at(path, project(path, p).first);
    const double r = tree.radii[static_cast<std::size_t>(engine::nearest_centreline_point(tree, q))];
    return distance <= 1.5 * r + 0.5;
  };
  std::vector<Vec3> best;
  bool best_along = false;
  double best_score = std::numeric_limits<double>::infinity(), best_length = 0.0;
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (std::size_t j = i + 1; j < ends.size(); ++j) {
      const auto& pi = tree.points[static_cast<std::size_t>(ends[i])];
      const auto& pj = tree.points[static_cast<std::size_t>(ends[j])];
      std::vector<Vec3> path = engine::centreline_path(tree, pi, pj);
      const double ds = project(path, start).second, de = project(path, end).second;
      const bool runs_along = along(path, start, ds) && along(path, end, de);
      const double score = ds + de;
      const double length = project(path, path.back()).first;
      const bool better = runs_along != best_along ? runs_along
                          : runs_along          ? length > best_length + 1e-9
                                                : score < best_score - 1e-9;
      if (best.empty() || better) {
        best_along = runs_along;
        best_score = score;
        best_length = length;
        best = std::move(path);
      }
    }
  double a = project(best, start).first, b = project(best, end).first;
  if (a > b) {
    std::reverse(best.begin(), best.end());
    a = best_length - a;
    b = best_length - b;
  }
  if (b - a < 1e-6) throw std::invalid_argument("the incision's two ends project to one point of the centreline");
  const double from = std::max(0.0, a - margin_mm), to = std::min(best_length, b + margin_mm);
  IncisionSpan span;
  span.centreline.push_back(point_at(best, from));
  double walked = 0.0;
  for (std::size_t k = 1; k < best.size(); ++k) {
    walked += (best[k] - best[k - 1]).norm();
    if (walked > from + 1e-9 && walked < to - 1e-9) span.centreline.push_back(best[k]);
  }
  span.centreline.push_back(point_at(best, to));
  span.length_mm = to - from;
  for (const Vec3& p : span.centreline)
    span.max_radius_mm =
        std::max(span.max_radius_mm, 2.0 * tree.radii[static_cast<std::size_t>(engine::nearest_centreline_point(tree, p))]);
  return span;
}

}  // namespace sutura::app
