#pragma once
// The Resect tool's reading of the surgeon's clicks: each click on the vessel wall places a
// cut plane across the vessel, perpendicular to the automatic centreline
// (engine/measure/centreline.hpp) and centred on the lumen outline in that plane; with two planes, the band
// between them is what the resect op removes. The preview runs that very resection on the
// current mesh, so what is shown (the cut loops, the faces removed) is what the op does.
#include <optional>
#include <string>
#include <vector>

#include "sutura/engine/measure/centreline.hpp"
#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/resect.hpp"

namespace sutura::app {

/// The automatic centreline the Resect and Section tools place their cuts on: the mesh's
/// current shape through engine::extract_centreline with its defaults (a tree with one end per
/// open end). Throws as that does (e.g. a surface without open ends). Cost: about 0.2 s at 19k
/// faces; the window makes it once per workspace revision.
engine::CentrelineTree tool_centreline(const engine::SurfaceMesh& mesh);

/// A cut across the vessel placed by a click on its wall.
struct SectionCut {
  engine::CutPlane plane;      ///< through the lumen outline's centroid
  double wall_distance = 0.0;  ///< mm, farthest outline point from the plane's origin
  double diameter = 0.0;       ///< mm, equivalent diameter of the outline
  bool closed = false;         ///< the outline goes all the way round
};

/// The cut for a click at `click` on the wall: perpendicular to the centreline at the point
/// whose section the click lies on (least |offset along the tangent| + |distance across -
/// inscribed radius|; at a branch point the tangent runs along the most nearly straight pair
/// of edges), centred on the lumen outline in that plane. Throws InvalidArgument when the tree
/// has no edge or the plane does not cut the surface there. O(tree points + F).
SectionCut cut_at(const engine::SurfaceMesh& mesh, const engine::CentrelineTree& tree, const engine::Vec3& click);

struct ResectPreview {
  std::vector<SectionCut> cuts;
  std::vector<engine::CutPlane> planes;  ///< the cuts' planes
  /// mm: the op's `radius` (only edges this close to a plane's origin are cut): `reach` when
  /// given, else kAutoReach times the larger wall distance of the cuts.
  double reach = 0.0;
  static constexpr double kAutoReach = 1.25;
  std::vector<std::vector<engine::Vec3>> loops;  ///< the cut loops (closed polylines), per plane
  std::vector<engine::Vec3> removed;             ///< centroids of the faces removed
  std::size_t removed_faces = 0;
  double removed_area = 0.0;                     ///< mm^2
  std::string error;  ///< why the resection cannot be done as placed; empty when it can
};

/// Planes for `clicks` (one per click, at most two used) and, with two, the resection they
/// make on `mesh` (seed between the planes' origins, as the op's default). `reach` <= 0: auto.
/// Cost: O(clicks * (tree points + F)) plus, with two planes, one resection O(F log F).
ResectPreview preview_resection(const engine::SurfaceMesh& mesh, const engine::CentrelineTree& tree,
                                const std::vector<engine::Vec3>& clicks, double reach);

}  // namespace sutura::app
