#pragma once
// Boundary chains: runs of boundary vertices, the things a suture joins.
#include <optional>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

/// Boundary vertices in the boundary direction (mesh on the left, as SurfaceMesh's boundary
/// loops run). `closed`: a whole loop, first vertex not repeated.
struct BoundaryChain {
  std::vector<VertexId> vertices;
  bool closed = false;
};

/// The chain from `from` to `to` following the boundary direction; from == to gives the whole
/// loop starting there (closed). Throws InvalidArgument when a vertex is not on the boundary
/// or the two are on different loops. O(boundary length).
BoundaryChain boundary_chain(const SurfaceMesh& mesh, VertexId from, VertexId to);

/// How a user names a chain: points near its ends (each resolved to the nearest boundary
/// vertex), or one point for a whole loop.
struct ChainSpec {
  Vec3 from = Vec3::Zero();
  Vec3 to = Vec3::Zero();
  /// Optional point near the chain: picks between candidate arcs when `from` or `to` resolve
  /// to coincident vertices (both lips of a fresh cut). Without it the shortest arc wins.
  std::optional<Vec3> via;
  bool loop = false;          ///< the whole boundary loop nearest `from`, starting there
  double max_distance = 1.0;  ///< mm: a point farther from the boundary is an error
};

/// Resolves a ChainSpec. Throws InvalidArgument naming the problem: a point farther than
/// max_distance from every boundary vertex, from/to on different loops, from and to resolving
/// to the same vertex without `loop`.
BoundaryChain find_boundary_chain(const SurfaceMesh& mesh, const ChainSpec& spec);

/// Length of the chain along its edges (closing edge included for a loop), mm.
double chain_length(const SurfaceMesh& mesh, const BoundaryChain& chain);

}  // namespace sutura::engine
