#include "sutura/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "vec3.hpp"

namespace sutura::render {
namespace {

constexpr float kDegToRad = std::numbers::pi_v<float> / 180.0f;
// Distance factor beyond the exact fit: the bounding sphere's silhouette covers
// 1 / kFitMargin of the smaller half field of view.
constexpr float kFitMargin = 1.08f;
// depth_range pads the bounding sphere by this fraction of its radius so geometry pulled
// towards the eye by the polyline depth bias is not clipped.
constexpr float kDepthPadding = 0.02f;
// Smallest near/far ratio; keeps a 24-bit depth buffer precise when the eye is inside the
// scene's bounding sphere.
constexpr float kMinNearOverFar = 1e-4f;

struct Sphere {
  Point3 centre;
  float radius;
};

Sphere bounding_sphere(const std::array<Point3, 2>& bounds) {
  const Point3 centre = (bounds[0] + bounds[1]) * 0.5f;
  float radius = 0.5f * length(bounds[1] - bounds[0]);
  if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;  // a point or degenerate box
  return {centre, radius};
}

Point3 normalized(const Point3& v, const char* what) {
  const float n = length(v);
  if (!(n > 0.0f) || !std::isfinite(n))
    throw std::invalid_argument(std::string(what) + " has no direction");
  return v * (1.0f / n);
}

// Side vector of the view basis. When `up` is (nearly) parallel to the view direction the
// world axis least aligned with it stands in, so orbiting over a pole never breaks.
Point3 side_vector(const Point3& forward, const Point3& up) {
  const Point3 side = cross(forward, up);
  if (length(side) > 1e-6f * length(up)) return normalized(side, "side vector");
  int least = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(forward[i]) < std::abs(forward[least])) least = i;
  }
  Point3 axis = {0.0f, 0.0f, 0.0f};
  axis[least] = 1.0f;
  return normalized(cross(forward, axis), "side vector");
}

}  // namespace

Camera fit_camera(const std::array<Point3, 2>& bounds, float aspect, Point3 view_dir, Point3 up,
                  float fov_y_deg) {
  if (!(aspect > 0.0f)) throw std::invalid_argument("fit_camera: aspect must be positive");
  if (!(fov_y_deg > 1.0f && fov_y_deg < 170.0f)) {
    throw std::invalid_argument("fit_camera: fov_y_deg must be in (1, 170)");
  }
  const Sphere sphere = bounding_sphere(bounds);
  const Point3 forward = normalized(view_dir, "fit_camera: view_dir");
  const float half_v = 0.5f * fov_y_deg * kDegToRad;
  const float half_h = std::atan(std::tan(half_v) * aspect);
  // A sphere of radius r seen from distance d subtends a cone of half angle asin(r / d).
  const float distance = kFitMargin * sphere.radius / std::sin(std::min(half_v, half_h));
  Camera camera;
  camera.target = sphere.centre;
  camera.eye = sphere.centre - forward * distance;
  camera.up = up;
  camera.fov_y_deg = fov_y_deg;
  return camera;
}

std::array<float, 2> depth_range(const Camera& c, const std::array<Point3, 2>& bounds) {
  const Sphere sphere = bounding_sphere(bounds);
  const Point3 forward = normalized(c.target - c.eye, "camera: target - eye");
  const float centre_depth = dot(sphere.centre - c.eye, forward);
  const float reach = sphere.radius * (1.0f + kDepthPadding);
  float far_z = centre_depth + reach;
  if (!(far_z > 0.0f)) far_z = reach;  // the scene is behind the camera: nothing to see
  const float near_z = std::max(centre_depth - reach, far_z * kMinNearOverFar);
  return {near_z, far_z};
}

std::array<float, 16> view_matrix(const Camera& c) {
  const Point3 f = normalized(c.target - c.eye, "camera: target - eye");
  const Point3 s = side_vector(f, c.up);
  const Point3 u = cross(s, f);
  // Rows s, u, -f and translation -R * eye, stored column by column.
  return {s[0],           u[0],           -f[0],         0.0f,  //
          s[1],           u[1],           -f[1],         0.0f,  //
          s[2],           u[2],           -f[2],         0.0f,  //
          -dot(s, c.eye), -dot(u, c.eye), dot(f, c.eye), 1.0f};
}

std::array<float, 16> projection_matrix(const Camera& c, float aspect, float near_z, float far_z) {
  if (!(aspect > 0.0f)) throw std::invalid_argument("projection_matrix: aspect must be positive");
  if (!(c.fov_y_deg > 1.0f && c.fov_y_deg < 170.0f)) {
    throw std::invalid_argument("projection_matrix: fov_y_deg must be in (1, 170)");
  }
  if (!(near_z > 0.0f && far_z > near_z)) {
    throw std::invalid_argument("projection_matrix: need 0 < near_z < far_z");
  }
  const float f = 1.0f / std::tan(0.5f * c.fov_y_deg * kDegToRad);
  const float depth = near_z - far_z;
  return {f / aspect,
          0.0f,
          0.0f,
          0.0f,  //
          0.0f,
          f,
          0.0f,
          0.0f,  //
          0.0f,
          0.0f,
          (far_z + near_z) / depth,
          -1.0f,
          0.0f,
          0.0f,
          2.0f * far_z * near_z / depth,
          0.0f};
}

}  // namespace sutura::render
