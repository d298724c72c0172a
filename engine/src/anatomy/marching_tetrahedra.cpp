#include "marching_tetrahedra.hpp"

#include <algorithm>
#include <unordered_map>
#include <utility>

namespace sutura::engine::anatomy {
namespace {

// Corner c of a cube has offset (c & 1, (c >> 1) & 1, (c >> 2) & 1). The six tetrahedra of the
// Kuhn split follow the monotone paths 0 -> 7 through the cube edges, one per axis order.
constexpr std::array<std::array<int, 4>, 6> kTets = {{
    {0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7},
}};

Vec3 corner_offset(int c) { return Vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1); }

// Parity of the permutation that sorts `order` (positions 0..3): true when odd.
bool odd_permutation(std::array<int, 4> order) {
  int swaps = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (order[i] > order[j]) ++swaps;
  return swaps % 2 == 1;
}

class Extractor {
 public:
  Extractor(const std::vector<double>& field, const Vec3& origin, double h,
            const std::array<int, 3>& n)
      : field_(field), origin_(origin), h_(h), n_(n) {}

  TriangleMesh run() {
    // Tetrahedra whose corner order (as listed in kTets) is negatively oriented get two
    // corners swapped, so every tetrahedron below is positively oriented.
    std::array<std::array<int, 4>, 6> tets = kTets;
    for (auto& t : tets) {
      const Vec3 a = corner_offset(t[0]);
      const double det = (corner_offset(t[1]) - a)
                             .dot((corner_offset(t[2]) - a).cross(corner_offset(t[3]) - a));
      if (det < 0.0) std::swap(t[2], t[3]);
    }
    for (int k = 0; k + 1 < n_[2]; ++k)
      for (int j = 0; j + 1 < n_[1]; ++j)
        for (int i = 0; i + 1 < n_[0]; ++i) {
          std::array<std::int64_t, 8> node{};
          int inside = 0;
          for (int c = 0; c < 8; ++c) {
            node[c] = index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
            if (field_[node[c]] < 0.0) ++inside;
          }
          if (inside == 0 || inside == 8) continue;
          for (const auto& t : tets)
            tetrahedron({node[t[0]], node[t[1]], node[t[2]], node[t[3]]});
        }
    return std::move(mesh_);
  }

 private:
  std::int64_t index(int i, int j, int k) const {
    return i + static_cast<std::int64_t>(n_[0]) * (j + static_cast<std::int64_t>(n_[1]) * k);
  }

  Vec3 node_position(std::int64_t id) const {
    const std::int64_t i = id % n_[0];
    const std::int64_t j = (id / n_[0]) % n_[1];
    const std::int64_t k = id / (static_cast<std::int64_t>(n_[0]) * n_[1]);
    return origin_ + h_ * Vec3(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
  }

  // Vertex on the edge from inside node a to outside node b.
  std::int32_t edge_vertex(std::int64_t a, std::int64_t b) {
    const std::int64_t lo = std::min(a, b), hi = std::max(a, b);
    const std::int64_t key = lo * static_cast<std::int64_t>(field_.size()) + hi;
    const auto [it, inserted] = vertex_of_edge_.try_emplace(key, static_cast<std::int32_t>(mesh_.positions.size()));
    if (inserted) {
      const double fa = field_[a], fb = field_[b];
      const double t = std::clamp(fa / (fa - fb), 0.02, 0.98);
      mesh_.positions.push_back(node_position(a) + t * (node_position(b) - node_position(a)));
    }
    return it->second;
  }

  // v is positively oriented. Orientation rules (checked on the unit corner tetrahedron):
  // with inside corner v0 first in an even permutation, triangle (e01, e02, e03) faces away
  // from v0; with inside corners v0, v1 and outside v2, v3 in an even permutation, the quad
  // (e02, e03, e13, e12) faces the outside corners.
  void tetrahedron(const std::array<std::int64_t, 4>& v) {
    std::array<int, 4> in{}, out{};
    int ni = 0, no = 0;
    for (int c = 0; c < 4; ++c) (field_[v[c]] < 0.0 ? in[ni++] : out[no++]) = c;
    if (ni == 0 || ni == 4) return;
    if (ni == 2) {
      std::array<int, 4> order = {in[0], in[1], out[0], out[1]};
      if (odd_permutation(order)) std::swap(order[2], order[3]);
      const auto a = v[order[0]], b = v[order[1]], c = v[order[2]], d = v[order[3]];
      const std::int32_t ac = edge_vertex(a, c), ad = edge_vertex(a, d);
      const std::int32_t bd = edge_vertex(b, d), bc = edge_vertex(b, c);
      mesh_.faces.push_back({ac, ad, bd});
      mesh_.faces.push_back({ac, bd, bc});
      return;
    }
    // One corner differs from the other three; put it first in an even permutation.
    const bool lone_inside = ni == 1;
    const int lone = lone_inside ? in[0] : out[0];
    std::array<int, 4> order{lone, 0, 0, 0};
    for (int c = 0, m = 1; c < 4; ++c)
      if (c != lone) order[m++] = c;
    if (odd_permutation(order)) std::swap(order[2], order[3]);
    std::array<std::int32_t, 3> tri{};
    for (int m = 0; m < 3; ++m)
      tri[m] = lone_inside ? edge_vertex(v[order[0]], v[order[m + 1]])
                           : edge_vertex(v[order[m + 1]], v[order[0]]);
    // The triangle faces away from the lone corner: outwards if it is inside, else inwards.
    if (lone_inside)
      mesh_.faces.push_back({tri[0], tri[1], tri[2]});
    else
      mesh_.faces.push_back({tri[0], tri[2], tri[1]});
  }

  const std::vector<double>& field_;
  Vec3 origin_;
  double h_;
  std::array<int, 3> n_;
  TriangleMesh mesh_;
  std::unordered_map<std::int64_t, std::int32_t> vertex_of_edge_;
};

}  // namespace

TriangleMesh marching_tetrahedra(const std::vector<double>& field, const Vec3& origin, double h,
                                 const std::array<int, 3>& n) {
  return Extractor(field, origin, h, n).run();
}

}  // namespace sutura::engine::anatomy
