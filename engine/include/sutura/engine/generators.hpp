#pragma once
// Procedural meshes: vessel tubes, flat strips/plates and patch shapes.
// Lengths are in model units; anatomy uses millimetres throughout.
// All generators are deterministic and produce validate()-clean meshes.
#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

/// Open circular tube along +z from z = 0 to z = length (two boundary loops).
struct TubeParams {
  double radius = 5.0;        ///< mm, > 0
  double length = 40.0;       ///< mm, > 0
  int segments_around = 32;   ///< >= 3
  int segments_along = 40;    ///< >= 1
};
SurfaceMesh make_tube(const TubeParams& p);

/// Flat rectangular strip/plate in the z = 0 plane, x in [0, length], y in [-width/2, width/2]
/// (one boundary loop). Quads are split along alternating diagonals so the mesh has no
/// preferred direction.
struct StripParams {
  double length = 40.0;       ///< mm along x, > 0
  double width = 10.0;        ///< mm along y, > 0
  int segments_length = 40;   ///< >= 1
  int segments_width = 10;    ///< >= 1
};
SurfaceMesh make_strip(const StripParams& p);

enum class PatchShape { Ellipse, Diamond, Triangle };

/// Flat patch in the z = 0 plane centred at the origin, long axis along x.
/// Ellipse: axes length x width. Diamond: diagonals length x width. Triangle: isosceles with
/// base `width` on x = -length/2 and apex at x = +length/2 (the widening gusset of an
/// end-to-end anastomosis).
struct PatchParams {
  PatchShape shape = PatchShape::Ellipse;
  double length = 20.0;            ///< mm, > 0
  double width = 8.0;              ///< mm, > 0
  double target_edge_length = 1.0; ///< mm, > 0; boundary and interior spacing aimed for
};
SurfaceMesh make_patch(const PatchParams& p);

/// Parses "ellipse" | "diamond" | "triangle"; throws InvalidArgument otherwise.
PatchShape parse_patch_shape(const std::string& name);

}  // namespace sutura::engine
