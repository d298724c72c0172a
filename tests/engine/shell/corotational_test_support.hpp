#pragma once
// Small meshes, problem set-up, finite differences and a minimal Newton loop for the tests of
// the corotational shell (Model 1) and the rest states. Header-only, test code only.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine::test {

struct FlatArrays {
  std::vector<Vec3> x;
  std::vector<FaceIndices> faces;
};

/// Grid of (nu+1) x (nv+1) points mapped by `point(i, j)`, quads split along alternating
/// diagonals, counter-clockwise in (i, j).
template <class PointFn>
FlatArrays grid(int nu, int nv, PointFn point) {
  FlatArrays m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) m.x.push_back(point(i, j));
  auto id = [nu](int i, int j) { return static_cast<std::int32_t>(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const auto a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      } else {
        m.faces.push_back({a, b, d});
        m.faces.push_back({b, c, d});
      }
    }
  return m;
}

/// Flat strip x in [0, length], y in [-width/2, width/2], z = 0.
inline FlatArrays strip(double length, double width, int nx, int ny) {
  return grid(nx, ny, [&](int i, int j) {
    return Vec3(length * i / nx, -0.5 * width + width * j / ny, 0.0);
  });
}

/// Cylindrical panel of radius r around the z axis, angles [0, span], z in [0, length].
inline FlatArrays cylinder_panel(double r, double span, double length, int n_around,
                                 int n_along) {
  return grid(n_around, n_along, [&](int i, int j) {
    const double phi = span * i / n_around;
    return Vec3(r * std::cos(phi), r * std::sin(phi), length * j / n_along);
  });
}

/// Closed tube of radius r around the z axis, z in [0, length] (the seam column of the grid
/// is merged onto the first one; its points stay in `x` unused).
inline FlatArrays tube(double r, double length, int n_around, int n_along) {
  FlatArrays m = cylinder_panel(r, 2.0 * 3.141592653589793, length, n_around, n_along);
  for (auto& f : m.faces)
    for (auto& v : f)
      if (v % (n_around + 1) == n_around) v -= n_around;
  return m;
}

/// Irregular flat patch: a 4 x 4-cell square of side `size` whose interior points are moved
/// by up to 30 % of a cell in fixed pseudo-random directions.
inline FlatArrays irregular_patch(double size) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const int n = 4;
  const double h = size / n;
  return grid(n, n, [&](int i, int j) {
    Vec3 p(h * i, h * j, 0.0);
    if (i > 0 && i < n && j > 0 && j < n) p += Vec3(u(rng) * h, u(rng) * h, 0.0);
    return p;
  });
}

/// Owns everything a ShellProblem points to (one material for all faces).
struct ProblemSetup {
  std::vector<FaceIndices> faces;
  RestState rest;
  std::vector<ShellMaterial> materials;
  std::vector<int> face_material;
  std::size_t num_nodes = 0;

  ProblemSetup(const FlatArrays& m, const ShellState& rest_state, const ShellMaterial& mat)
      : faces(m.faces),
        rest(rest_from_state(m.faces, rest_state)),
        materials{mat},
        face_material(m.faces.size(), 0),
        num_nodes(m.x.size()) {}
  [[nodiscard]] ShellProblem problem() const {
    return {&faces, &rest, &materials, &face_material, num_nodes};
  }
};

inline ShellState identity_state(const std::vector<Vec3>& x) {
  return {x, std::vector<Quat>(x.size(), Quat::Identity())};
}

inline Quat random_rotation(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 axis(u(rng), u(rng), u(rng));
  axis.normalize();
  return Quat(Eigen::AngleAxisd(max_angle * std::abs(u(rng)), axis));
}

/// exp([w]x) as a quaternion.
inline Quat rotation(const Vec3& w) {
  const double a = w.norm();
  return a == 0.0 ? Quat::Identity() : Quat(Eigen::AngleAxisd(a, w / a));
}

/// The state displaced by `h` along DOF `k` (through apply_increment).
inline ShellState displaced(const ShellState& s, Eigen::Index k, double h, int dofs) {
  ShellState r = s;
  Eigen::VectorXd du = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.x.size()) * dofs);
  du(k) = h;
  apply_increment(r, du, dofs);
  return r;
}

inline Eigen::SparseMatrix<double> assemble(const Triplets& t, Eigen::Index n) {
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

/// Minimal Newton solver for tests: solves g(s) = f_ext on the DOFs with free[k] = true,
/// with the nonsymmetric consistent tangent and SparseLU. Returns the residual norms
/// |g - f_ext| (free DOFs) before each iteration and after the last one.
inline std::vector<double> newton(const ShellModel& model, const ShellProblem& p, ShellState& s,
                                  const Eigen::VectorXd& f_ext, const std::vector<bool>& free,
                                  double tol, int max_iter) {
  const auto n = static_cast<Eigen::Index>(free.size());
  std::vector<Eigen::Index> reduced(free.size(), -1);
  Eigen::Index nf = 0;
  for (Eigen::Index k = 0; k < n; ++k)
    if (free[k]) reduced[k] = nf++;
  std::vector<double> history;
  for (int it = 0;; ++it) {
    Eigen::VectorXd g;
    Triplets t;
    model.energy_gradient_hessian(p, s, g, t, /*symmetric=*/false);
    Eigen::VectorXd r(nf);
    for (Eigen::Index k = 0; k < n; ++k)
      if (free[k]) r(reduced[k]) = g(k) - f_ext(k);
    history.push_back(r.norm());
    if (history.back() < tol || it == max_iter) return history;
    Triplets tr;
    for (const auto& e : t)
      if (free[e.row()] && free[e.col()])
        tr.emplace_back(reduced[e.row()], reduced[e.col()], e.value());
    Eigen::SparseMatrix<double> K = assemble(tr, nf);
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(K);
    const Eigen::VectorXd dr = lu.solve(-r);
    Eigen::VectorXd du = Eigen::VectorXd::Zero(n);
    for (Eigen::Index k = 0; k < n; ++k)
      if (free[k]) du(k) = dr(reduced[k]);
    apply_increment(s, du, model.dofs_per_node());
  }
}

}  // namespace sutura::engine::test
