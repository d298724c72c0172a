#include "hinge_topology.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "sutura/engine/errors.hpp"

namespace sutura::engine::dshell {

HingeTopology build_hinge_topology(const std::vector<FaceIndices>& faces) {
  const std::size_t num_faces = faces.size();
  // (undirected edge key, half-edge id), sorted: the half-edges of one edge become adjacent.
  std::vector<std::pair<std::uint64_t, std::int32_t>> keyed;
  keyed.reserve(3 * num_faces);
  for (std::size_t f = 0; f < num_faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::uint32_t>(faces[f][k]);
      const auto v = static_cast<std::uint32_t>(faces[f][(k + 1) % 3]);
      const std::uint64_t key = (std::uint64_t{std::min(u, v)} << 32) | std::max(u, v);
      keyed.emplace_back(key, static_cast<std::int32_t>(3 * f + k));
    }
  }
  std::sort(keyed.begin(), keyed.end());

  HingeTopology topo;
  topo.face_hinge.assign(num_faces, {-1, -1, -1});
  auto edge_name = [](std::uint64_t key) {
    return "edge (" + std::to_string(key >> 32) + ", " + std::to_string(key & 0xffffffffu) + ")";
  };
  for (std::size_t i = 0; i < keyed.size();) {
    std::size_t j = i + 1;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    if (j - i > 2) {
      throw TopologyError("discrete shell: " + edge_name(keyed[i].first) + " is shared by " +
                          std::to_string(j - i) + " faces (non-manifold)");
    }
    if (j - i == 2) {
      Hinge h;
      for (int side = 0; side < 2; ++side) {
        const std::int32_t he = keyed[i + side].second;
        h.face[side] = he / 3;
        h.halfedge[side] = he % 3;
      }
      const FaceIndices& f = faces[h.face[0]];
      const FaceIndices& g = faces[h.face[1]];
      const int kf = h.halfedge[0];
      const int kg = h.halfedge[1];
      if (f[kf] != g[(kg + 1) % 3]) {
        throw TopologyError("discrete shell: faces " + std::to_string(h.face[0]) + " and " +
                            std::to_string(h.face[1]) + " traverse " +
                            edge_name(keyed[i].first) +
                            " in the same direction (inconsistent orientation)");
      }
      h.node = {f[kf], f[(kf + 1) % 3], f[(kf + 2) % 3], g[(kg + 2) % 3]};
      const auto id = static_cast<std::int32_t>(topo.hinges.size());
      topo.face_hinge[h.face[0]][kf] = id;
      topo.face_hinge[h.face[1]][kg] = id;
      topo.hinges.push_back(h);
    }
    i = j;
  }
  return topo;
}

std::array<int, 4> hinge_slots(int k, int side) {
  const int k1 = (k + 1) % 3;
  const int k2 = (k + 2) % 3;
  if (side == 0) return {k, k1, k2, 3 + k};  // a = corner k, b = k+1, c = k+2, d across k
  return {k1, k, 3 + k, k2};                  // b = corner k, a = k+1, d = k+2, c across k
}

}  // namespace sutura::engine::dshell
