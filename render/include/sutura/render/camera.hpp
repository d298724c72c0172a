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
/// Throws std::invalid_argument for a zero view_dir, aspect <= 0 or fov_y_deg outside (1, 170).
Camera fit_camera(const std::array<Point3, 2>& bounds, float aspect,
                  Point3 view_dir = {-0.4f, 1.0f, -0.35f}, Point3 up = {0.0f, 0.0f, 1.0f},
                  float fov_y_deg = 35.0f);

/// Near and far clip distances (positive, along the view direction) that enclose the
/// bounding sphere of `bounds` with a small padding; near is at least 1e-4 * far.
std::array<float, 2> depth_range(const Camera& c, const std::array<Point3, 2>& bounds);

/// Column-major 4x4 view and projection matrices (OpenGL conventions: the camera looks down
/// -z in view space; NDC depth -1 at near_z, +1 at far_z). Throw std::invalid_argument for
/// eye == target, fov_y_deg outside (1, 170), aspect <= 0 or not 0 < near_z < far_z. An `up`
/// parallel to the view direction is replaced by the world axis least aligned with it.
std::array<float, 16> view_matrix(const Camera& c);
std::array<float, 16> projection_matrix(const Camera& c, float aspect, float near_z, float far_z);

}  // namespace sutura::render
