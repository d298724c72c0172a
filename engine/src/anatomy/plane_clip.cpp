#include "plane_clip.hpp"

#include <cmath>
#include <map>
#include <utility>

namespace sutura::engine::anatomy {

void clip_end(TriangleMesh& mesh, const Vec3& centre, const Vec3& normal, double reach_radius,
              double reach_depth) {
  constexpr double kOnPlane = 1e-6;
  const std::size_t nv = mesh.positions.size();
  // Signed distance from the plane for vertices in the cylinder (plus the same depth on the
  // inner side, where edges leaving the cut region end); -1 elsewhere (kept).
  std::vector<double> side(nv, -1.0);
  for (std::size_t v = 0; v < nv; ++v) {
    Vec3& p = mesh.positions[v];
    double s = (p - centre).dot(normal);
    if (std::abs(s) > reach_depth || (p - centre - s * normal).norm() > reach_radius) continue;
    if (std::abs(s) < kOnPlane) {
      p -= (s + 2.0 * kOnPlane) * normal;
      s = -2.0 * kOnPlane;
    }
    side[v] = s;
  }

  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> cut_vertex;
  auto cut = [&](std::int32_t a, std::int32_t b) {
    const auto key = std::minmax(a, b);
    const auto [it, inserted] =
        cut_vertex.try_emplace(key, static_cast<std::int32_t>(mesh.positions.size()));
    if (inserted) {
      const double t = side[a] / (side[a] - side[b]);
      const Vec3 p = mesh.positions[a] + t * (mesh.positions[b] - mesh.positions[a]);
      mesh.positions.push_back(p - (p - centre).dot(normal) * normal);
    }
    return it->second;
  };

  std::vector<FaceIndices> kept;
  kept.reserve(mesh.faces.size());
  for (const FaceIndices& f : mesh.faces) {
    int outside = 0;
    for (std::int32_t v : f) outside += side[v] > 0.0 ? 1 : 0;
    if (outside == 0) {
      kept.push_back(f);
      continue;
    }
    if (outside == 3) continue;
    // Walk the corners in order, keeping inside corners and inserting a cut vertex on every
    // edge that crosses the plane: 3 - outside + 2 vertices, a triangle or a quad.
    std::vector<std::int32_t> poly;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = f[k], b = f[(k + 1) % 3];
      const bool a_in = side[a] <= 0.0, b_in = side[b] <= 0.0;
      if (a_in) poly.push_back(a);
      if (a_in != b_in) poly.push_back(cut(a, b));
    }
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) kept.push_back({poly[0], poly[k], poly[k + 1]});
  }

  // Drop unused vertices, keeping the order of the others.
  std::vector<std::int32_t> remap(mesh.positions.size(), -1);
  for (const FaceIndices& f : kept)
    for (std::int32_t v : f) remap[v] = 0;
  std::vector<Vec3> positions;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (remap[v] < 0) continue;
    remap[v] = static_cast<std::int32_t>(positions.size());
    positions.push_back(mesh.positions[v]);
  }
  for (FaceIndices& f : kept)
    for (std::int32_t& v : f) v = remap[v];
  mesh.positions = std::move(positions);
  mesh.faces = std::move(kept);
}

}  // namespace sutura::engine::anatomy
