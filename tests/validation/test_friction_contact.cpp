// Friction between a body and the plate, isolated: an elastic block on a tilted plate (gravity
// turned by alpha instead of the plate). Coulomb's law: below the friction angle, tan(alpha) <
// mu, static friction holds the block; above it the block slides at g (sin(alpha) -
// mu cos(alpha)); without friction it slides at g sin(alpha). The block-sliding validation
// (test_mpm_validation.cpp) checks kinetic friction at a given speed; this one checks that the
// grid's friction holds what it should hold and starts a slide where it should. It fails if
// friction has no effect (the frictionless block drifts 1.07 mm in 30 ms; held, it may drift
// 1 % of that). The particles resting on the plate take about a third of their velocity from the
// node layer z = dx, which the plate rule leaves alone; for a body in static equilibrium that
// layer carries no momentum, and the block is held (it drifts 1.3 um, its elastic settling).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "fem/body.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/solid_mesher.hpp"
#include "mpm/rules.hpp"
#include "mpm/stepper.hpp"

namespace snapjump {
namespace {

constexpr double kG = 9.80665;

// Internal forces and gravity turned by alpha about y: the plate's frame of a plate tilted by
// alpha, down the slope along +x.
class TiltedGravity final : public mpm::ForceProvider {
 public:
  TiltedGravity(const fem::Body& body, double alpha) : body_(body), alpha_(alpha) {}
  void forces(const mesh::Points& x, double, mesh::Points& f) override {
    body_.internal_forces(x, f);
    const auto& m = body_.mass();
    for (std::size_t a = 0; a < m.size(); ++a) {
      f.x[a] += m[a] * kG * std::sin(alpha_);
      f.z[a] -= m[a] * kG * std::cos(alpha_);
    }
  }

 private:
  const fem::Body& body_;
  double alpha_;
};

struct Incline {
  double drift = 0.0;         // mean x displacement of the block at t_end [m]
  double acceleration = 0.0;  // mean x acceleration over [t_end / 3, t_end] [m/s^2]
};

// A 10 mm silicone cube (E = 1.2 MPa, nu = 0.3) released at rest at its resting height on the
// plate (a quarter cell above z = 0, docs/validation.md), grid cells of 1.5 mm, no damping.
Incline block_on_incline(double mu, double tan_alpha, double t_end) {
  const double E = 1.2e6, nu = 0.3, rho = 1160.0, a = 0.010, dx = 0.0015;
  const fem::Body block(mesh::make_box_mesh(-a / 2, -a / 2, 0.25 * dx, a, a, a, 0.004),
                        fem::Material::from_young(E, nu, rho));
  TiltedGravity forces(block, std::atan(tan_alpha));
  mpm::Stepper s(hybrid::particles_of(block), forces, {block.stable_time_step(0.3), dx, 0.5});
  s.add_rule(std::make_unique<mpm::PlateRule>(mu));
  const auto x0 = s.particles().x;
  const auto mean = [&](const std::vector<double>& v) {
    const auto& p = s.particles();
    double sum = 0.0, m = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      sum += p.mass[i] * v[i];
      m += p.mass[i];
    }
    return sum / m;
  };
  const double t1 = t_end / 3.0;
  double v1 = 0.0, start = -1.0;
  while (s.time() < t_end) {
    s.step();
    if (start < 0.0 && s.time() >= t1) {
      v1 = mean(s.particles().v.x);
      start = s.time();
    }
  }
  Incline out;
  out.drift = mean(s.particles().x.x) - mean(x0.x);
  out.acceleration = (mean(s.particles().v.x) - v1) / (s.time() - start);
  std::printf("  tan(alpha) = %.2f, mu = %.2f: drift %.5f mm in %.0f ms, acceleration %.4f m/s^2\n",
              tan_alpha, mu, 1e3 * out.drift, 1e3 * t_end, out.acceleration);
  return out;
}

TEST(FrictionContact, BlockOnAnInclineSticksBelowTheFrictionAngleAndSlidesAbove) {
  const double t_end = 0.03, mu = 0.5;
  const auto free = block_on_incline(0.0, 0.25, t_end);
  const auto held = block_on_incline(mu, 0.25, t_end);
  const auto sliding = block_on_incline(mu, 0.75, t_end);
  const auto slope = [](double tan_alpha, double m) {
    const double alpha = std::atan(tan_alpha);
    return kG * (std::sin(alpha) - m * std::cos(alpha));
  };
  std::printf("  theory: %.4f m/s^2 without friction, 0 held, %.4f m/s^2 sliding with friction\n",
              slope(0.25, 0.0), slope(0.75, mu));
  // Without friction: g sin(alpha).
  EXPECT_NEAR(free.acceleration / slope(0.25, 0.0), 1.0, 0.02);
  // Below the friction angle the block stays where it was put: it moves less than 1 % of the
  // frictionless drift (its elastic settling moves it about a micrometre).
  EXPECT_LT(std::abs(held.drift), 0.01 * free.drift);
  // Above it, the block slides at g (sin(alpha) - mu cos(alpha)).
  EXPECT_NEAR(sliding.acceleration / slope(0.75, mu), 1.0, 0.05);
}

}  // namespace
}  // namespace snapjump
