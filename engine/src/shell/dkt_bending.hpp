#pragma once
// DKT plate-bending triangle (private to engine/src/shell).
//
// Batoz, Bathe & Ho, "A study of three-node triangular plate bending elements",
// IJNME 15 (1980) 1771-1812. The normal-rotation field beta = (beta_x, beta_y) (fibre tilt,
// beta = -grad w in the Kirchhoff limit) is quadratic on the 6-node triangle; its side-midpoint
// values are eliminated by the discrete Kirchhoff constraints: the tangential component equals
// -dw/ds of the cubic Hermite w along the side, the normal component varies linearly.
// Curvatures kappa = [beta_x,x, beta_y,y, beta_x,y + beta_y,x] are linear, so the 3-point
// side-midpoint rule integrates K = int B^T D B dA exactly; D = t^3/12 C (plane stress).
//
// Local DOFs per corner: (w, theta_x, theta_y), with the rotation-vector components theta
// related to the fibre tilt by beta_x = theta_y, beta_y = -theta_x. Corners counter-clockwise.
// Units: mm, N; stiffness N/mm, N, N*mm. Cost: about 2k flops.
#include <array>

#include <Eigen/Core>

#include "sutura/engine/shell/material.hpp"

namespace sutura::engine {

/// Curvature-displacement matrix (3x9) at barycentric coordinates `L` (sum 1), 1/mm.
Eigen::Matrix<double, 3, 9> dkt_curvature_matrix(const std::array<Eigen::Vector2d, 3>& p,
                                                 const Eigen::Vector3d& L);

/// 9x9 bending stiffness of the triangle with local corner coordinates `p`.
Eigen::Matrix<double, 9, 9> dkt_bending_stiffness(const std::array<Eigen::Vector2d, 3>& p,
                                                  const ShellMaterial& m);

}  // namespace sutura::engine
