#pragma once
// Automatic centreline of a vessel: a tree of points with the radius of the largest sphere
// inscribed at each (the distance to the wall), its branch points, and one branch per open
// end. Each end's path runs through the rings of geodesic distance from its loop and is then
// moved onto the centroids of the sections perpendicular to it; branches join the trunk (root
// to farthest end) on its axis. The method and why it is not CGAL's skeleton: the .cpp;
// accuracy: docs/patient-data.md.
#include <string>
#include <utility>
#include <vector>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

struct CentrelineTree {
  std::vector<Vec3> points;                 ///< mm
  std::vector<double> radii;                ///< mm: distance from the point to the wall
  std::vector<std::pair<int, int>> edges;   ///< undirected, i < j
  std::vector<int> branch_points;           ///< nodes of three or more edges, increasing
  /// Per open end (in the order given): the node at its centre.
  std::vector<int> end_nodes;
};

/// The centreline tree of `vessel` (one connected surface with at least two open ends). `ends`
/// name the open ends, the first being the root (e.g. prepare_vessel's, or the generator's);
/// each is matched to the boundary loop nearest its centre, and its node is at that centre.
/// Empty: one end per boundary loop, at the loop's vertex mean, the longest loop first (the
/// root), then in loop order. The root should be the vessel's widest end: the branches join
/// the trunk on their way to it. Throws
/// InvalidArgument for an empty or unconnected surface, fewer than two open ends, or ends
/// that do not match the loops one to one. Deterministic. Cost: per end one Dijkstra over the
/// vertices (O(V log V)) and three sections (each O(F)) per point of its path to the root
/// (points a mean edge apart, at most about 256 per path), so O(ends * F^1.5) up to about
/// 65k faces and O(ends * F) beyond (times: docs/performance.md).
CentrelineTree extract_centreline(const SurfaceMesh& vessel, const std::vector<VesselEnd>& ends = {});

/// The index of the tree point nearest `p` (the first of equals); the tree must have points.
int nearest_centreline_point(const CentrelineTree& tree, const Vec3& p);

/// The path through the tree between the nodes nearest `from` and `to` (polyline, mm, from
/// the first to the second). Throws InvalidArgument when both are the same node or lie on
/// unconnected parts.
std::vector<Vec3> centreline_path(const CentrelineTree& tree, const Vec3& from, const Vec3& to);

}  // namespace sutura::engine
