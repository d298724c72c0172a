#pragma once
// Cross-section of a vessel surface by a plane: the lumen outline a surgeon reads off before
// and after a repair (area, equivalent / minimum / maximum diameter).
//
// Method: every face is intersected with the plane and the segments are chained through the
// mesh edges they cross, so chaining is topological (no distance tolerances). Vertices exactly
// on the plane are counted on the positive side (symbolic perturbation: the plane is moved by
// an infinitesimal amount against its normal), so a plane through a vertex or along an edge
// still gives every face crossing 0 or 2 edges and the chains stay manifold; the crossing
// point of an edge with an endpoint on the plane is that endpoint, and repeated consecutive
// points are dropped from the outline. Consequence: a plane that touches the surface only
// along its boundary from the positive side (e.g. exactly the first ring of an open tube
// with the normal pointing into the tube) finds no intersection.
//
// Units are those of the positions (mm); areas mm^2.
#include <limits>
#include <span>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

/// Oriented plane {x : (x - origin) . normal = 0}. `normal` need not be unit length (it is
/// normalised), but must be finite and non-zero.
struct Plane {
  Vec3 origin = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};

struct CrossSectionParams {
  /// mm, > 0. Only intersection segments with both ends within this distance of the plane's
  /// origin are kept (the plane may also cut other branches far away). A lumen that leaves the
  /// ball is reported as open, so choose it larger than the vessel radius. Default: no limit.
  double max_radius = std::numeric_limits<double>::infinity();
};

/// The chain selected as the lumen outline and its measures. All lengths in the plane.
struct CrossSection {
  /// True when the outline is a closed loop; false for an open chain (the surface ends inside
  /// the plane, e.g. an unsutured incision: the lumen is not closed there).
  bool closed = false;
  /// Area of the outline projected onto the plane (shoelace formula in the plane basis),
  /// mm^2, >= 0. For an open chain: the polygon closed by the straight chord between its ends.
  double area = 0.0;
  /// Length of the outline, mm (closing segment included only when closed).
  double perimeter = 0.0;
  /// sqrt(4 area / pi), mm: diameter of the circle with the same area.
  double equivalent_diameter = 0.0;
  /// Minimum width of the outline's convex hull over all directions in the plane (rotating
  /// calipers), mm; 0 when all points are collinear.
  double min_diameter = 0.0;
  /// Largest distance between two outline points, mm.
  double max_diameter = 0.0;
  /// Area centroid of the outline polygon (vertex mean when the area is zero); on the plane.
  Vec3 centroid = Vec3::Zero();
  /// Outline points in chain order, without repeated consecutive points; for a closed loop the
  /// first point is not repeated at the end. Orientation: counter-clockwise seen from the
  /// normal side (for an open chain: as traced).
  std::vector<Vec3> points;
};

/// Intersects the surface (positions, faces) with `plane` and returns the outline that
/// surrounds the plane's origin (the smallest closed loop whose polygon contains it), or,
/// when no loop does, the closed or open chain nearest to the origin (ties: first in face
/// order). Throws InvalidArgument for a zero or non-finite normal, a non-finite origin,
/// a non-positive max_radius, a face index out of range, an edge used by more than two
/// faces, or when the plane does not cut the surface (within max_radius).
/// Cost O(F + k log k) for k crossed edges; no allocation proportional to F except the
/// per-vertex signed distances.
CrossSection cross_section(std::span<const Vec3> positions, std::span<const FaceIndices> faces,
                           const Plane& plane, const CrossSectionParams& params = {});
/// The same on a mesh's current positions.
CrossSection cross_section(const SurfaceMesh& mesh, const Plane& plane,
                           const CrossSectionParams& params = {});

}  // namespace sutura::engine
