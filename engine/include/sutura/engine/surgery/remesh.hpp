#pragma once
// Constrained local remeshing: any region of a surface is remeshed to a target edge length
// (CGAL's isotropic remeshing: split, collapse, flip, tangential relaxation, projection onto
// the old surface), finer near a polyline when asked (graded, by nested bands), keeping
// constrained edges as polylines (lips, seams, open boundaries) and constrained vertices where
// they are. The result is an edit like any other: a new mesh and EditMaps, so every attribute
// follows it (surface_attributes.hpp). New vertices lie on the old surface and are located in
// an old face (Interpolated, barycentric weights); a new face that is not an old one keeps the
// old face under its centroid as parent (FaceOriginKind::Resampled) and takes its rest shape by
// the strain transfer of carry.hpp (docs/remeshing.md gives the rule and its error).
#include <optional>
#include <utility>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"

namespace sutura::engine {

/// Angles and edge lengths of a set of faces.
struct MeshQuality {
  double min_angle_deg = 0.0;  ///< smallest interior angle of any face
  double p5_angle_deg = 0.0;   ///< 5th percentile of the faces' smallest angles
  double min_edge = 0.0;       ///< mm
  double max_edge = 0.0;       ///< mm
  std::size_t faces = 0;
  FaceId worst_face;           ///< the face with the smallest angle (invalid when no face)
};

/// Smallest interior angle of the triangle (a, b, c), degrees (0 for a degenerate one). O(1).
double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c);

/// Sum of the angles at v of its faces, degrees: 360 inside a flat region; on an open boundary,
/// the corner the boundary makes there (180 on a straight run). O(valence).
double vertex_angle_sum_deg(const SurfaceMesh& mesh, VertexId v);

/// Quality of `faces` of `mesh` (all faces when empty). Cost O(F log F).
MeshQuality mesh_quality(const SurfaceMesh& mesh, const std::vector<FaceId>& faces = {});

/// Quality of the elements' rest shapes (per-element triangles; a merged vertex has one rest
/// position per element, so this is what the solver's elements are shaped like at rest).
/// Cost O(F log F).
MeshQuality rest_quality(const RestState& rest);

/// Mean edge length of `faces` (all faces when empty), mm. Cost O(F).
double mean_edge_length(const SurfaceMesh& mesh, const std::vector<FaceId>& faces = {});

/// Faces with a corner within `radius` (mm) of the polyline through `points` (one point: of the
/// point), sorted. Cost O(F * points).
std::vector<FaceId> faces_near_polyline(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                                        double radius);

/// Faces with a corner within `radius` (mm, along edge paths) of a corner of a face whose
/// smallest angle in `mesh` is below `below_deg` (degrees), sorted; empty when no face is.
/// Distances follow the edges (Dijkstra from those corners), so a part lying across a fold or
/// against another wall (a flap turned down onto its bed) is not drawn in unless it is joined
/// to them within `radius`. Throws InvalidArgument for `below_deg` outside (0, 60] or a radius
/// that is not finite and >= 0. Cost O(F log F).
std::vector<FaceId> faces_near_small_angles(const SurfaceMesh& mesh, double below_deg,
                                            double radius);

/// How a remesh works its region, apart from where and how fine. Every remeshed mesh depends
/// on these, so a session pins them per format version (app/src/session_defaults.cpp) and a
/// default changed here changes no recorded session.
struct RemeshPasses {
  int iterations = 3;  ///< in [1, 100], CGAL iterations per band
  /// Degrees, in [0, 40]: after the bands, a free corner (not fixed, on no constrained
  /// polyline nor open boundary, all its faces in the region) of a remeshed face with a
  /// smaller angle is moved on the surface to where a local search finds the smallest angle
  /// of its faces largest, only if that raises it. Only faces around a moved corner (and
  /// pairs flipped afterwards) change, and the smallest angle among them only rises: the
  /// region's smallest angle never falls. Where no face is below it, nothing changes. 0: off.
  /// The default 25 leaves a margin above 20 degrees for the rest shapes the state transfer
  /// gives, which the remesher does not see (docs/remeshing.md).
  double raise_angles_below_deg = 25.0;
  /// A face outside the region that the remesh changes (where it splits or collapses an edge of
  /// the region's rim) counts as remeshed: the passes that raise angles reach it, and `after`
  /// and `region` include it. Off, such faces keep what the split or collapse made of them and
  /// are not reported. Sessions: on for incise's bands since format 5.
  bool rim_faces_in_region = false;
};

/// `passes` with rim_faces_in_region on.
constexpr RemeshPasses with_rim_faces(RemeshPasses passes) {
  passes.rim_faces_in_region = true;
  return passes;
}

