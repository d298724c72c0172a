#include "shape_deformation.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <utility>

#include "../geometry/best_rotation.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

namespace {

// The weighted graph Laplacian of the free vertices that reach a prescribed one, factorised.
struct FreeLaplacian {
  std::vector<std::vector<std::pair<int, double>>> adjacent;  // per vertex: (neighbour, 1 / rest length)
  std::vector<int> unknown;                 // per vertex: row, or -1 (prescribed or unreached)
  int m = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
};

void build(const std::vector<Vec3>& positions, const std::vector<FaceIndices>& faces,
           const std::vector<bool>& prescribed, FreeLaplacian& L) {
  const std::size_t n = positions.size();
  // Undirected edges, each once (an interior edge appears in two faces).
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * faces.size());
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      const int u = f[k], v = f[(k + 1) % 3];
      edges.emplace_back(std::min(u, v), std::max(u, v));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  L.adjacent.assign(n, {});
  for (const auto& [u, v] : edges) {
    // A zero-length edge (coincident copies) gets a large but finite weight.
    const double w = 1.0 / std::max((positions[u] - positions[v]).norm(), 1e-9);
    L.adjacent[u].emplace_back(v, w);
    L.adjacent[v].emplace_back(u, w);
  }
  // Free vertices that reach a prescribed one; the others stay where they are.
  std::vector<char> reached(n, 0);
  std::vector<int> queue;
  for (std::size_t v = 0; v < n; ++v)
    if (prescribed[v]) reached[v] = 1, queue.push_back(int(v));
  for (std::size_t head = 0; head < queue.size(); ++head)
    for (const auto& [w, unused] : L.adjacent[queue[head]])
      if (!reached[w]) reached[w] = 1, queue.push_back(w);
  L.unknown.assign(n, -1);
  for (std::size_t v = 0; v < n; ++v)
    if (!prescribed[v] && reached[v]) L.unknown[v] = L.m++;
  if (L.m == 0) return;
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t v = 0; v < n; ++v) {
    const int i = L.unknown[v];
    if (i < 0) continue;
    for (const auto& [w, weight] : L.adjacent[v]) {
      triplets.emplace_back(i, i, weight);
      if (L.unknown[w] >= 0) triplets.emplace_back(i, L.unknown[w], -weight);
    }
  }
  Eigen::SparseMatrix<double> A(L.m, L.m);
  A.setFromTriplets(triplets.begin(), triplets.end());
  L.solver.compute(A);
  if (L.solver.info() != Eigen::Success)
    throw InvalidArgument("shape deformation: the Laplacian of the free vertices is singular");
}

// Harmonic extension of displacements `d` given at the prescribed vertices: adds the free
// vertices' share to `out` (entries of prescribed and unreached vertices are left alone).
void add_spread(const FreeLaplacian& L, const std::vector<Vec3>& d, std::vector<Vec3>& out) {
  if (L.m == 0) return;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(L.m, 3);
  for (std::size_t v = 0; v < L.adjacent.size(); ++v) {
    const int i = L.unknown[v];
    if (i < 0) continue;
    for (const auto& [w, weight] : L.adjacent[v])
      if (L.unknown[w] < 0) rhs.row(i) += weight * d[w].transpose();
  }
  const Eigen::MatrixXd x = L.solver.solve(rhs);
  for (std::size_t v = 0; v < out.size(); ++v)
    if (L.unknown[v] >= 0) out[v] += x.row(L.unknown[v]).transpose();
}

}  // namespace

std::vector<Vec3> harmonic_spread(const std::vector<Vec3>& positions,
                                  const std::vector<FaceIndices>& faces,
                                  const std::vector<bool>& prescribed,
                                  const std::vector<Vec3>& value) {
  const std::size_t n = positions.size();
  if (prescribed.size() != n || value.size() != n)
    throw InvalidArgument("harmonic_spread: one flag and one value per vertex needed");
  FreeLaplacian L;
  build(positions, faces, prescribed, L);
  std::vector<Vec3> d(n, Vec3::Zero());
  for (std::size_t v = 0; v < n; ++v)
    if (prescribed[v]) d[v] = value[v];
  add_spread(L, d, d);
  return d;
}

std::vector<Vec3> as_rigid_as_possible(const std::vector<Vec3>& positions,
                                       const std::vector<FaceIndices>& faces,
                                       const std::vector<bool>& prescribed,
                                       const std::vector<Vec3>& value, int iterations, int stages) {
  const std::size_t n = positions.size();
  if (prescribed.size() != n || value.size() != n)
    throw InvalidArgument("as_rigid_as_possible: one flag and one value per vertex needed");
  if (iterations < 0 || stages < 1)
    throw InvalidArgument("as_rigid_as_possible: iterations >= 0 and stages >= 1 needed");
  FreeLaplacian L;
  build(positions, faces, prescribed, L);
  std::vector<Vec3> p = positions;
  std::vector<Eigen::Matrix3d> R(n);
  for (int stage = 1; stage <= stages; ++stage) {
    // Move the prescribed vertices to this stage's targets and warm-start the free ones by
    // the harmonic spread of that step (exact for a translation, so a part that only
    // translates comes out translated to round-off).
    std::vector<Vec3> step(n, Vec3::Zero());
    for (std::size_t v = 0; v < n; ++v) {
      if (!prescribed[v]) continue;
      const Vec3 target = stage == stages
                              ? Vec3(positions[v] + value[v])
                              : Vec3(positions[v] + value[v] * (double(stage) / stages));
      step[v] = target - p[v];
      p[v] = target;
    }
    if (L.m == 0) continue;
    add_spread(L, step, p);
    for (int it = 0; it < iterations; ++it) {
      // Local step: the rotation that best maps each rest neighbourhood onto the current one.
      for (std::size_t v = 0; v < n; ++v) {
        Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
        for (const auto& [w, weight] : L.adjacent[v])
          S += weight * (positions[v] - positions[w]) * (p[v] - p[w]).transpose();
        R[v] = best_rotation(S);
      }
      // Global step: positions that best match the rotated rest edges.
      Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(L.m, 3);
      for (std::size_t v = 0; v < n; ++v) {
        const int i = L.unknown[v];
        if (i < 0) continue;
        for (const auto& [w, weight] : L.adjacent[v]) {
          rhs.row(i) += (0.5 * weight * (R[v] + R[w]) * (positions[v] - positions[w])).transpose();
          if (L.unknown[w] < 0) rhs.row(i) += weight * p[w].transpose();
        }
      }
      const Eigen::MatrixXd x = L.solver.solve(rhs);
      for (std::size_t v = 0; v < n; ++v)
        if (L.unknown[v] >= 0) p[v] = x.row(L.unknown[v]).transpose();
    }
  }
  return p;
}

}  // namespace sutura::engine::detail
