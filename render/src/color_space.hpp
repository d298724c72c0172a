#pragma once
// sRGB transfer function. Scene colours are linear RGB (scene.hpp); images and windows hold
// sRGB-encoded bytes. The shaders use the same formula (shaders.cpp).
#include <algorithm>
#include <cmath>

namespace sutura::render {

/// sRGB-encoded value in [0, 1] of a linear value (clamped to [0, 1] first).
inline float srgb_from_linear(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace sutura::render
