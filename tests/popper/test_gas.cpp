#include <gtest/gtest.h>

#include <cmath>

#include "popper/gas.hpp"

namespace snapjump::popper {
namespace {

// At a fixed gas volume V with the reference volume V0 (the undeformed popper), J_V = V / V0 and
// delta_p = p0 (1 - J_n / J_V) obeys delta_p'' = -(p0 / J_V) alpha_n delta_p, with delta_p(0) =
// dp0 and delta_p'(0) = -(p0 / J_V) beta_n dp0. So delta_p(t) = dp0 (cos(w t) - (beta_n p0 /
// (J_V w)) sin(w t)), w^2 = alpha_n p0 / J_V: the reference volume sets the pace of the inflow.
void expect_oscillator(double V, double V0) {
  const double p0 = 101325.0, alpha = 1.0e-3, beta = 5.0e-5, dp0 = 3000.0;
  Gas gas(p0, alpha, beta, V0);
  gas.hold(dp0);
  EXPECT_DOUBLE_EQ(gas.delta_p(), dp0);
  gas.open_valve(V);
  const double JV = V / V0, dt = 1e-6, w = std::sqrt(alpha * p0 / JV);
  double t = 0.0;
  for (int k = 0; k < 200000; ++k) {
    gas.advance(dt, V);
    t += dt;
    if (k % 20000 == 19999) {
      const double exact = dp0 * (std::cos(w * t) - beta * p0 / (JV * w) * std::sin(w * t));
      EXPECT_NEAR(gas.delta_p(), exact, 2e-3 * dp0) << "t = " << t << ", V / V0 = " << JV;
    }
  }
}

TEST(Gas, ValveLawAtFixedVolumeIsAnOscillator) { expect_oscillator(2e-4, 2e-4); }

// The default popper: 200 mL container, the inverted shell takes about 38 mL from it and the
// undeformed one adds as much, so V_release / V0 is about 0.68 and the pressure recovers about
// 1.5 times faster than with the release as the reference.
TEST(Gas, ReferenceIsTheUndeformedPopper) {
  expect_oscillator(1.62e-4, 2.38e-4);
  // At the release the air inside is what the held pressure leaves in the release volume:
  // J_n = J_V (1 - dp0 / p0), not 1.
  const double p0 = 101325.0, dp0 = 3000.0, V = 1.62e-4, V0 = 2.38e-4;
  Gas gas(p0, 1e-3, 5e-5, V0);
  gas.hold(dp0);
  gas.open_valve(V);
  EXPECT_DOUBLE_EQ(gas.J_n(), V / V0 * (1.0 - dp0 / p0));
  EXPECT_DOUBLE_EQ(gas.J_n_rate(), 5e-5 * dp0);
  gas.advance(0.0, V);
  EXPECT_NEAR(gas.delta_p(), dp0, 1e-9);  // no flow in no time: still dp0
}

// With the valve closed the syringe holds the pressure difference, whatever the volume.
TEST(Gas, ClosedValveHoldsThePressure) {
  Gas gas(101325.0, 1e-3, 5e-5, 2e-4);
  gas.hold(2000.0);
  gas.advance(1e-3, 1e-4);
  EXPECT_DOUBLE_EQ(gas.delta_p(), 2000.0);
  EXPECT_FALSE(gas.valve_open());
}

TEST(Gas, BoylesLawAtTheRelease) {
  // Right after the valve opens (no time for air to flow), halving the volume doubles the
  // inside pressure: p_in = (p0 - dp0) V_release / V.
  const double p0 = 101325.0, dp0 = 3000.0;
  Gas gas(p0, 1e-3, 5e-5, 3e-4);
  gas.hold(dp0);
  gas.open_valve(2e-4);
  gas.advance(0.0, 1e-4);
  EXPECT_NEAR(p0 - gas.delta_p(), 2.0 * (p0 - dp0), 1e-9);
}

TEST(Gas, ReferenceVolumeMustBePositive) {
  EXPECT_THROW(Gas(101325.0, 1e-3, 5e-5, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace snapjump::popper
