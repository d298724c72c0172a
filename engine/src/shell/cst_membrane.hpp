#pragma once
// Constant-strain triangle (CST) membrane with the St.Venant-Kirchhoff energy (Model 2).
//
// Written in covariant (metric) form, so the element needs only the intrinsic shape of its own
// rest triangle X (never a per-vertex rest position, never its placement in space):
//   d1 = x1 - x0, d2 = x2 - x0,   a = [di . dj]      (current first fundamental form, 2x2)
//   abar = the same from the rest corners X
//   E = (a - abar) / 2                                 (covariant Green-Lagrange strain)
//   L = abar^-1 E                                      (mixed strain; its eigenvalues are the
//                                                       principal Green strains)
//   W = A t [ mu tr(L^2) + lambda/2 tr(L)^2 ]         (StVK, A = rest area, t = thickness)
// with plane-stress Lame parameters lambda = E nu / (1 - nu^2), mu = E / (2 (1 + nu)).
// Units: mm, MPa => W in N*mm, gradient in N, Hessian in N/mm.
// Cost per element: ~60 flops (energy), ~250 (gradient), ~1500 (Hessian).
#include <array>

#include <Eigen/Core>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/material.hpp"

namespace sutura::engine::dshell {

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

/// Rest data of one CST element, derived from its rest corners and material.
struct CstRest {
  Eigen::Matrix2d abar;      ///< rest metric, mm^2
  Eigen::Matrix2d abar_inv;  ///< its inverse, 1/mm^2
  double area = 0.0;         ///< rest area A, mm^2
  double lambda = 0.0;       ///< A t lambda_plane_stress, N*mm
  double mu = 0.0;           ///< A t mu, N*mm
};

/// First fundamental form [di . dj] of a triangle with d1 = p1 - p0, d2 = p2 - p0.
Eigen::Matrix2d triangle_metric(const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// Precomputes the rest data. The rest triangle must be non-degenerate (checked by the caller).
CstRest make_cst_rest(const std::array<Vec3, 3>& X, const ShellMaterial& m);

/// Membrane energy of the element at corners x (N*mm); optionally its gradient (corner-major:
/// x0, x1, x2) and exact Hessian.
double cst_energy(const CstRest& r, const std::array<Vec3, 3>& x, Vec9* grad, Mat9* hess);

/// Largest principal Green-Lagrange strain of the element (signed, dimensionless).
double cst_max_principal_strain(const CstRest& r, const std::array<Vec3, 3>& x);

}  // namespace sutura::engine::dshell
