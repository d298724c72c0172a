#pragma once
// Parameter checks shared by the generators: each failure is an InvalidArgument naming the
// operation, the parameter and the offending value.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

// Upper bound on generated faces: keeps half-edge ids far inside int32 and turns an absurd
// parameter into an InvalidArgument instead of an allocation failure.
inline constexpr double kMaxFaces = 2.0e7;

inline std::string format_number(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

inline void require_positive(const char* op, const char* name, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InvalidArgument(std::string(op) + ": " + name +
                          " must be a positive finite number (got " + format_number(value) + ")");
  }
}

inline void require_at_least(const char* op, const char* name, int value, int minimum) {
  if (value < minimum) {
    throw InvalidArgument(std::string(op) + ": " + name + " must be at least " +
                          std::to_string(minimum) + " (got " + std::to_string(value) + ")");
  }
}

inline void require_face_budget(const char* op, const std::string& what, double faces,
                                double limit = kMaxFaces) {
  if (faces > std::min(limit, kMaxFaces)) {
    throw InvalidArgument(std::string(op) + ": " + what + " would need about " +
                          format_number(faces) + " triangles, more than the limit of " +
                          format_number(std::min(limit, kMaxFaces)));
  }
}

}  // namespace sutura::engine::detail
