#include "sutura/ui/orbit_camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sutura::ui {

using engine::Vec3;

namespace {

constexpr double kDegPerPixel = 0.3;
constexpr double kMaxPitch = 89.0 * std::numbers::pi / 180.0;

render::Point3 to_point(const Vec3& v) { return {float(v.x()), float(v.y()), float(v.z())}; }
Vec3 to_vec(const render::Point3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

Vec3 OrbitCamera::forward() const {
  return {std::cos(pitch_) * std::sin(yaw_), std::cos(pitch_) * std::cos(yaw_), -std::sin(pitch_)};
}

void OrbitCamera::fit(const std::array<render::Point3, 2>& bounds, float aspect) {
  const render::Camera c = render::fit_camera(bounds, aspect);
  target_ = to_vec(c.target);
  const Vec3 d = target_ - to_vec(c.eye);
  distance_ = d.norm();
  const Vec3 f = d / distance_;
  yaw_ = std::atan2(f.x(), f.y());
  pitch_ = std::asin(std::clamp(-f.z(), -1.0, 1.0));
  fov_y_deg_ = c.fov_y_deg;
}

void OrbitCamera::orbit(float dx_px, float dy_px) {
  const double k = kDegPerPixel * std::numbers::pi / 180.0;
  yaw_ += k * dx_px;
  pitch_ = std::clamp(pitch_ + k * dy_px, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float dx_px, float dy_px, float height_px) {
  const Vec3 f = forward();
  const Vec3 right = f.cross(Vec3::UnitZ()).normalized();
  const Vec3 up = right.cross(f);
  // World size of one pixel at the target's depth.
  const double px = 2.0 * distance_ * std::tan(0.5 * fov_y_deg_ * std::numbers::pi / 180.0) /
                    std::max(1.0f, height_px);
  target_ += px * (-double(dx_px) * right + double(dy_px) * up);
}

const char* to_string(StandardView v) {
  switch (v) {
    case StandardView::Anterior: return "Anterior";
    case StandardView::Posterior: return "Posterior";
    case StandardView::LeftLateral: return "Left lateral";
    case StandardView::RightLateral: return "Right lateral";
    case StandardView::Superior: return "Superior";
    case StandardView::Inferior: return "Inferior";
  }
  return "?";
}

void OrbitCamera::look_from(StandardView view) {
  constexpr double pi = std::numbers::pi;
  // forward() = (cos pitch sin yaw, cos pitch cos yaw, -sin pitch): yaw 0 looks along +y.
  switch (view) {
    case StandardView::Anterior: yaw_ = 0.0, pitch_ = 0.0; break;
    case StandardView::Posterior: yaw_ = pi, pitch_ = 0.0; break;
    case StandardView::LeftLateral: yaw_ = -0.5 * pi, pitch_ = 0.0; break;
    case StandardView::RightLateral: yaw_ = 0.5 * pi, pitch_ = 0.0; break;
    case StandardView::Superior: yaw_ = 0.0, pitch_ = kMaxPitch; break;
    case StandardView::Inferior: yaw_ = 0.0, pitch_ = -kMaxPitch; break;
  }
}

std::optional<StandardView> OrbitCamera::standard_view() const {
  for (const StandardView v : kStandardViews) {
    OrbitCamera c = *this;
    c.look_from(v);
    if (c.yaw_ == yaw_ && c.pitch_ == pitch_) return v;
  }
  return std::nullopt;
}

std::array<Vec3, 3> OrbitCamera::view_axes() const {
  const Vec3 f = forward();
  const Vec3 right = f.cross(Vec3::UnitZ()).normalized();
  return {right, right.cross(f), f};
}

void OrbitCamera::zoom(float steps) {
  distance_ = std::clamp(distance_ * std::pow(0.9, double(steps)), 1e-3, 1e6);
}

void OrbitCamera::zoom_towards(const Vec3& p, float steps) {
  // eye' = p + k (eye - p) with the direction kept: target' = p + k (target - p) and
  // distance' = k distance, so p - eye' = k (p - eye) projects to the same pixel.
  const double before = distance_;
  zoom(steps);
  const double k = distance_ / before;
  target_ = p + k * (target_ - p);
}

render::Camera OrbitCamera::camera() const {
  render::Camera c;
  c.target = to_point(target_);
  c.eye = to_point(target_ - distance_ * forward());
  c.up = {0.0f, 0.0f, 1.0f};
  c.fov_y_deg = float(fov_y_deg_);
  return c;
}

engine::Ray OrbitCamera::ray_through(float x, float y, float width, float height) const {
  const Vec3 f = forward();
  const Vec3 right = f.cross(Vec3::UnitZ()).normalized();
  const Vec3 up = right.cross(f);
  const double half_h = std::tan(0.5 * fov_y_deg_ * std::numbers::pi / 180.0);
  const double half_w = half_h * width / std::max(1.0f, height);
  const double ndc_x = 2.0 * (x + 0.5) / width - 1.0;
  const double ndc_y = 1.0 - 2.0 * (y + 0.5) / height;
  engine::Ray r;
  r.origin = target_ - distance_ * f;
  r.direction = (f + ndc_x * half_w * right + ndc_y * half_h * up).normalized();
  return r;
}

double OrbitCamera::radians_per_pixel(float height_px) const {
  return 2.0 * std::atan(std::tan(0.5 * fov_y_deg_ * std::numbers::pi / 180.0) / std::max(1.0f, height_px));
}

bool OrbitCamera::project(const Vec3& p, float width, float height,
                          std::array<float, 2>& pixel) const {
  const Vec3 f = forward();
  const Vec3 right = f.cross(Vec3::UnitZ()).normalized();
  const Vec3 up = right.cross(f);
  const Vec3 d = p - (target_ - distance_ * f);
  const double depth = d.dot(f);
  if (depth <= 0.0) return false;
  const double half_h = std::tan(0.5 * fov_y_deg_ * std::numbers::pi / 180.0);
  const double half_w = half_h * width / std::max(1.0f, height);
  const double ndc_x = d.dot(right) / depth / half_w;
  const double ndc_y = d.dot(up) / depth / half_h;
  pixel = {float((ndc_x + 1.0) * 0.5 * width - 0.5), float((1.0 - ndc_y) * 0.5 * height - 0.5)};
  return true;
}

}  // namespace sutura::ui
