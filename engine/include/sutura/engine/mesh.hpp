#pragma once
// SurfaceMesh: topology and current positions of one manifold triangle mesh.
//
// Data layout (geometry-central / corner-table style): faces are a flat array of vertex-id
// triples; half-edge k of face f has the implicit id 3f+k and runs from corner k to corner
// (k+1)%3, so next/prev/face are arithmetic and only `twin_` (one id per half-edge, invalid on
// the boundary) and one outgoing half-edge per vertex are stored. Topology edits (incise, join,
// ...) build a new mesh from edited face arrays and return parent maps; rebuilding adjacency is
// O(F log F) and keeps every invariant in one place.
//
// Rest geometry is NOT stored here: rest state lives per element elsewhere, so that a join can
// give two faces sharing a vertex different rest positions (paper, Sec. 2.2).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sutura/engine/ids.hpp"

namespace sutura::engine {

using Vec3 = Eigen::Vector3d;
using FaceIndices = std::array<std::int32_t, 3>;

/// Result of SurfaceMesh::validate(): empty `problems` means every invariant holds.
struct ValidationReport {
  std::vector<std::string> problems;
  [[nodiscard]] bool ok() const { return problems.empty(); }
  /// All problems joined by "; " (for test failure messages and error texts).
  [[nodiscard]] std::string summary() const;
};

class SurfaceMesh {
 public:
  SurfaceMesh() = default;

  /// Builds the mesh and its adjacency from flat arrays.
  /// Throws TopologyError naming the first problem found: a face index out of range, a face
  /// that repeats a vertex, an edge used by more than two faces, two faces traversing a shared
  /// edge in the same direction (inconsistent orientation), a pinched (non-manifold) vertex, a
  /// vertex used by no face, or a non-finite coordinate. Cost O(F log F).
  SurfaceMesh(std::vector<Vec3> positions, std::vector<FaceIndices> faces);

  // --- counts -------------------------------------------------------------------------------
  [[nodiscard]] std::size_t num_vertices() const { return positions_.size(); }
  [[nodiscard]] std::size_t num_faces() const { return faces_.size(); }
  [[nodiscard]] std::size_t num_halfedges() const { return 3 * faces_.size(); }
  [[nodiscard]] std::size_t num_edges() const { return num_edges_; }
  [[nodiscard]] bool empty() const { return faces_.empty(); }

  // --- faces and half-edges (O(1)) ---------------------------------------------------------
  [[nodiscard]] const std::vector<FaceIndices>& faces() const { return faces_; }
  [[nodiscard]] std::array<VertexId, 3> face_vertices(FaceId f) const;
  [[nodiscard]] static HalfedgeId halfedge(FaceId f, int corner) {
    return HalfedgeId(3 * f.value + corner);
  }
  [[nodiscard]] static FaceId face(HalfedgeId h) { return FaceId(h.value / 3); }
  [[nodiscard]] static HalfedgeId next(HalfedgeId h) {
    return HalfedgeId(h.value - h.value % 3 + (h.value % 3 + 1) % 3);
  }
  [[nodiscard]] static HalfedgeId prev(HalfedgeId h) {
    return HalfedgeId(h.value - h.value % 3 + (h.value % 3 + 2) % 3);
  }
  [[nodiscard]] VertexId from_vertex(HalfedgeId h) const;
  [[nodiscard]] VertexId to_vertex(HalfedgeId h) const;
  /// Opposite half-edge of the neighbouring face; invalid when h lies on the boundary.
  [[nodiscard]] HalfedgeId twin(HalfedgeId h) const { return twin_[h.index()]; }
  [[nodiscard]] bool is_boundary(HalfedgeId h) const { return !twin_[h.index()].valid(); }

  // --- vertices ----------------------------------------------------------------------------
  /// An outgoing half-edge of v; for a boundary vertex it is the outgoing boundary half-edge
  /// (the one without twin), so that rotating counter-clockwise from it, h -> twin(prev(h)),
  /// visits the whole fan; for an interior vertex it is the lowest outgoing half-edge id.
  [[nodiscard]] HalfedgeId vertex_halfedge(VertexId v) const { return vertex_halfedge_[v.index()]; }
  [[nodiscard]] bool is_boundary(VertexId v) const;
  /// Faces around v in fan order (counter-clockwise seen from the normal side). O(valence).
  [[nodiscard]] std::vector<FaceId> vertex_faces(VertexId v) const;
  /// One-ring neighbours of v in fan order. O(valence).
  [[nodiscard]] std::vector<VertexId> vertex_neighbors(VertexId v) const;

  // --- edges and boundary ------------------------------------------------------------------
  /// One half-edge per undirected edge (the boundary half-edge, or the lower id of a pair),
  /// in increasing half-edge order. O(H).
  [[nodiscard]] std::vector<HalfedgeId> edges() const;
  /// Every boundary loop as vertices in the direction of its boundary half-edges (mesh on the
  /// left), each loop starting at its smallest vertex id, loops sorted by that id. O(H).
  [[nodiscard]] std::vector<std::vector<VertexId>> boundary_loops() const;
  /// V - E + F.
  [[nodiscard]] int euler_characteristic() const;

  // --- geometry ----------------------------------------------------------------------------
  [[nodiscard]] const std::vector<Vec3>& positions() const { return positions_; }
  [[nodiscard]] const Vec3& position(VertexId v) const { return positions_[v.index()]; }
  void set_position(VertexId v, const Vec3& p) { positions_[v.index()] = p; }
  /// Replaces all positions; throws InvalidArgument if the size differs from num_vertices().
  void set_positions(std::vector<Vec3> positions);

  [[nodiscard]] Vec3 face_normal(FaceId f) const;  ///< unit normal (zero for a degenerate face)
  [[nodiscard]] double face_area(FaceId f) const;
  [[nodiscard]] Vec3 face_centroid(FaceId f) const;
  [[nodiscard]] double total_area() const;
  [[nodiscard]] double mean_edge_length() const;
  /// Area-weighted unit vertex normals. O(F).
  [[nodiscard]] std::vector<Vec3> vertex_normals() const;
  [[nodiscard]] Eigen::AlignedBox3d bounds() const;

  /// Faces whose area is below rel_tol * (mean edge length)^2: near-degenerate triangles.
  [[nodiscard]] std::vector<FaceId> degenerate_faces(double rel_tol = 1e-10) const;

  /// Re-derives every invariant from the face array and positions and compares with the
  /// stored adjacency: index ranges, twin symmetry and opposite direction, edge multiplicity,
  /// vertex manifoldness, consistent orientation, finite positions, degenerate faces.
  /// Used after every edit in tests. O(F log F).
  [[nodiscard]] ValidationReport validate() const;

  // --- flat arrays for the renderer --------------------------------------------------------
  [[nodiscard]] std::vector<float> flat_positions() const;         ///< xyz per vertex
  [[nodiscard]] std::vector<std::uint32_t> flat_triangles() const;  ///< 3 indices per face

 private:
  void build_adjacency();

  std::vector<Vec3> positions_;
  std::vector<FaceIndices> faces_;
  std::vector<HalfedgeId> twin_;             // per half-edge
  std::vector<HalfedgeId> vertex_halfedge_;  // per vertex
  std::size_t num_edges_ = 0;
};

}  // namespace sutura::engine
