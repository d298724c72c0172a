#pragma once
// Matched seams: before a suture, both chains of each pair are resampled to the same number
// of equal arc-length segments and the band of faces around each is remeshed at that
// spacing, so that the join pairs their vertices one to one and inserts none. Why: pairing
// chains of different spacings by arc length (join.hpp) inserts partners next to existing
// vertices, and the thin triangles beside the seam are the worst elements of a repaired mesh
// (docs/remeshing.md: down to 1 degree after a resection anastomosis). Each side is remeshed
// in its own configuration before the join, where it is whole and (for a fresh patch) in its
// rest shape, not in the joined shape, which is far from any rest shape across a wide gap.
#include <array>
#include <utility>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"
#include "sutura/engine/surgery/edit_maps.hpp"
#include "sutura/engine/surgery/join.hpp"
#include "sutura/engine/surgery/remesh.hpp"

namespace sutura::engine {

/// A chain to resample: its new inner points at these fractions of its length from its
/// first vertex (increasing, in (0, 1); a loop needs at least two).
struct ChainResample {
  BoundaryChain chain;
  std::vector<double> at;
};

/// The inner fractions of `segments` equal pieces: 1/segments, ..., (segments-1)/segments.
std::vector<double> equal_fractions(int segments);

struct ResampleChainsParams {
  /// mm, > 0: the spacing of the remeshed band (normally each chain's length / segments).
  double target_edge_length = 0.0;
  /// The band: faces with a corner within this many target lengths of a chain.
  double band_width = 2.0;
  /// >= 1: > 1 grades the band from the target length at the chains to the spacing around
  /// it (RemeshParams::grading; the band widened to hold the grading). The chains, joined in
  /// the order given, are the grading curve: give chains that continue one another (the two
  /// lips of an incision).
  double grading = 1.0;
  /// The band remesh's passes (RemeshParams::passes).
  RemeshPasses band_passes;
  /// Kept by the remesh as they are (see RemeshParams): held vertices, earlier seams.
  std::vector<bool> constrained_vertices;
  std::vector<std::pair<VertexId, VertexId>> constrained_edges;
  /// Per face (empty or mesh-sized): faces left exactly as they are. For faces whose current
  /// shape is far from their rest shape (a patch laid compressed into a closed slit): triangles
  /// made in that shape would be distorted at rest (carry.hpp). Their vertices are held, and
  /// match_seams makes their chain vertices breakpoints, with no point between them unless
  /// the edge measures more than 4/3 of the seam spacing (it is then split evenly, its face
  /// into as many parts).
  std::vector<bool> frozen_faces;
  /// Per face (empty or mesh-sized): the rest length of edge k (corners k, k + 1), mm. A
  /// frozen face's chain edge then counts at its rest length when match_seams spaces the
  /// common points, so the chain opposite a compressed patch is divided as the patch will be
  /// once it has relaxed, not as it lies (a gusset base laid at a third of its length left
  /// 0.14 mm edges on the rim sutured to it). Other edges count at their current length.
  std::vector<std::array<double, 3>> rest_edge_lengths;
  /// Degrees, >= 0, match_seams only: an inner chain vertex where the boundary turns by more
  /// than this in the surface (|180 - its faces' angle sum|: about 180 at a slit's tip, and
  /// also at a needle-sharp spike) is a breakpoint like a held vertex (so, like one, dropped
  /// when another breakpoint lies within a third of a piece). A milder corner (a lip meeting
  /// an open end: about 90) may be collapsed into a chain neighbour, cutting it by up to one
  /// seam spacing: kept as well, it would leave short seam pieces beside the other chain's
  /// breakpoints (docs/remeshing.md).
  double corner_turn_deg = 120.0;
};

struct ResampleChainsResult {
  SurfaceMesh mesh;
  EditMaps maps;  ///< from the mesh passed in
  /// The chains in the new mesh, in the order given: their ends and the new points (on the
  /// old chain), and an old vertex between two where it could not be removed.
  std::vector<BoundaryChain> chains;
  MeshQuality before, after;  ///< of the band
};

/// Resamples the chains (boundary runs of `mesh`, disjoint but for shared ends): the new
/// points are inserted, the old inner vertices removed (collapsed along the chain; a held one
/// stays), and the band around them remeshed with the new points held. Deterministic. Throws
/// InvalidArgument for a chain that is not a boundary run, fractions out of order or range,
/// or a target length <= 0; Error when the remesh cannot keep a chain (an internal error).
/// Cost: O(chain length) for the resampling, then one remesh of the band (remesh.hpp).
ResampleChainsResult resample_chains(const SurfaceMesh& mesh, const std::vector<ChainResample>& chains,
                                     const ResampleChainsParams& params);

/// The seam spacing of a suture pair: the median edge length of the faces next to its two
/// chains (band_around's), never below `min_spacing`. Cost O(F).
double seam_spacing(const SurfaceMesh& mesh, const SuturePair& pair, double min_spacing = 0.0);

/// Segments for a pair sutured at `spacing`: the mean of its chains' lengths (`length_a`,
/// `length_b`, mm) over the spacing, rounded, at least 1 (3 for loops).
int seam_segments(const SuturePair& pair, double length_a, double length_b, double spacing);

/// Resamples every pair's two chains to the same number of points at one set of fractions of
/// their lengths, each edge counted at its current length or, for a frozen face's edge with
/// params.rest_edge_lengths given, at its rest length (seam_segments pieces at its
/// seam_spacing; held vertices of either chain, ends of constrained edges meeting it, sharp
/// corners (params.corner_turn_deg) and vertices of frozen faces kept as breakpoints at their
/// own fraction; no piece longer than 4/3 of the spacing), and remeshes around them, so that
/// join(result.mesh, result.pairs) with JoinPairing::InOrder inserts no vertex. Throws
/// InvalidArgument for a corner_turn_deg below 0 or not a number; otherwise the same contract
/// and cost as resample_chains.
struct MatchedSeams {
  ResampleChainsResult edit;
  std::vector<SuturePair> pairs;
  std::vector<double> spacing;  ///< mm, per pair
};
MatchedSeams match_seams(const SurfaceMesh& mesh, const std::vector<SuturePair>& pairs,
                         ResampleChainsParams params);

}  // namespace sutura::engine
