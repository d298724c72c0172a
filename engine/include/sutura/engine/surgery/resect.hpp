#pragma once
// Resection: cut a vessel across with planes and remove the part between the cuts (or beyond
// one cut: dividing a branch), leaving clean boundary loops for an anastomosis.
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"

namespace sutura::engine {

struct CutPlane {
  Vec3 origin = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  ///< need not be unit; must be non-zero
};

struct ResectionParams {
  /// mm, > 0: only edges within this distance of a plane's origin are cut, so a plane across
  /// one vessel does not also cut a branch or another segment further away.
  double radius = 10.0;
  /// Sliver guard in (0, 0.5): a crossing closer than this fraction of the edge to an end
  /// uses that vertex as the cut point instead of inserting a new one.
  double sliver_fraction = 0.15;
};

struct ResectionResult {
  SurfaceMesh mesh;
  EditMaps maps;
  /// The boundary loop left by each plane's cut, in plane order (closed chains in the new mesh).
  std::vector<BoundaryChain> loops;
  std::size_t removed_faces = 0;
  double removed_area = 0.0;  ///< mm^2 (current shape)
};

/// Cuts along each plane (1 or 2) and removes the region containing the face nearest `seed`
/// that the cuts enclose: with two planes across a vessel and the seed between them, the band
/// between the cuts (resection); with one plane across a branch and the seed beyond it, the
/// branch end (division). Throws InvalidArgument naming the problem when a plane is degenerate,
/// the seed lies farther than `radius` from the surface, a cut does not go all the way round
/// within `radius` (the region would leak past a plane), or nothing or everything would be
/// removed. Cost O(F log F).
ResectionResult resect(const SurfaceMesh& mesh, const std::vector<CutPlane>& planes,
                       const Vec3& seed, const ResectionParams& params = {});

}  // namespace sutura::engine
