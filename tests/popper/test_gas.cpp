#include <gtest/gtest.h>

#include <cmath>

#include "popper/gas.hpp"

namespace snapjump::popper {
namespace {

// At a fixed gas volume, u = delta_p / p0 obeys u'' = -alpha_n p0 u with u(0) = dp0 / p0 and
// u'(0) = -beta_n dp0, so delta_p(t) = dp0 (cos(w t) - (beta_n p0 / w) sin(w t)), w^2 = alpha_n p0.
TEST(Gas, ValveLawAtFixedVolumeIsAnOscillator) {
  const double p0 = 101325.0, alpha = 1.0e-3, beta = 5.0e-5, dp0 = 3000.0, V = 2e-4;
  Gas gas(p0, alpha, beta);
  gas.hold(dp0);
  EXPECT_DOUBLE_EQ(gas.delta_p(), dp0);
  gas.open_valve(V);
  const double dt = 1e-6, w = std::sqrt(alpha * p0);
  double t = 0.0;
  for (int k = 0; k < 200000; ++k) {
    gas.advance(dt, V);
    t += dt;
    if (k % 20000 == 19999) {
      const double exact = dp0 * (std::cos(w * t) - beta * p0 / w * std::sin(w * t));
      EXPECT_NEAR(gas.delta_p(), exact, 2e-3 * dp0) << "t = " << t;
    }
  }
}

// Isothermal: with the valve closed, squeezing the gas raises the inside pressure as 1/V.
TEST(Gas, ClosedValveHoldsThePressure) {
  Gas gas(101325.0, 1e-3, 5e-5);
  gas.hold(2000.0);
  gas.advance(1e-3, 1e-4);
  EXPECT_DOUBLE_EQ(gas.delta_p(), 2000.0);
  EXPECT_FALSE(gas.valve_open());
}

TEST(Gas, BoylesLawAtTheRelease) {
  // Right after the valve opens (no time for air to flow), halving the volume doubles the
  // inside pressure: p_in = (p0 - dp0) V_ref / V.
  const double p0 = 101325.0, dp0 = 3000.0;
  Gas gas(p0, 1e-3, 5e-5);
  gas.hold(dp0);
  gas.open_valve(2e-4);
  gas.advance(0.0, 1e-4);
  EXPECT_NEAR(p0 - gas.delta_p(), 2.0 * (p0 - dp0), 1e-9);
}

}  // namespace
}  // namespace snapjump::popper
