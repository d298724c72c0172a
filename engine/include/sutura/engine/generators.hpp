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

/// Open cylindrical panel: axis along +y from y = 0 to y = length, points at angle theta
/// (measured from +z towards +x) lie at (R sin theta, y, R cos theta). Used by the shell
/// benchmarks (Scordelis-Lo roof: theta in [-40, 40] deg; pinched-cylinder octant: [0, 90]).
/// Normals point outward (away from the axis).
struct CylinderPanelParams {
  double radius = 25.0;         ///< mm, > 0
  double length = 50.0;         ///< mm, > 0
  double angle_start_deg = -40.0;
  double angle_end_deg = 40.0;  ///< > angle_start_deg, span at most 360
  int segments_around = 16;     ///< >= 1
  int segments_along = 16;      ///< >= 1
};
SurfaceMesh make_cylinder_panel(const CylinderPanelParams& p);

enum class PatchShape { Ellipse, Diamond, Triangle };

/// Flat patch in the z = 0 plane centred at the origin, long axis along x.
/// Ellipse: axes length x width. Diamond: diagonals length x width. Triangle: isosceles with
/// base `width` on x = -length/2 and apex at x = +length/2 (the widening gusset of an
/// end-to-end anastomosis).
struct PatchParams {
  PatchShape shape = PatchShape::Ellipse;
  double length = 20.0;            ///< mm, > 0
  double width = 8.0;              ///< mm, > 0
  /// mm, > 0; boundary and interior spacing aimed for. Reduced when the patch is too narrow
  /// for two rows of triangles of that size across it, so that triangles stay well shaped.
  double target_edge_length = 1.0;
  /// Refused (InvalidArgument) when its estimated faces, at the spacing it would use, exceed
  /// this (never more than the generators' ceiling of 2e7).
  double max_faces = 2.0e7;
};
SurfaceMesh make_patch(const PatchParams& p);

/// Parses "ellipse" | "diamond" | "triangle"; throws InvalidArgument otherwise.
PatchShape parse_patch_shape(const std::string& name);

}  // namespace sutura::engine
