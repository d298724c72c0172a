// The arch's z-score regressions (engine/measure/z_score.hpp) against their closed form, the
// coefficients of Pettersen et al. 2008 written out here once more (docs/anatomy.md).
#include <gtest/gtest.h>

#include <cmath>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/measure/z_score.hpp"

namespace sutura::engine {
namespace {

// ln(D / cm) at z = 0 for the isthmus, BSA 0.3 m^2, by hand:
// -1.072 + 2.539 (0.3) - 1.627 (0.09) + 0.368 (0.027) = -0.446794.
TEST(ZScore, TheIsthmusRegressionHasItsClosedForm) {
  EXPECT_NEAR(arch_diameter_at_z(ArchSite::Isthmus, 0.3, 0.0), 10.0 * std::exp(-0.446794), 1e-12);
  // One residual standard deviation is sqrt(0.027) in ln(D).
  EXPECT_NEAR(arch_diameter_at_z(ArchSite::Isthmus, 0.3, -2.0),
              10.0 * std::exp(-0.446794 - 2.0 * std::sqrt(0.027)), 1e-12);
  // The transverse arch and the descending aorta, BSA 0.2 m^2.
  EXPECT_NEAR(arch_diameter_at_z(ArchSite::TransverseArch, 0.2, 0.0),
              10.0 * std::exp(-0.79 + 3.02 * 0.2 - 2.484 * 0.04 + 0.712 * 0.008), 1e-12);
  EXPECT_NEAR(arch_diameter_at_z(ArchSite::DescendingAorta, 0.2, 1.0),
              10.0 * std::exp(-0.976 + 2.469 * 0.2 - 1.746 * 0.04 + 0.445 * 0.008 + std::sqrt(0.026)), 1e-12);
}

TEST(ZScore, ScoreAndDiameterAreInverses) {
  for (const ArchSite site : {ArchSite::TransverseArch, ArchSite::Isthmus, ArchSite::DescendingAorta})
    for (const double bsa : {0.1, 0.25, 1.0, 2.0})
      for (const double z : {-3.0, -2.0, 0.0, 1.5}) {
        const double d = arch_diameter_at_z(site, bsa, z);
        EXPECT_NEAR(arch_z_score(site, bsa, d), z, 1e-12) << arch_site_name(site) << " " << bsa;
      }
  // A neonate's (BSA 0.2 m^2) normal isthmus is a few millimetres, growing with the child.
  const double neonate = arch_diameter_at_z(ArchSite::Isthmus, 0.2, 0.0);
  EXPECT_GT(neonate, 4.0);
  EXPECT_LT(neonate, 7.0);
  EXPECT_LT(neonate, arch_diameter_at_z(ArchSite::Isthmus, 1.0, 0.0));
}

TEST(ZScore, NamesAndRangesAreChecked) {
  EXPECT_EQ(parse_arch_site("isthmus"), ArchSite::Isthmus);
  EXPECT_EQ(parse_arch_site(arch_site_name(ArchSite::TransverseArch)), ArchSite::TransverseArch);
  EXPECT_EQ(parse_arch_site(arch_site_name(ArchSite::DescendingAorta)), ArchSite::DescendingAorta);
  EXPECT_THROW(parse_arch_site("Isthmus"), InvalidArgument);
  EXPECT_THROW(arch_diameter_at_z(ArchSite::Isthmus, 0.05, 0.0), InvalidArgument);
  EXPECT_THROW(arch_diameter_at_z(ArchSite::Isthmus, 2.5, 0.0), InvalidArgument);
  EXPECT_THROW(arch_diameter_at_z(ArchSite::Isthmus, std::nan(""), 0.0), InvalidArgument);
  EXPECT_THROW(arch_diameter_at_z(ArchSite::Isthmus, 0.2, -6.0), InvalidArgument);
  EXPECT_THROW(arch_z_score(ArchSite::Isthmus, 0.2, 0.0), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
