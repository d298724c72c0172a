#pragma once
// Minimal float 3-vector arithmetic on Point3 for the renderer's CPU-side geometry.
#include <cmath>

#include "sutura/render/scene.hpp"

namespace sutura::render {

inline Point3 operator+(const Point3& a, const Point3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Point3 operator-(const Point3& a, const Point3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Point3 operator*(const Point3& a, float s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline float dot(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline float length(const Point3& a) { return std::sqrt(dot(a, a)); }

}  // namespace sutura::render
