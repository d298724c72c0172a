#pragma once
// Join (suture): the paper's rest-shape mapping (Sec. 2.2). Paired boundary vertices are
// merged into one simulated vertex at the mean of its copies, while every element keeps its
// own rest geometry, so one simulated vertex maps to n rest positions (1:n; n >= 3 where a
// patch corner meets two lips or incisions overlap). Purely topological: no forces, no
// springs; the relaxation (relaxation.hpp) then pulls the rest shape from y0 to x0.
#include <string>
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

/// Where the joined shape x starts.
enum class SuturePlacement {
  /// Each merged vertex at the mean of its copies; nothing else moves (the paper). Right when
  /// the chains lie close together (lips of one incision, a patch laid over it).
  Mean,
  /// Chain a is drawn onto chain b: each merged vertex at its b copy (the mean of its b
  /// copies), and the rest of the mesh follows as rigidly as possible (held vertices stay):
  /// an as-rigid-as-possible deformation (Sorkine & Alexa 2007) applied in stages, each
  /// warm-started by the harmonic extension of its step. For chains far apart, e.g. a flap turned down
  /// into an incision 15 mm away: the mean of such copies stretches the elements next to
  /// them across the gap while the rest of the flap stays behind, and the relaxation cannot
  /// untangle that start. Measured on a subclavian flap (docs/validation.md): the static
  /// relaxation from the harmonic extension alone stalls at s = 0.05, from a one-stage rigid
  /// fit at 0.64, from the staged fit (default) at 0.76.
  OntoB,
};

/// Parses "mean" | "onto_b"; throws InvalidArgument otherwise.
SuturePlacement parse_suture_placement(const std::string& name);

/// Which vertices of a pair's chains are partners.
enum class JoinPairing {
  /// By normalised arc length along the current positions; vertices without a partner get one
  /// inserted (below).
  ArcLength,
  /// In order: chains of equal counts (matched seams, seam_match.hpp) pair vertex for vertex,
  /// as stitches spaced evenly along both, whatever their current positions; nothing is
  /// inserted. Unequal counts are an error.
  InOrder,
};

struct JoinParams {
  SuturePlacement placement = SuturePlacement::Mean;
  JoinPairing pairing = JoinPairing::ArcLength;
  /// Per input vertex (or empty): vertices OntoB must not move (held supports). Every copy in
  /// a suture is prescribed anyway; a held copy of chain a still moves onto its partner.
  std::vector<bool> held;
  /// OntoB: the copies' displacement is applied in `rigid_stages` (>= 1) equal steps, each
  /// followed by `rigid_iterations` (>= 0) local/global iterations of the rigid fit (a flap
  /// turned over by 150 degrees in one step folds through itself).
  int rigid_iterations = 20;
  int rigid_stages = 8;
};

struct JoinResult {
  SurfaceMesh mesh;
  EditMaps maps;
  std::vector<SutureReport> sutures;              ///< one per pair
  std::vector<std::vector<VertexId>> seams;       ///< per pair, the merged vertices in order
  std::vector<VertexId> merged;                   ///< every vertex made of more than one copy
  /// Unmerged vertices moved by the placement (OntoB only): with `merged`, the vertices whose
  /// position in `mesh` differs from their parents' carried position.
  std::vector<VertexId> displaced;
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
/// the surface non-manifold. Cost O(F log F) plus O(n_a n_b) per pair of different counts;
/// OntoB adds one sparse Cholesky factorisation over the vertices (O(V^1.5) on a surface
/// mesh) and rigid_stages * (rigid_iterations + 1) back-substitutions with 3x3 SVDs per vertex.
/// The joined positions are in `mesh`; the maps' weights give each vertex its parents' mean.
JoinResult join(const SurfaceMesh& mesh, const std::vector<SuturePair>& pairs,
                const JoinParams& params = {});

}  // namespace sutura::engine
