#pragma once
// Shell material. Unit system throughout the engine: mm, N, s, tonne
// => stress and Young's modulus in MPa (N/mm^2), density in t/mm^3 (1060 kg/m^3 = 1.06e-9).
#include <string>

namespace sutura::engine {

struct ShellMaterial {
  double youngs_modulus = 1.0;     ///< E, MPa (infant aortic wall: about 0.5-2 MPa), > 0
  double poisson_ratio = 0.45;     ///< nu, in [0, 0.5)
  double thickness = 1.0;          ///< t, mm, > 0
  double density = 1.06e-9;        ///< rho, t/mm^3, > 0
  /// Drilling stiffness factor: the rotation about the element normal is tied to the in-plane
  /// rotation of the membrane with this fraction of the membrane shear stiffness
  /// (ANDES-OPT alpha_b / Allman-type penalty). Dimensionless, > 0; results of the tests do not
  /// depend on it within the documented range [1e-3, 1]. Model 1 keeps ANDES-OPT's own drilling
  /// stiffness and adds the penalty 1/2 drilling_factor G t A (theta_mean - omega)^2 on the
  /// element-mean corner drilling rotation minus the rotation of the linear displacement field
  /// (G = E / (2 (1 + nu)), A the rest area); it vanishes in the constant-strain patch test.
  double drilling_factor = 0.1;
};

/// Throws InvalidArgument naming the field and value if a parameter is out of range.
void validate(const ShellMaterial& m);

/// Above this Poisson ratio Model 1's membrane element (ANDES-OPT) would have a higher-order
/// stiffness factor beta0 = (1 - 4 nu^2) / 2 below its floor 0.01 (andes_membrane.cpp).
inline constexpr double kNearlyIncompressible = 0.495;

/// A valid material at the edge of what the models represent, in words naming the field and
/// why; empty when there is nothing to say. Today: poisson_ratio above kNearlyIncompressible.
std::string material_warning(const ShellMaterial& m);

}  // namespace sutura::engine
