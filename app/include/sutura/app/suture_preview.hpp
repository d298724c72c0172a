#pragma once
// The suture tool's reading of the surgeon's clicks. Each side is named by clicking its two
// ends, in either order: the tool takes the arc between them (the shorter one unless the
// surgeon asks for the long way round) and orders the ends so that the arc runs in the
// boundary direction, as the join op resolves chains. Side B never takes an arc sharing an
// edge with side A (a lip is not sutured to itself), so clicking both lips of an incision
// from the same end gives the two lips. The join then pairs A's first end with B's last:
// the only pairing that keeps the joined surface consistently oriented.
//
// The same point clicked twice names that vertex's whole boundary loop, starting there (an
// open end, for an end-to-end anastomosis); two loops pair first with first, running in
// opposite directions. With `lip_to_lip`, at a point of a cut, where the two lips have a copy
// each, it names instead the arc from one lip round to the other (the shorter one, or the long
// way round; side B the other arc): clicked for both sides at the corner where a subclavian
// artery's incision meets the aortotomy, the flap (the opened artery) and the aortotomy it is
// sewn into. Both readings are offered because an incised open end is both a loop and a cut.
#include <array>
#include <string>
#include <vector>

#include "sutura/app/op_builders.hpp"
#include "sutura/engine/mesh.hpp"

namespace sutura::app {

/// The complete sides among `clicks` (click order: A end, A end, B end, B end), as the join
/// op will record them: ends in the boundary direction, and `via` where the ends alone would
/// name another arc. A side whose arc cannot be resolved either way keeps its click order
/// (preview_suture says why). Cost: a few chain resolutions per side, O(boundary length) each.
std::vector<ChainEnds> suture_sides(const engine::SurfaceMesh& mesh, const std::vector<engine::Vec3>& clicks,
                                    std::array<bool, 2> long_way = {false, false},
                                    bool lip_to_lip = false);

struct SuturePreview {
  std::vector<std::vector<engine::Vec3>> chains;  ///< resolved chains, polylines to draw
  std::vector<double> lengths;                    ///< mm, per chain
  /// With both chains: the ends that meet (A's first and B's last, A's last and B's first;
  /// for two loops, their first vertices).
  std::vector<std::array<engine::Vec3, 2>> meeting_ends;
  std::vector<std::string> lines;                 ///< text for the panel
};

/// What the join of suture_sides(mesh, clicks, long_way, lip_to_lip) will resolve: chains in the rules of
/// the join op (nearest boundary vertices to each point, boundary direction, `via`); a click
/// that resolves to nothing is explained in `lines`.
SuturePreview preview_suture(const engine::SurfaceMesh& mesh, const std::vector<engine::Vec3>& clicks,
                             std::array<bool, 2> long_way = {false, false}, bool lip_to_lip = false);

}  // namespace sutura::app
