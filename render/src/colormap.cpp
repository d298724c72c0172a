#include "colormap.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace sutura::render {
namespace {

using Rgb8 = std::array<int, 3>;

// Evenly spaced sRGB anchors, interpolated linearly in sRGB like matplotlib's colormaps.
// Viridis: its nine-step palette (t = 0, 1/8, ..., 1).
constexpr std::array<Rgb8, 9> kViridis = {{{68, 1, 84},
                                           {71, 45, 123},
                                           {59, 82, 139},
                                           {44, 114, 142},
                                           {33, 144, 140},
                                           {39, 173, 129},
                                           {93, 200, 99},
                                           {170, 220, 50},
                                           {253, 231, 37}}};
// Coolwarm: Moreland's diverging map sampled at t = 0, 1/8, ..., 1 (blue, grey, red).
constexpr std::array<Rgb8, 9> kCoolwarm = {{{59, 76, 192},
                                            {98, 130, 234},
                                            {141, 176, 254},
                                            {184, 208, 249},
                                            {221, 221, 221},
                                            {245, 196, 173},
                                            {244, 154, 123},
                                            {222, 96, 77},
                                            {180, 4, 38}}};

std::array<double, 3> sample_anchors(std::span<const Rgb8> anchors, double t) {
  const double x = t * static_cast<double>(anchors.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(x), anchors.size() - 2);
  const double f = x - static_cast<double>(i);
  std::array<double, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    rgb[c] = ((1.0 - f) * anchors[i][c] + f * anchors[i + 1][c]) / 255.0;
  }
  return rgb;
}

// Jet: piecewise-linear ramps, blue -> cyan -> yellow -> red, each channel a clamped tent.
std::array<double, 3> sample_jet(double t) {
  const auto tent = [t](double centre) {
    return std::clamp(1.5 - std::abs(4.0 * t - centre), 0.0, 1.0);
  };
  return {tent(3.0), tent(2.0), tent(1.0)};
}

}  // namespace

ColormapTable colormap_table(ColorMapName name) {
  ColormapTable table{};
  for (int i = 0; i < kColormapSize; ++i) {
    const double t = static_cast<double>(i) / (kColormapSize - 1);
    std::array<double, 3> rgb{};
    switch (name) {
      case ColorMapName::Viridis:
        rgb = sample_anchors(kViridis, t);
        break;
      case ColorMapName::Coolwarm:
        rgb = sample_anchors(kCoolwarm, t);
        break;
      case ColorMapName::Jet:
        rgb = sample_jet(t);
        break;
    }
    for (int c = 0; c < 3; ++c) {
      table[4 * i + c] = static_cast<std::uint8_t>(std::lround(255.0 * rgb[c]));
    }
    table[4 * i + 3] = 255;
  }
  return table;
}

}  // namespace sutura::render
