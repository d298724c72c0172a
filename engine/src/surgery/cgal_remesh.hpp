#pragma once
// CGAL's isotropic remeshing of face ranges of one mesh, band after band, with constrained
// polylines and vertices (the only CGAL translation unit of the surgery code). Plain arrays in
// and out; remesh.cpp turns the result into an edit with EditMaps.
#include <utility>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine::detail {

struct RemeshBand {
  double target_edge_length = 0.0;  ///< mm
  /// Faces whose centroid lies within this distance (mm) of the band curve are remeshed;
  /// negative: every face of the region.
  double reach = -1.0;
};

struct CgalRemeshInput {
  const std::vector<Vec3>* positions = nullptr;
  const std::vector<FaceIndices>* faces = nullptr;
  std::vector<bool> region;  ///< per face: may be remeshed
  std::vector<Vec3> band_curve;  ///< polyline the band reaches are measured from
  std::vector<RemeshBand> bands;  ///< remeshed in this order (coarsest first)
  int iterations = 3;
  std::vector<std::pair<int, int>> constrained_edges;  ///< kept as polylines
  std::vector<bool> constrained_vertices;              ///< per vertex: never moved nor removed
  std::vector<bool> removed_boundary_vertices;  ///< per vertex: collapsed along the boundary first
  /// Before remeshing, an input much finer than the target is first coarsened by shortest-edge
  /// collapses (CGAL's Surface_mesh_simplification, midpoint placement, constrained edges and
  /// open boundaries kept) until no edge is shorter than this (mm), and its vertices projected
  /// back; the remesher then has far fewer collapses to make, and still projects onto the full
  /// input. Every face must then be in `region` and no vertex fixed. 0: off.
  double coarsen_below = 0.0;
  /// From this many faces on, the coarsening runs in two halves of the mesh, on two threads
  /// when the compute threads allow (the same result on any thread count; see coarsen()).
  std::size_t coarsen_in_halves_from = 200000;
  /// After remeshing, a face whose centroid or an edge midpoint lies farther than this (mm)
  /// from the input surface has its longest edge split at the projected midpoint, if that
  /// edge is longer than 2/3 of the (last band's) target (1/2 where the face strays farther
  /// than twice this; on the open boundary: longer than the target) (rounds of splits and
  /// Delaunay flips, at most 6): curvature the target length cannot follow gets finer faces,
  /// down to a third of the target (a quarter). 0: off (the surgical bands). Every face must then be in `region`.
  double max_deviation = 0.0;  ///< needs a band (its target sets the split floor)
  /// After the bands' flips and needle collapses: the free corners (not fixed, on no polyline
  /// nor open boundary) of band faces with an angle below this (degrees) are moved on the
  /// input, each only where that raises the smallest angle of its faces (then Delaunay flips;
  /// 4 rounds at most). 0: off.
  double raise_angles_below_deg = 0.0;
  /// After the bands, a face outside the region that they changed (a new or moved corner, or
  /// corners no input face has: an edge on the region's rim was split or collapsed) joins the
  /// region: the passes below reach it and the output flags it as remeshed.
  bool rim_faces_in_region = false;
  /// Last, a thin face (an angle below this, degrees) on an open-boundary edge shorter than
  /// half the target has that edge's ends moved along the boundary to even it out; then thin faces
  /// and the faces around their corners get CGAL's angle smoothing (open boundaries, polylines
  /// and fixed vertices held, the others projected back), Delaunay flips, and the needle
  /// collapses of the bands with this angle as their goal; 6 rounds at most.
  /// 0: off.
  double repair_below_deg = 0.0;  ///< needs a band (its target sets "short")
};

/// Where an output point lies on the input surface.
struct SurfaceLocation {
  int face = -1;                              ///< input face
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();  ///< in that face, clamped to it
};

struct CgalRemeshOutput {
  std::vector<Vec3> positions;
  std::vector<FaceIndices> faces;
  std::vector<int> old_vertex;  ///< per output vertex: its input vertex, or -1 when new
  std::vector<bool> moved;      ///< per output vertex: position differs from its input vertex's
  std::vector<SurfaceLocation> vertex_location;  ///< per output vertex that is new or moved
  std::vector<int> old_face;  ///< per output face: the input face it is (same corners), or -1
  std::vector<SurfaceLocation> face_location;  ///< per output face that is not an input face:
                                               ///< where its centroid lies
  std::vector<bool> region;  ///< per output face: remeshed (in a band, or a rim face joined to it)
  std::vector<std::pair<int, int>> constrained_edges;
};

/// Remeshes band after band. Interior vertices are projected onto the input surface, vertices
/// on constrained polylines (and open boundaries) onto the input polylines, so lips and
/// boundaries keep their exact trace. Deterministic.
CgalRemeshOutput cgal_remesh(const CgalRemeshInput& in);

}  // namespace sutura::engine::detail
