#pragma once
// Test helpers for the engine's CHOLMOD internals: a supernodal LL^T whose factor object is
// reachable, and a grid Laplacian that CHOLMOD orders by nested dissection.
#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <vector>

namespace sutura::engine::testing {

class SupernodalLlt : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> {
 public:
  [[nodiscard]] const cholmod_factor& factor() const { return *m_cholmodFactor; }
  [[nodiscard]] cholmod_factor& factor() { return *m_cholmodFactor; }
};

// 2D Laplacian plus `diagonal - 4` times the identity on an n x n grid (positive definite for
// diagonal > 4 - 4 cos(pi / (n + 1)) * 2).
inline Eigen::SparseMatrix<double> grid_laplacian(int n, double diagonal = 5.0) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), diagonal);
      if (i + 1 < n) t.emplace_back(id(i, j), id(i + 1, j), -1.0), t.emplace_back(id(i + 1, j), id(i, j), -1.0);
      if (j + 1 < n) t.emplace_back(id(i, j), id(i, j + 1), -1.0), t.emplace_back(id(i, j + 1), id(i, j), -1.0);
    }
  Eigen::SparseMatrix<double> A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace sutura::engine::testing
