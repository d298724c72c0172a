#pragma once
// CPU preparation of a SurfaceItem for the GPU: validation, smooth normals, colour-map
// coordinates. Cost: O(vertices + triangles) per call, no allocation when `out` has capacity.
#include <cstdint>
#include <span>
#include <vector>

#include "sutura/render/scene.hpp"

namespace sutura::render {

/// Interleaved vertex as the surface program reads it (see shaders.hpp attribute locations).
struct SurfaceVertex {
  float position[3];
  float normal[3];  ///< unit, area-weighted average of the adjacent faces' normals
  float scalar;     ///< colour-map coordinate in [0, 1]; -1 without a finite scalar
};

/// Throws std::invalid_argument when the arrays are inconsistent: positions not a multiple of
/// 3, triangles not a multiple of 3, an index out of range, or scalars neither empty nor one
/// per vertex. O(triangles).
void validate_surface(const SurfaceItem& surface);

/// Fills `out` with one SurfaceVertex per vertex of a valid `surface`. Normals follow the
/// triangles' winding: each face contributes its cross product, whose length is twice its
/// area, so larger faces weigh more; vertices without a non-degenerate face get (0, 0, 1). Scalars
/// are mapped linearly from [map.min, map.max] to [0, 1] and clamped (min == max maps to 0.5).
void build_surface_vertices(const SurfaceItem& surface, const ColorMap& map,
                            std::vector<SurfaceVertex>& out);

/// Fills `out` with the unique edges of `triangles` as index pairs (smaller index first),
/// sorted, for drawing the wireframe as GL_LINES: each edge once, instead of once per
/// adjacent triangle as glPolygonMode(GL_LINE) would (~25% faster on llvmpipe).
/// Cost: O(t log t) for t triangles; `out` keeps its capacity.
void build_edge_indices(std::span<const std::uint32_t> triangles, std::vector<std::uint32_t>& out);

}  // namespace sutura::render
