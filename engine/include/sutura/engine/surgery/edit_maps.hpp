#pragma once
// Parent maps returned by every topology edit (geometry-central style): they say where each
// new vertex and face came from, so that simulation state, per-element rest geometry,
// materials and constraints can be carried across the edit (carry.hpp) without the edit
// knowing about any of them.
#include <vector>

#include <Eigen/Core>

#include "sutura/engine/ids.hpp"

namespace sutura::engine {

/// How a new vertex relates to the old mesh. Decides how per-vertex data is carried:
/// constraints are copied, intersected (a point between a fixed and a free vertex is free) or
/// united (a suture of a fixed and a free vertex is fixed).
enum class VertexOriginKind {
  Copy,          ///< the same material point (also: one lip copy of an incised vertex)
  Interpolated,  ///< a new point inside an old edge or face (weights = barycentric coordinates)
  Merged,        ///< a suture: the copies of one simulated vertex, weights 1/n each
};

struct VertexOrigin {
  VertexOriginKind kind = VertexOriginKind::Copy;
  std::vector<VertexId> parents;  ///< old vertices, non-empty
  std::vector<double> weights;    ///< same size, sum 1; new position = sum w_i x_i
};

/// How a new face relates to the old mesh. Decides how its rest shape is carried (carry.hpp).
enum class FaceOriginKind {
  /// Inside its parent (a sub-face of a split, or the parent itself): rest corners by the
  /// barycentrics, exact since a triangle's current-to-rest map is affine.
  Subface,
  /// Made by a remesh: its corners lie on the old surface, possibly in several old faces.
  /// `parent` is the old face under its centroid and `bary` the corners' barycentrics in the
  /// parent's plane (they may leave [0, 1]); its rest shape comes from its own current shape
  /// pulled back through the parent's strain (carry.hpp, docs/remeshing.md).
  Resampled,
};

/// Row k of `bary` holds the barycentric coordinates of new corner k with respect to the
/// parent's corners (identity for an untouched face).
struct FaceOrigin {
  FaceId parent;
  Eigen::Matrix3d bary = Eigen::Matrix3d::Identity();
  FaceOriginKind kind = FaceOriginKind::Subface;
};

struct EditMaps {
  std::vector<VertexOrigin> vertices;  ///< one per vertex of the new mesh
  std::vector<FaceOrigin> faces;       ///< one per face of the new mesh

  /// Identity maps of a mesh with nv vertices and nf faces.
  static EditMaps identity(std::size_t nv, std::size_t nf);
};

/// Maps of `second` applied after `first` (second's parents index first's new mesh).
/// Merges that meet interpolation are expanded linearly; the kind is the "strongest" of the
/// two (Merged > Interpolated > Copy; Resampled > Subface). Cost O(V + F).
EditMaps compose(const EditMaps& first, const EditMaps& second);

}  // namespace sutura::engine
