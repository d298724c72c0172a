// Validation of ShellMaterial parameters (see material.hpp).
#include <cmath>
#include <sstream>
#include <string>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/shell/material.hpp"

namespace sutura::engine {
namespace {

[[noreturn]] void fail(const char* field, double value, const char* requirement) {
  std::ostringstream os;
  os.precision(17);
  os << "ShellMaterial." << field << " = " << value << " is invalid: must be " << requirement;
  throw InvalidArgument(os.str());
}

}  // namespace

void validate(const ShellMaterial& m) {
  // The negated comparisons also reject NaN.
  if (!(m.youngs_modulus > 0.0) || !std::isfinite(m.youngs_modulus))
    fail("youngs_modulus", m.youngs_modulus, "finite and > 0 (MPa)");
  if (!(m.poisson_ratio >= 0.0 && m.poisson_ratio < 0.5))
    fail("poisson_ratio", m.poisson_ratio, "in [0, 0.5)");
  if (!(m.thickness > 0.0) || !std::isfinite(m.thickness))
    fail("thickness", m.thickness, "finite and > 0 (mm)");
  if (!(m.density > 0.0) || !std::isfinite(m.density))
    fail("density", m.density, "finite and > 0 (t/mm^3)");
  if (!(m.drilling_factor > 0.0) || !std::isfinite(m.drilling_factor))
    fail("drilling_factor", m.drilling_factor, "finite and > 0");
}

std::string material_warning(const ShellMaterial& m) {
  if (!(m.poisson_ratio > kNearlyIncompressible)) return {};
  std::ostringstream os;
  os.precision(17);
  os << "poisson_ratio " << m.poisson_ratio << " is above " << kNearlyIncompressible
     << ", nearly incompressible: the membrane element's higher-order stiffness (ANDES-OPT beta0 = "
        "(1 - 4 nu^2) / 2) is held at its floor 0.01 there, and no model thins the wall as it "
        "stretches; the results approximate such a wall less well than at 0.45-0.49";
  return os.str();
}

}  // namespace sutura::engine
