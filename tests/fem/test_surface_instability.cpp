// Biot's surface instability of a compressed half-space against its published value.
#include <gtest/gtest.h>

#include "fem/surface_instability.hpp"

namespace snapjump::fem {
namespace {

TEST(SurfaceInstability, TheNearlyIncompressibleNeoHookeanSurfaceWrinklesAtBiotsStretch) {
  // Biot (1963): an incompressible neo-Hookean half-space in plane strain becomes unstable at a
  // stretch of 0.5437 along its surface, 1 / 0.5437^2 = 3.383 times its normal stretch.
  const auto m = Material::from_young(1.2e6, 0.4999, 1160.0);
  const auto s = biot_instability(m);
  EXPECT_NEAR(s.tangential, 0.5437, 1e-3);
  EXPECT_NEAR(s.ratio, 3.383, 0.2e-2 * 3.383);
  // and whatever the third stretch (the incompressible neo-Hookean solid's instability depends on
  // the ratio in its plane alone).
  for (const double third : {0.9, 1.1}) {
    EXPECT_NEAR(biot_instability(m, third).ratio, 3.383, 0.2e-2 * 3.383) << third;
  }
}

TEST(SurfaceInstability, TheFreeSurfacesNormalStressVanishes) {
  const auto m = Material::from_young(1.2e6, 0.45, 1160.0);
  const double l2 = free_normal_stretch(m, 0.7, 0.95);
  const double F[9] = {0.7, 0, 0, 0, l2, 0, 0, 0, 0.95};
  double P[9];
  ASSERT_TRUE(first_piola_stress(m, F, P));
  EXPECT_NEAR(P[4], 0.0, 1e-12 * m.mu);
  EXPECT_GT(l2, 1.0);  // compressed along the surface, it thickens
}

TEST(SurfaceInstability, ACompressibleSolidWrinklesEarlierAndGentTendsToNeoHookean) {
  const double incompressible = biot_instability(Material::from_young(1.2e6, 0.4999, 1160.0)).ratio;
  const auto m = Material::from_young(1.2e6, 0.45, 1160.0);
  const auto s = biot_instability(m);
  EXPECT_LT(s.ratio, incompressible);
  EXPECT_GT(s.ratio, 2.0);
  EXPECT_NEAR(biot_instability(m.with_gent(1e7)).ratio, s.ratio, 1e-4 * s.ratio);
  // A stiffening law holds its surface smooth to a larger ratio.
  EXPECT_GT(biot_instability(m.with_gent(20.0)).ratio, s.ratio);
}

}  // namespace
}  // namespace snapjump::fem