struct RemeshParams {
  /// mm, > 0: edge length near `grading_curve` (everywhere without one).
  double target_edge_length = 0.0;
  /// Faces to remesh (any order); none given = the whole surface, an empty list is an error.
  std::optional<std::vector<FaceId>> region;
  /// >= 1: with a curve, the edge length changes by this factor per band of the current
  /// length away from the curve towards the region's own mean edge length (grows where the
  /// region is coarser, shrinks where it is finer; nested bands, the outer ones remeshed
  /// first). 1 = uniform.
  double grading = 1.0;
  /// Polyline (mm) near which the mesh is finest; empty = uniform.
  std::vector<Vec3> grading_curve;
  RemeshPasses passes;
  /// Edges kept as polylines (their vertices may be added along them or collapsed along them,
  /// never moved off them): lips, seams, feature lines. Open boundary edges always are.
  std::vector<std::pair<VertexId, VertexId>> constrained_edges;
  /// Per vertex (empty or mesh-sized): never moved nor removed (fixed DOFs, loads, probes,
  /// ends of constrained polylines).
  std::vector<bool> constrained_vertices;
  /// Per vertex (empty or mesh-sized): open-boundary vertices of the region to remove before
  /// remeshing, each collapsed along the boundary into a neighbour on it that keeps its place
  /// (the boundary there becomes the chord), unless the collapse would fold a face; a vertex
  /// that cannot go stays. For resampling a chain (seam_match.hpp), which CGAL's collapses do
  /// not do along a boundary.
  std::vector<bool> removed_boundary_vertices;
};

struct RemeshResult {
  SurfaceMesh mesh;
  EditMaps maps;  ///< from the mesh passed in
  /// Of the region (before) and of the faces it became (after), with
  /// passes.rim_faces_in_region the rim faces the remesh changed too (after only).
  MeshQuality before, after;
  std::vector<FaceId> region;  ///< faces of the new mesh that were remeshed (as `after`)
  /// The constrained edges of the new mesh (sub-edges of the given ones), as vertex pairs.
  std::vector<std::pair<VertexId, VertexId>> constrained_edges;
};

/// Consecutive vertex pairs of `chains` that are edges of `mesh` (a chain's pairs that are not,
/// e.g. after an edit collapsed a vertex between them, are skipped); a chain of three or more
/// whose ends are adjacent is closed. Sorted, unique.
std::vector<std::pair<VertexId, VertexId>> chain_edges(
    const SurfaceMesh& mesh, const std::vector<std::vector<VertexId>>& chains);

/// Edges between faces of different values of `face_value` (materials: a patch's border).
std::vector<std::pair<VertexId, VertexId>> value_border_edges(const SurfaceMesh& mesh,
                                                              const std::vector<int>& face_value);

/// The edges of `after` (an edit of the mesh `maps` start from) that lie along the given
/// edges of that mesh: both ends descend from one given edge (a copy of an end, or a point
/// interpolated between its two ends). Sorted, unique. Cost O(V + F + edges).
std::vector<std::pair<VertexId, VertexId>> carry_edges(
    const EditMaps& maps, const SurfaceMesh& after,
    const std::vector<std::pair<VertexId, VertexId>>& edges);

/// Parameters that remesh the band of faces within `band_width` target lengths of `chains`
/// (sutures, lips), the chains' edges constrained. `target_edge_length` 0: the median edge
/// length of the faces with a corner on a chain's 2-ring (the host's spacing, robust to the
/// few short edges a suture leaves). Throws InvalidArgument when no chain has an edge.
RemeshParams band_around(const SurfaceMesh& mesh, const std::vector<std::vector<VertexId>>& chains,
                         double band_width, double target_edge_length = 0.0);

/// Remeshes `params.region` of `mesh`. Deterministic (CGAL's remesher draws no random numbers
/// and visits elements in index order; nothing here depends on the thread count).
/// Throws InvalidArgument naming the field for: target_edge_length <= 0 or non-finite or
/// larger than the region's extent ("target_edge_length"), a region face out of range or a
/// region without faces ("region"), grading < 1 ("grading"), iterations < 1 or > 100
/// ("iterations"), raise_angles_below_deg outside [0, 40] ("raise_angles_below_deg"), a
/// constrained edge that is not an edge ("constrained_edges"), a constrained-vertex list of
/// the wrong size ("constrained_vertices"). The mesh passed in is
/// never changed. Cost: O(F_region * iterations * log F) per band.
RemeshResult remesh(const SurfaceMesh& mesh, const RemeshParams& params);

}  // namespace sutura::engine
