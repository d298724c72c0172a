#pragma once
// TriangleSoup: a small mutable face array for local refinement (edge and face splits) during
// one topology edit. SurfaceMesh is rebuilt once at the end (O(F log F)) instead of after
// every split; a directed-edge table makes each split O(1) expected.
//
// Every vertex and face keeps its origin in the mesh the soup was made from (EditMaps), so the
// final maps need no composition.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"

namespace sutura::engine::detail {

class TriangleSoup {
 public:
  explicit TriangleSoup(const SurfaceMesh& mesh);

  [[nodiscard]] std::size_t num_vertices() const { return positions_.size(); }
  [[nodiscard]] std::size_t num_faces() const { return faces_.size(); }
  [[nodiscard]] const Vec3& position(int v) const { return positions_[v]; }
  [[nodiscard]] const FaceIndices& face(int f) const { return faces_[f]; }
  [[nodiscard]] const EditMaps& maps() const { return maps_; }
  /// The soup faces descending from original face `parent` (they tile it).
  [[nodiscard]] const std::vector<int>& faces_of(FaceId parent) const {
    return faces_of_parent_[parent.index()];
  }

  /// Face holding the directed edge u -> v, or -1.
  [[nodiscard]] int face_with_edge(int u, int v) const;
  [[nodiscard]] bool has_edge(int u, int v) const {
    return face_with_edge(u, v) >= 0 || face_with_edge(v, u) >= 0;
  }

  /// Inserts a vertex at (1-t) u + t v on the edge {u, v} (interior or boundary) and splits
  /// the one or two faces holding it, connecting the new vertex to their opposite corners.
  /// Returns the new vertex. Throws InvalidArgument if {u, v} is not an edge.
  int split_edge(int u, int v, double t);
  /// Inserts a vertex at barycentric coordinates `b` (all > 0) of face f and splits the face
  /// into three. Returns the new vertex.
  int split_face(int f, const Eigen::Vector3d& b);

  /// The soup face among those descending from original face `parent` that contains the point
  /// with original barycentric coordinates `b`, and its local barycentric coordinates there.
  /// Returns -1 when none does (within a small tolerance).
  int locate(FaceId parent, const Eigen::Vector3d& b, Eigen::Vector3d& local) const;

  /// Builds the mesh (validating it) and moves out the maps.
  SurfaceMesh build(EditMaps& maps) &&;

 private:
  static std::uint64_t key(int u, int v) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) |
           static_cast<std::uint32_t>(v);
  }
  int add_vertex(const Vec3& p, const std::vector<int>& from, const std::vector<double>& w);
  void set_face(int f, const FaceIndices& idx, const Eigen::Matrix3d& bary);
  int add_face(const FaceIndices& idx, FaceId parent, const Eigen::Matrix3d& bary);

  std::vector<Vec3> positions_;
  std::vector<FaceIndices> faces_;
  std::vector<std::vector<int>> faces_of_parent_;  // original face -> soup faces
  EditMaps maps_;
  std::unordered_map<std::uint64_t, int> edge_face_;  // directed edge -> face (lookups only)
};

}  // namespace sutura::engine::detail
