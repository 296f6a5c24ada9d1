#include <gtest/gtest.h>

#include <cmath>

#include "axi/plate.hpp"

namespace snapjump::axi {
namespace {

// A node of mass m that would end its step below the plate lands on it: it ends the step at
// z = 0, the impulse that stopped it is m times the change of its normal velocity, and the force
// is that impulse over the step. Coulomb's law on the radial momentum: a node whose momentum is
// below mu times the normal impulse sticks, one above it loses exactly mu jn and keeps its
// direction. A node that stays above the plate is left alone.
TEST(AxiPlateRule, ALandingNodeEndsOnThePlateAndFrictionFollowsCoulomb) {
  const double dt = 1e-6, m = 2e-4, mu = 0.5;
  PlateRule plate(3, mu);
  plate.begin_step();

  // Node 0: at z = 1 um, falling at 3 m/s; lands (the step would carry it 3 um down). Its radial
  // momentum m 0.1 is below mu jn = 0.5 m (3 - 1): it sticks.
  double vr0 = 0.1, vz0 = -3.0;
  plate.apply(0, m, 1e-6, vr0, vz0, dt);
  const double jn0 = m * (-1e-6 / dt + 3.0);
  EXPECT_DOUBLE_EQ(1e-6 + dt * vz0, 0.0);
  EXPECT_EQ(vr0, 0.0);

  // Node 1: on the plate, falling at 1 m/s and sliding at 5 m/s: jn = m, friction takes mu m.
  double vr1 = -5.0, vz1 = -1.0;
  plate.apply(1, m, 0.0, vr1, vz1, dt);
  const double jn1 = m * 1.0;
  EXPECT_EQ(vz1, 0.0);
  EXPECT_DOUBLE_EQ(vr1, -5.0 + mu * jn1 / m);

  // Node 2: 1 mm up, falling at 1 m/s: the step does not reach the plate.
  double vr2 = 1.0, vz2 = -1.0;
  plate.apply(2, m, 1e-3, vr2, vz2, dt);
  EXPECT_EQ(vr2, 1.0);
  EXPECT_EQ(vz2, -1.0);

  plate.end_step(dt);
  EXPECT_TRUE(plate.loaded(0));
  EXPECT_TRUE(plate.loaded(1));
  EXPECT_FALSE(plate.loaded(2));
  EXPECT_DOUBLE_EQ(plate.force(), (jn0 + jn1) / dt);

  // A new step forgets the last one's nodes; its force is its own.
  plate.begin_step();
  plate.end_step(dt);
  EXPECT_FALSE(plate.loaded(0));
  EXPECT_EQ(plate.force(), 0.0);
}

}  // namespace
}  // namespace snapjump::axi
