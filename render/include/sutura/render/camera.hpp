#pragma once
// Perspective camera given by eye/target/up, or fitted to scene bounds.
#include <array>

#include "sutura/render/scene.hpp"

namespace sutura::render {

struct Camera {
  Point3 eye = {0.0f, -3.0f, 0.0f};
  Point3 target = {0.0f, 0.0f, 0.0f};
  Point3 up = {0.0f, 0.0f, 1.0f};
  float fov_y_deg = 35.0f;  ///< vertical field of view, degrees in (1, 170)
};

/// Camera looking along `view_dir` (need not be unit) at the centre of `bounds`, backed off
/// so the bounding sphere fits the viewport of aspect `aspect` (width/height) with a margin.
Camera fit_camera(const std::array<Point3, 2>& bounds, float aspect,
                  Point3 view_dir = {-0.4f, 1.0f, -0.35f}, Point3 up = {0.0f, 0.0f, 1.0f},
                  float fov_y_deg = 35.0f);

/// Column-major 4x4 view and projection matrices (OpenGL conventions).
std::array<float, 16> view_matrix(const Camera& c);
std::array<float, 16> projection_matrix(const Camera& c, float aspect, float near_z, float far_z);

}  // namespace sutura::render
