#pragma once
// Join (suture): the paper's rest-shape mapping (Sec. 2.2). Paired boundary vertices are
// merged into one simulated vertex at the mean of its copies, while every element keeps its
// own rest geometry, so one simulated vertex maps to n rest positions (1:n; n >= 3 where a
// patch corner meets two lips or incisions overlap). Purely topological: no forces, no
// springs; the relaxation (relaxation.hpp) then pulls the rest shape from y0 to x0.
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"

namespace sutura::engine {

/// Two chains sutured together. Both run in the boundary direction; the suture pairs a's
/// first vertex with b's last (and a's last with b's first), which is what keeps the joined
/// surface consistently oriented. Closed chains (two whole loops, an end-to-end anastomosis)
/// pair a's first vertex with b's first and run in opposite directions.
struct SuturePair {
  BoundaryChain a, b;
};

struct SutureReport {
  std::size_t vertices_a = 0, vertices_b = 0;  ///< before resampling
  int inserted_a = 0, inserted_b = 0;          ///< vertices added to make the counts equal
  double length_a = 0.0, length_b = 0.0;       ///< mm, along the current positions
  double max_gap = 0.0;                        ///< mm, largest distance between paired copies
};

struct JoinResult {
  SurfaceMesh mesh;
  EditMaps maps;
  std::vector<SutureReport> sutures;              ///< one per pair
  std::vector<std::vector<VertexId>> seams;       ///< per pair, the merged vertices in order
  std::vector<VertexId> merged;                   ///< every vertex made of more than one copy
};

/// Sutures all pairs in one edit. Vertices are paired by normalised arc length: vertices of
/// both chains at the same arc length (within 0.4 of the local spacing) are partners, and
/// every vertex without one gets a partner inserted by splitting the other chain's edge at
/// its arc length (the resampling the paper requires; a coarser chain is refined to the finer
/// one's vertices). Insertions are reported in `sutures`. Pairing vertices that lie at
/// different arc lengths instead would suture non-corresponding rest points and leave a shear
/// defect along the seam.
/// Throws InvalidArgument naming the suture and the problem: a chain that is not a run of
/// boundary edges in the boundary direction, chains that overlap (a chain joined with itself),
/// a closed loop paired with an open chain, a suture that would collapse a triangle or make
/// the surface non-manifold. Cost O(F log F) plus O(n_a n_b) per pair of different counts.
JoinResult join(const SurfaceMesh& mesh, const std::vector<SuturePair>& pairs);

}  // namespace sutura::engine
