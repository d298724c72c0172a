#pragma once
// Incision: a purely topological edit (paper, Sec. 2.1) along a curve sketched on the surface.
#include <optional>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"
#include "sutura/engine/surgery/remesh.hpp"

namespace sutura::engine {

enum class IncisionMode {
  /// Snap every point to its nearest vertex and follow mesh edges (shortest edge path,
  /// Dijkstra): the paper's prototype. No vertices are added except to split a one-edge slit.
  SnapToEdges,
  /// Follow the surface between consecutive points (the trace of the plane through both
  /// points that contains the mean surface normal) and insert vertices where the curve
  /// crosses edges, so the incision need not follow the mesh. The cut's vertices lie on that
  /// curve: a crossing or point is put on an existing vertex or edge only within 1e-6 of an
  /// edge length of it, or, where exact vertices would make a degenerate triangle (the curve
  /// grazes a vertex), within at most 1e-2. Thin triangles beside the lips are left to `remesh`.
  CutThroughFaces,
};

/// Parses "snap" | "cut"; throws InvalidArgument otherwise.
IncisionMode parse_incision_mode(const std::string& name);

/// IncisionParams::repair_below_deg's band remeshes: their target edge lengths at the cut, as
/// fractions of the band's, tried in this order (the first IncisionParams::repair_attempts).
inline constexpr double kRepairTargets[] = {0.6, 0.45, 0.3, 0.2, 0.1};

struct IncisionParams {
  IncisionMode mode = IncisionMode::CutThroughFaces;
  /// mm, > 0: a curve point farther than this from the surface is rejected ("off the surface").
  double max_distance = 1.0;
  /// Cut-through: a first or last point closer to the open boundary than this fraction of the
  /// local edge length is put on the boundary (drawn to the rim: the cut opens the boundary
  /// loop instead of leaving a sliver between its end and the rim). In [0, 0.5].
  double end_snap = 0.25;
  /// Cut-through only: remesh a band around the traced cut before opening it (remesh.hpp), the
  /// cut's edges kept as a constrained polyline, so the lips get well-shaped triangles while
  /// their vertices stay on the trace. Off: the raw trace (exact, thin triangles included).
  bool remesh = true;
  /// mm, >= 0: edge length of the band; 0 = the mean edge length of the faces the curve's
  /// points lie in (the host's spacing).
  double target_edge_length = 0.0;
  /// > 0: half-width of the band, in target edge lengths.
  double band_width = 2.0;
  /// >= 1: edge growth per band away from the cut (1 = uniform; see RemeshParams::grading).
  double grading = 1.0;
  /// Degrees, in [0, 40]: where the remeshed band still has a smaller angle (a cut that runs
  /// or ends within about half an edge of the open boundary leaves a gap narrower than the
  /// band's edges), the band is remeshed again from the raw cut with the targets of
  /// kRepairTargets at the cut, graded by at least 1.5 out to the host's spacing, in that
  /// order; the first that reaches this limit is kept, else the one with the largest smallest
  /// angle (IncisionResult::band_repair_fraction says which). Each attempt costs one band
  /// remesh. 0: off.
  double repair_below_deg = 20.0;
  /// How many of kRepairTargets are tried, in [0, 5].
  int repair_attempts = 5;
  /// The passes of every band remesh. With rim_faces_in_region (the default here) the faces
  /// just outside the band that a remesh changes (where it splits or collapses a rim edge) are
  /// the band's: their angles are raised too, and band_after and the repair's decision include
  /// them.
  RemeshPasses band_passes = with_rim_faces({});
  /// Per vertex of the mesh passed in (empty = none): vertices the remesh must keep where they
  /// are (fixed DOFs, point loads, probes).
  std::vector<bool> constrained_vertices;
  /// Edges of the mesh passed in that the remesh keeps as polylines (earlier sutures, material
  /// borders); the parts the cut splits are kept too.
  std::vector<std::pair<VertexId, VertexId>> constrained_edges;
};

struct IncisionResult {
  SurfaceMesh mesh;
  EditMaps maps;  ///< from the mesh passed in
  /// The cut as vertices of the new mesh, in the direction the curve was drawn: one lip is
  /// `left` (the copies, on the left of the drawing direction seen from the normal side), the
  /// other `right` (the original vertices). Both start at the first curve point and end at the
  /// last. An interior end is shared by both lips (a slit); an end on the boundary is two
  /// vertices (the cut opens the boundary loop).
  std::vector<VertexId> left, right;
  bool starts_on_boundary = false;
  bool ends_on_boundary = false;
  int inserted_vertices = 0;  ///< vertices created where the curve crosses edges or faces
  int snapped_points = 0;     ///< cut vertices that are vertices of the mesh passed in
  double length = 0.0;        ///< mm, along the cut
  bool remeshed = false;      ///< the band around the cut was remeshed
  /// Of the band, when remeshed; band_after includes the faces just outside it that its remesh
  /// changed when band_passes.rim_faces_in_region is set (band_before does not).
  MeshQuality band_before, band_after;
  /// The kRepairTargets fraction whose remesh was kept (IncisionParams::repair_below_deg);
  /// 0: the first remesh was kept.
  double band_repair_fraction = 0.0;
  /// Degrees: the smallest corner where a lip ends on the open boundary (the sum of the
  /// angles of the faces at that lip end); none when no lip does. A cut drawn onto an open end
  /// at a grazing angle makes this small, and no face in that corner can have a larger angle
  /// while the lips stay on the drawn curve.
  std::optional<double> open_end_corner_deg;
};

/// Cuts `mesh` along the curve through `points` (at least 2; each within max_distance of the
/// surface; consecutive points on the same spot count once). Throws InvalidArgument naming the
/// problem for: fewer than two points, a point off the surface, all points on one spot, a
/// curve that crosses or touches itself or runs along or across the boundary between its ends,
/// a path that cannot be traced (it would leave the surface). Returns the new mesh (validate()
/// holds) and the parent maps.
/// Cost: O(F) per point for the projection plus O(F log F) for the rebuild (once more, rarely,
/// when the curve grazes a vertex).
IncisionResult incise(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                      const IncisionParams& params = {});

}  // namespace sutura::engine
