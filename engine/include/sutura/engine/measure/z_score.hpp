#pragma once
// Echocardiographic z-scores of the aortic arch's diameters for a child's body surface area:
// the regressions of Pettersen et al. (J Am Soc Echocardiogr 2008;21:922-934), healthy
// infants, children and adolescents, ln(D / cm) = b0 + b1 BSA + b2 BSA^2 + b3 BSA^3 with a
// residual variance (MSE), so that z = (ln(D / cm) - mean) / sqrt(MSE). The coefficients and
// where they were read are in docs/anatomy.md.
#include <string>

namespace sutura::engine {

/// A site of the arch with a regression, named in sessions as "transverse_arch", "isthmus"
/// and "descending_aorta" (Pettersen's proximal transverse arch, aortic isthmus, and
/// descending aorta just beyond the isthmus).
enum class ArchSite { TransverseArch, Isthmus, DescendingAorta };

/// Throws InvalidArgument naming the allowed names for any other name. O(1).
ArchSite parse_arch_site(const std::string& name);
/// The session name of `site`. O(1).
const char* arch_site_name(ArchSite site);

/// The body surface areas the regressions are used for, m^2 (their cohort's range, as the
/// implementations read give it).
inline constexpr double kMinBsa = 0.1, kMaxBsa = 2.0;

/// The diameter (mm) at z-score `z` of `site` for body surface area `bsa_m2`. Throws
/// InvalidArgument for a BSA outside [kMinBsa, kMaxBsa] or a z outside [-5, 5]. O(1).
double arch_diameter_at_z(ArchSite site, double bsa_m2, double z);

/// The z-score of diameter `diameter_mm` (> 0) of `site` for `bsa_m2`. Throws as above. O(1).
double arch_z_score(ArchSite site, double bsa_m2, double diameter_mm);

}  // namespace sutura::engine
