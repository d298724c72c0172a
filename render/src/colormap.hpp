#pragma once
// Scalar colour maps as 256-entry sRGB tables: Viridis (perceptually uniform, sequential),
// Coolwarm (Moreland's diverging blue-grey-red) and Jet (the classic rainbow, for users who
// expect it). The renderer uploads a table as an sRGB texture, so sampling yields linear
// colour and the displayed, unlit colour equals the table entry.
#include <array>
#include <cstdint>

#include "sutura/render/scene.hpp"

namespace sutura::render {

inline constexpr int kColormapSize = 256;

/// RGBA8 entries (alpha 255) for t = i / 255, i = 0..255, sRGB-encoded.
using ColormapTable = std::array<std::uint8_t, 4 * kColormapSize>;

ColormapTable colormap_table(ColorMapName name);

}  // namespace sutura::render
