#pragma once
// Triangle meshes built from plain arrays for the render tests and the snapshot benchmark.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "sutura/render/scene.hpp"

namespace sutura::render::testing {

struct TestMesh {
  std::vector<float> positions;          // xyz per vertex
  std::vector<std::uint32_t> triangles;  // counter-clockwise seen from outside / from +z

  [[nodiscard]] SurfaceItem surface() const {
    SurfaceItem s;
    s.positions = positions;
    s.triangles = triangles;
    return s;
  }
  [[nodiscard]] std::size_t vertex_count() const { return positions.size() / 3; }
};

/// Closed UV sphere centred on the origin: 2 * slices * (stacks - 1) triangles.
inline TestMesh uv_sphere(float radius, int stacks, int slices) {
  TestMesh m;
  const float pi = std::numbers::pi_v<float>;
  for (int i = 0; i <= stacks; ++i) {
    const float polar = pi * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float azimuth = 2.0f * pi * static_cast<float>(j) / static_cast<float>(slices);
      m.positions.insert(m.positions.end(),
                         {radius * std::sin(polar) * std::cos(azimuth),
                          radius * std::sin(polar) * std::sin(azimuth), radius * std::cos(polar)});
    }
  }
  const auto index = [slices](int i, int j) {
    return static_cast<std::uint32_t>(i * (slices + 1) + j);
  };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      if (i > 0)
        m.triangles.insert(m.triangles.end(), {index(i, j), index(i + 1, j), index(i, j + 1)});
      if (i < stacks - 1) {
        m.triangles.insert(m.triangles.end(),
                           {index(i, j + 1), index(i + 1, j), index(i + 1, j + 1)});
      }
    }
  }
  return m;
}

/// Open cylinder of `radius` along the x axis from -length/2 to +length/2:
/// 2 * rings * segments triangles.
inline TestMesh tube(float radius, float length, int rings, int segments) {
  TestMesh m;
  const float pi = std::numbers::pi_v<float>;
  for (int i = 0; i <= rings; ++i) {
    const float x = length * (static_cast<float>(i) / static_cast<float>(rings) - 0.5f);
    for (int j = 0; j < segments; ++j) {
      const float a = 2.0f * pi * static_cast<float>(j) / static_cast<float>(segments);
      m.positions.insert(m.positions.end(), {x, radius * std::cos(a), radius * std::sin(a)});
    }
  }
  const auto index = [segments](int i, int j) {
    return static_cast<std::uint32_t>(i * segments + (j % segments));
  };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      m.triangles.insert(m.triangles.end(), {index(i, j), index(i, j + 1), index(i + 1, j)});
      m.triangles.insert(m.triangles.end(),
                         {index(i, j + 1), index(i + 1, j + 1), index(i + 1, j)});
    }
  }
  return m;
}

/// Flat square [-half, half]^2 in the plane z = 0 as an n x n grid, front side facing +z.
inline TestMesh square(float half, int n) {
  TestMesh m;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      m.positions.insert(
          m.positions.end(),
          {half * (2.0f * static_cast<float>(j) / static_cast<float>(n) - 1.0f),
           half * (2.0f * static_cast<float>(i) / static_cast<float>(n) - 1.0f), 0.0f});
    }
  }
  const auto index = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      m.triangles.insert(m.triangles.end(), {index(i, j), index(i, j + 1), index(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {index(i, j), index(i + 1, j + 1), index(i + 1, j)});
    }
  }
  return m;
}

}  // namespace sutura::render::testing
