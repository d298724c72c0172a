#include "sutura/engine/measure/z_score.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

struct Regression {
  double b0, b1, b2, b3, mse;  // ln(D / cm) = b0 + b1 BSA + b2 BSA^2 + b3 BSA^3; residual variance
};

// Pettersen et al. 2008, in the order of ArchSite (docs/anatomy.md gives the source read).
constexpr std::array<Regression, 3> kPettersen = {{
    {-0.790, 3.020, -2.484, 0.712, 0.023},  // proximal transverse arch
    {-1.072, 2.539, -1.627, 0.368, 0.027},  // aortic isthmus
    {-0.976, 2.469, -1.746, 0.445, 0.026},  // descending aorta beyond the isthmus
}};

const Regression& regression(ArchSite site, double bsa_m2) {
  if (!(bsa_m2 >= kMinBsa && bsa_m2 <= kMaxBsa)) {
    std::ostringstream m;
    m << "body surface area " << bsa_m2 << " m^2 is outside the regressions' range [" << kMinBsa << ", "
      << kMaxBsa << "]";
    throw InvalidArgument(m.str());
  }
  return kPettersen[static_cast<std::size_t>(site)];
}

double mean_log_cm(const Regression& r, double bsa) {
  return r.b0 + bsa * (r.b1 + bsa * (r.b2 + bsa * r.b3));
}

}  // namespace

ArchSite parse_arch_site(const std::string& name) {
  if (name == "transverse_arch") return ArchSite::TransverseArch;
  if (name == "isthmus") return ArchSite::Isthmus;
  if (name == "descending_aorta") return ArchSite::DescendingAorta;
  throw InvalidArgument("unknown arch site '" + name + "' (transverse_arch, isthmus, descending_aorta)");
}

const char* arch_site_name(ArchSite site) {
  switch (site) {
    case ArchSite::TransverseArch: return "transverse_arch";
    case ArchSite::Isthmus: return "isthmus";
    case ArchSite::DescendingAorta: return "descending_aorta";
  }
  return "?";
}

double arch_diameter_at_z(ArchSite site, double bsa_m2, double z) {
  const Regression& r = regression(site, bsa_m2);
  if (!(z >= -5.0 && z <= 5.0)) throw InvalidArgument("z-score " + std::to_string(z) + " is outside [-5, 5]");
  return 10.0 * std::exp(mean_log_cm(r, bsa_m2) + z * std::sqrt(r.mse));
}

double arch_z_score(ArchSite site, double bsa_m2, double diameter_mm) {
  const Regression& r = regression(site, bsa_m2);
  if (!(diameter_mm > 0.0 && std::isfinite(diameter_mm)))
    throw InvalidArgument("a diameter must be > 0 mm, got " + std::to_string(diameter_mm));
  return (std::log(diameter_mm / 10.0) - mean_log_cm(r, bsa_m2)) / std::sqrt(r.mse);
}

}  // namespace sutura::engine
