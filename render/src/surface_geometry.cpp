#include "surface_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vec3.hpp"

namespace sutura::render {

void validate_surface(const SurfaceItem& s) {
  if (s.positions.size() % 3 != 0) {
    throw std::invalid_argument("surface: positions has " + std::to_string(s.positions.size()) +
                                " floats, not a multiple of 3");
  }
  if (s.triangles.size() % 3 != 0) {
    throw std::invalid_argument("surface: triangles has " + std::to_string(s.triangles.size()) +
                                " indices, not a multiple of 3");
  }
  const std::size_t vertices = s.positions.size() / 3;
  for (const std::uint32_t index : s.triangles) {
    if (index >= vertices) {
      throw std::invalid_argument("surface: vertex index " + std::to_string(index) +
                                  " out of range for " + std::to_string(vertices) + " vertices");
    }
  }
  if (!s.scalars.empty() && s.scalars.size() != vertices) {
    throw std::invalid_argument("surface: " + std::to_string(s.scalars.size()) + " scalars for " +
                                std::to_string(vertices) + " vertices");
  }
}

namespace {

float map_scalar(float value, const ColorMap& map) {
  if (!std::isfinite(value)) return -1.0f;
  const float range = map.max - map.min;
  if (!(std::abs(range) > 0.0f) || !std::isfinite(range)) return 0.5f;
  return std::clamp((value - map.min) / range, 0.0f, 1.0f);
}

}  // namespace

void build_surface_vertices(const SurfaceItem& surface, const ColorMap& map,
                            std::vector<SurfaceVertex>& out) {
  const std::size_t count = surface.positions.size() / 3;
  out.resize(count);
  const float* p = surface.positions.data();
  for (std::size_t v = 0; v < count; ++v) {
    out[v] = {{p[3 * v], p[3 * v + 1], p[3 * v + 2]}, {0.0f, 0.0f, 0.0f}, -1.0f};
  }

  const auto position = [p](std::uint32_t v) {
    return Point3{p[3 * v], p[3 * v + 1], p[3 * v + 2]};
  };
  const std::uint32_t* t = surface.triangles.data();
  for (std::size_t f = 0; f < surface.triangles.size(); f += 3) {
    const Point3 a = position(t[f]);
    const Point3 face = cross(position(t[f + 1]) - a, position(t[f + 2]) - a);
    for (std::size_t k = 0; k < 3; ++k) {
      float* n = out[t[f + k]].normal;
      n[0] += face[0];
      n[1] += face[1];
      n[2] += face[2];
    }
  }
  for (SurfaceVertex& v : out) {
    const float len = length({v.normal[0], v.normal[1], v.normal[2]});
    if (len > 0.0f && std::isfinite(len)) {
      for (float& c : v.normal) c /= len;
    } else {
      v.normal[0] = 0.0f;
      v.normal[1] = 0.0f;
      v.normal[2] = 1.0f;
    }
  }

  if (!surface.scalars.empty()) {
    for (std::size_t v = 0; v < count; ++v) out[v].scalar = map_scalar(surface.scalars[v], map);
  }
}

void build_edge_indices(std::span<const std::uint32_t> triangles, std::vector<std::uint32_t>& out) {
  // Each edge as one 64-bit key (low index in the high half), so sorting groups duplicates
  // and fixes a deterministic order.
  std::vector<std::uint64_t> keys;
  keys.reserve(triangles.size());
  for (std::size_t f = 0; f + 2 < triangles.size(); f += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles[f + k];
      const std::uint32_t b = triangles[f + (k + 1) % 3];
      if (a == b) continue;
      keys.push_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  out.resize(2 * keys.size());
  for (std::size_t e = 0; e < keys.size(); ++e) {
    out[2 * e] = static_cast<std::uint32_t>(keys[e] >> 32);
    out[2 * e + 1] = static_cast<std::uint32_t>(keys[e]);
  }
}

}  // namespace sutura::render
