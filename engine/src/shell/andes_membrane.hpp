#pragma once
// ANDES-OPT membrane triangle with corner drilling freedoms (private to engine/src/shell).
//
// C. A. Felippa, "A study of optimal membrane triangles with drilling freedoms",
// CMAME 192 (2003) 2125-2168: K = K_b + K_h, the basic (constant-stress) stiffness
// K_b = L C L^T / V and the higher-order stiffness
// K_h = 3/4 beta0 V T_theta_u^T (sum over side midpoints Q^T T_e^T C T_e Q) T_theta_u, with the
// optimal parameters alpha_b = 3/2, beta0 = max((1 - 4 nu^2)/2, 0.01) (isotropic),
// beta_1..9 = (1, 2, 1, 0, 1, -1, -1, -1, -2).
//
// Sutura adds a drilling penalty on the element-mean hierarchical rotation
// theta_mean - omega (omega = rotation of the linear displacement field):
// energy 1/2 * drilling_factor * G * t * A * (theta_mean - omega)^2, G = E / (2 (1 + nu)).
// It vanishes for every linear displacement field with compatible corner rotations (patch
// tests hold for any factor) and sets a floor under the drilling stiffness where ANDES-OPT's
// own (beta0-scaled) stiffness is small (nu -> 1/2).
//
// Local DOFs per corner: (u_x, u_y, theta_z); corners counter-clockwise. Units: lengths mm,
// stiffness N/mm (N*mm/rad for rotations). Cost: about 1.5k flops.
#include <array>

#include <Eigen/Core>

#include "sutura/engine/shell/material.hpp"

namespace sutura::engine {

/// 9x9 membrane stiffness of the triangle with local corner coordinates `p` (counter-clockwise,
/// positive area required).
Eigen::Matrix<double, 9, 9> andes_membrane_stiffness(const std::array<Eigen::Vector2d, 3>& p,
                                                     const ShellMaterial& m);

}  // namespace sutura::engine
