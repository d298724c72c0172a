#pragma once
// Polylines and point markers as triangles for the marker program (shaders.cpp), which
// expands them in screen space in its vertex shader. Geometry shaders would be the textbook
// tool, but on llvmpipe each one adds ~90 ms of LLVM compilation to the first snapshot of a
// process, and they run slower than this vertex-shader expansion.
#include <vector>

#include "sutura/render/scene.hpp"

namespace sutura::render {

/// One corner of a marker quad. Every vertex of a quad carries the whole primitive, so the
/// vertex shader can clip and expand it consistently.
struct MarkerVertex {
  float from[3];    ///< segment start, or disc centre (world units)
  float to[3];      ///< segment end (unused for discs)
  float corner[2];  ///< segment: x 0 at `from` / 1 at `to`, y side -1 / +1; disc: (+-1, +-1)
  float color[3];   ///< linear RGB
  float size_px;    ///< segment width or disc diameter, pixels
  float disc;       ///< 1 for a round disc, 0 for a segment
};

/// Triangles (6 vertices per quad) in drawing order: all polyline segments, then a disc of
/// the line's width on every polyline vertex (round joints and caps), then the point items.
/// Polylines with fewer than 2 points or width_px <= 0 and point items with size_px <= 0 are
/// skipped. Cost: O(points); `out` is cleared first and keeps its capacity.
void build_marker_vertices(const Scene& scene, std::vector<MarkerVertex>& out);

}  // namespace sutura::render
