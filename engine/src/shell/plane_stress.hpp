#pragma once
// Isotropic plane-stress constitutive matrix (private to engine/src/shell).
// Voigt order [xx, yy, xy] with engineering shear strain gamma_xy = 2 eps_xy:
// C = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]], MPa. Membrane stiffness is t*C,
// bending stiffness t^3/12 * C.
#include <Eigen/Core>

#include "sutura/engine/shell/material.hpp"

namespace sutura::engine {

inline Eigen::Matrix3d plane_stress_matrix(const ShellMaterial& m) {
  const double nu = m.poisson_ratio;
  const double k = m.youngs_modulus / (1.0 - nu * nu);
  Eigen::Matrix3d C;
  C << k, k * nu, 0.0,  //
      k * nu, k, 0.0,   //
      0.0, 0.0, 0.5 * k * (1.0 - nu);
  return C;
}

}  // namespace sutura::engine
