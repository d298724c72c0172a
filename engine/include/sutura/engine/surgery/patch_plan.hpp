#pragma once
// Placing a patch over an incision and choosing which of its edges meet which lip.
#include "sutura/engine/generators.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"
#include "sutura/engine/surgery/remesh.hpp"

namespace sutura::engine {

struct PatchPlanParams {
  PatchShape shape = PatchShape::Ellipse;
  /// mm: widening across the incision (ellipse minor axis, diamond diagonal, triangle base).
  double width = 4.0;
  /// mm along the incision; 0 = the incision's length (mean of the two lips).
  double length = 0.0;
  /// mm; 0 = the mean edge length of the lips, so both sides of the suture match, but not
  /// below `min_edge_length`.
  double edge_length = 0.0;
  /// mm, >= 0: the finest spacing `edge_length` 0 may give. Why: a patch cut much finer than
  /// its width is laid out over the slit as many thin rows (compressed across by
  /// 0.4 * lip spacing / half-width), and the relaxation can collapse one (docs/remeshing.md).
  double min_edge_length = 0.0;
  /// mm: the lips' end points must lie this close to the boundary.
  double max_distance = 1.0;
  /// Matched seams (seam_match.hpp): when > 0, the patch's left and right edges are resampled
  /// to this many equal segments each and the band along them remeshed, flat, before the
  /// patch is laid out, so that each edge pairs one to one with a lip resampled to the same
  /// count. 0: the edges as make_patch cuts them (the join pairs them by arc length).
  int left_segments = 0, right_segments = 0;
  /// The passes of that band remesh (RemeshParams::passes).
  RemeshPasses seam_passes;
  /// The patch is refused (InvalidArgument) when it would have more faces (PatchParams).
  double max_faces = 2.0e7;
};

struct PatchPlan {
  /// The patch as cut from the sheet (its rest shape): flat, moved rigidly onto the tangent
  /// plane at the incision's middle, so its rest triads are in the host's world frame.
  SurfaceMesh rest;
  SurfaceMesh placed;  ///< same topology, a tent over the closed incision (see plan_patch)
  BoundaryChain lip_left, lip_right;      ///< host chains (boundary direction)
  BoundaryChain edge_left, edge_right;    ///< patch chains (boundary direction) meeting them
  double incision_length = 0.0;           ///< mm, mean lip length
  double edge_length = 0.0;               ///< mm, the spacing the patch was cut at
  /// Each edge has as many vertices as its lip (left_segments/right_segments were met): they
  /// pair in order (JoinPairing::InOrder), stitch for stitch, and are laid out beside them.
  bool matched = false;
};

/// Plans a patch for the incision whose ends are near `start` and `end` on `host`: an interior
/// slit (both ends shared by the two lips) takes an ellipse or a diamond; an incision opened
/// from the boundary (start on the boundary, end inside) takes a triangle whose apex meets the
/// end and whose base spans the opened boundary (the widening gusset of an anastomosis).
/// The rest patch lies in the tangent plane at the incision's middle (long axis along the cut,
/// normal along the host's). The placed one is a narrow tent over the closed slit: along the
/// cut it follows the lips, across it it is compressed (its edges within 0.4 lip edge lengths
/// of their lips) and arched outwards by up to half its half-width; the relaxation opens the
/// slit to the patch's width.
/// Throws InvalidArgument for an unknown configuration (no such lips, a triangle on a slit, an
/// ellipse on a boundary incision) or bad sizes: width and length more than a factor of 50
/// apart, or more than max_faces faces.
PatchPlan plan_patch(const SurfaceMesh& host, const Vec3& start, const Vec3& end,
                     const PatchPlanParams& params);

}  // namespace sutura::engine
