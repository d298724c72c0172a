#pragma once
// Colour-map legend as 2D triangles in pixel space: a vertical colour bar at the right edge
// with a thin frame, the max value at its top, the min value at its bottom and the label
// above it, in the stb_easy_font bitmap font at an integer scale (crisp at any resolution).
#include <vector>

#include "sutura/render/scene.hpp"

namespace sutura::render {

/// Overlay vertex (see shaders.hpp): pixel position with origin top-left and y down, linear
/// colour, and a colour-map coordinate (or -1 to use the colour).
struct OverlayVertex {
  float x, y;
  float scalar;
  float r, g, b;
};

/// Pixels of the legend's column at the right edge of a width x height viewport (with a
/// margin on its left); 0 when it would not fit or map.show_legend is off.
int legend_width(const ColorMap& map, int width, int height);

/// Triangles (3 vertices each) of the legend for a `width` x `height` viewport, all within
/// its column at the right edge (legend_width). Text is dark on light backgrounds and light
/// on dark ones. Empty when the legend would not fit: its column must take at most half the
/// width and the bar must be at least 16 pixels high. The label is wrapped at its spaces to
/// the column of bar and numbers.
/// Numbers use the shortest of 4 significant digits ("0.25", "1.5e+03"), independent of
/// the C locale.
std::vector<OverlayVertex> legend_triangles(const ColorMap& map, int width, int height,
                                            const Color& background);

}  // namespace sutura::render
