// The MPM engine against physics nobody here wrote (docs/validation.md, "MPM engine"):
// Hertz's impact of an elastic sphere on a rigid plane, Coulomb sliding, a body at rest on the
// plate. Sizes are chosen for the test suite (a minute or two on two cores).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fem/body.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/solid_mesher.hpp"
#include "mpm/stepper.hpp"

namespace snapjump::mpm {

using hybrid::BodyForces;
using hybrid::particles_of;
namespace {

constexpr double kG = 9.80665;

double mean(const std::vector<double>& v, const Particles& p) {
  double s = 0, m = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    s += p.mass[i] * v[i];
    m += p.mass[i];
  }
  return s / m;
}

// Hertz: a sphere (radius R, mass m) hitting a rigid plane at v0 stays in contact for
// t_c = 2.868 (m^2 / (R E*^2 v0))^(1/5) and peaks at F = (4/3) E* sqrt(R) d^(3/2) with
// d = (15 m v0^2 / (16 E* sqrt(R)))^(2/5), E* = E / (1 - nu^2).
TEST(MpmValidation, ElasticSphereOnFrictionlessPlateFollowsHertz) {
  const double R = 0.010, E = 1.2e6, nu = 0.3, rho = 1160.0, v0 = 1.0;
  const double dx = 0.00035;
  const fem::Body ball(mesh::make_ball_mesh(R, R + 1.6 * dx, 0.003, 0.0007, 0.004),
                       fem::Material::from_young(E, nu, rho));
  const double m = ball.total_mass();
  const double Es = E / (1 - nu * nu);
  const double t_hertz = 2.868 * std::pow(m * m / (R * Es * Es * v0), 0.2);
  const double d = std::pow(15 * m * v0 * v0 / (16 * Es * std::sqrt(R)), 0.4);
  const double F_hertz = 4.0 / 3.0 * Es * std::sqrt(R) * std::pow(d, 1.5);

  BodyForces forces(ball, 0.0);
  auto particles = particles_of(ball);
  for (auto& vz : particles.v.z) vz = -v0;
  Stepper s(std::move(particles), forces, {ball.stable_time_step(0.3), dx, 0.5});
  auto& plate = dynamic_cast<PlateRule&>(s.add_rule(std::make_unique<PlateRule>(0.0)));
  double t_first = -1, t_last = -1, F_peak = 0;
  while (s.time() < 3.0 * t_hertz) {
    s.step();
    if (plate.force() > 0) {
      if (t_first < 0) t_first = s.time() - s.dt();
      t_last = s.time();
      F_peak = std::max(F_peak, plate.force());
    }
  }
  const double duration = t_last - t_first;
  const double v_after = mean(s.particles().v.z, s.particles());
  std::printf(
      "Hertz: contact %.4f ms (theory %.4f ms), peak force %.4f N (theory %.4f N), "
      "rebound %.3f v0, %zu particles, dt %.3g s\n",
      1e3 * duration, 1e3 * t_hertz, F_peak, F_hertz, v_after / v0, s.particles().size(), s.dt());
  EXPECT_NEAR(duration / t_hertz, 1.0, 0.10);
  EXPECT_NEAR(F_peak / F_hertz, 1.0, 0.10);
  // It leaves the plate again: moving up, and the plate no longer pushes.
  EXPECT_GT(v_after, 0.5 * v0);
  EXPECT_LT(t_last, 2.0 * t_hertz);
}

// A block sliding on the plate: Coulomb friction decelerates it at mu g; without friction it
// keeps its speed, and the plate carries its weight.
struct Slide {
  double deceleration = 0.0;  // mean over [t1, t2] [m/s^2]
  double weight_ratio = 0.0;  // mean plate force over [t1, t2] / weight
};

Slide slide(double mu) {
  const double E = 1.2e6, nu = 0.3, rho = 1160.0, a = 0.010, dx = 0.0015, v0 = 0.5;
  const fem::Body block(mesh::make_box_mesh(-a / 2, -a / 2, 0.8 * dx, a, a, a, 0.004),
                        fem::Material::from_young(E, nu, rho));
  BodyForces forces(block, kG);
  auto particles = particles_of(block);
  for (auto& vx : particles.v.x) vx = v0;
  Stepper s(std::move(particles), forces, {block.stable_time_step(0.3), dx, 0.5});
  auto& plate = dynamic_cast<PlateRule&>(s.add_rule(std::make_unique<PlateRule>(mu)));
  const double t1 = 0.01, t2 = 0.06;
  double v1 = 0, impulse = 0, start = 0;
  while (s.time() < t2) {
    s.step();
    if (start == 0 && s.time() >= t1) {
      v1 = mean(s.particles().v.x, s.particles());
      start = s.time();
    } else if (start > 0) {
      impulse += plate.force() * s.dt();
    }
  }
  const double v2 = mean(s.particles().v.x, s.particles());
  Slide out;
  out.deceleration = (v1 - v2) / (s.time() - start);
  out.weight_ratio = impulse / (s.time() - start) / (block.total_mass() * kG);
  return out;
}

TEST(MpmValidation, BlockSlidingWithFrictionDeceleratesAtMuG) {
  const auto r = slide(0.3);
  std::printf(
      "sliding, mu = 0.3: deceleration %.4f m/s^2 (mu g = %.4f), mean plate force %.4f "
      "of the weight\n",
      r.deceleration, 0.3 * kG, r.weight_ratio);
  EXPECT_NEAR(r.deceleration / (0.3 * kG), 1.0, 0.05);
}

// Without friction the block keeps its speed; vertically it rests on the plate, which carries its
// weight (averaged over the block's vibrations, there is no damping).
TEST(MpmValidation, FrictionlessBlockKeepsItsSpeedAndRestsOnThePlate) {
  const auto r = slide(0.0);
  std::printf(
      "sliding, mu = 0: deceleration %.2e m/s^2; at rest on the plate: mean plate force "
      "%.5f of the weight\n",
      r.deceleration, r.weight_ratio);
  EXPECT_LT(std::abs(r.deceleration), 0.01 * 0.3 * kG);
  EXPECT_NEAR(r.weight_ratio, 1.0, 0.01);
}

}  // namespace
}  // namespace snapjump::mpm
