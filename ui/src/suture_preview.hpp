#pragma once
// The suture tool's reading of the surgeon's clicks. Each side is named by clicking its two
// ends, in either order: the tool takes the arc between them (the shorter one unless the
// surgeon asks for the long way round) and orders the clicks so that the arc runs in the
// boundary direction, as the join op resolves chains. Side B never takes an arc sharing an
// edge with side A (a lip is not sutured to itself), so clicking both lips of an incision
// from the same end gives the two lips. The join then pairs A's first end with B's last:
// the only pairing that keeps the joined surface consistently oriented. A side whose two clicks
// are the same boundary vertex is that vertex's whole boundary loop, starting there (an open
// end, for an end-to-end anastomosis); two loops pair first with first, running in opposite
// directions.
#include <array>
#include <string>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::ui {

/// `clicks` in click order (any prefix of A end, A end, B end, B end), reordered per side as
/// described above; a side whose arc cannot be resolved either way keeps its click order
/// (preview_suture says why). Cost: four chain resolutions, O(boundary length) each.
std::vector<engine::Vec3> orient_suture_clicks(const engine::SurfaceMesh& mesh,
                                               const std::vector<engine::Vec3>& clicks,
                                               std::array<bool, 2> long_way = {false, false});

struct SuturePreview {
  std::vector<std::vector<engine::Vec3>> chains;  ///< resolved chains, polylines to draw
  std::vector<double> lengths;                    ///< mm, per chain
  /// With both chains: the ends that meet (A's first and B's last, A's last and B's first;
  /// for two loops, their first vertices).
  std::vector<std::array<engine::Vec3, 2>> meeting_ends;
  std::vector<std::string> lines;                 ///< text for the panel
};

/// What the join of orient_suture_clicks(mesh, clicks, long_way) will resolve: chains in
/// the rules of the join op (nearest boundary vertex to each point, boundary direction);
/// a click that resolves to nothing is explained in `lines`.
SuturePreview preview_suture(const engine::SurfaceMesh& mesh, const std::vector<engine::Vec3>& clicks,
                             std::array<bool, 2> long_way = {false, false});

}  // namespace sutura::ui
