// The MPM step as a whole: free fall, the time step's bounds, a runaway particle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include "fem/body.hpp"
#include "mesh/cap_mesher.hpp"
#include "mesh/solid_mesher.hpp"
#include "mpm/grid.hpp"
#include "mpm/mpm_test_support.hpp"
#include "mpm/stepper.hpp"

namespace snapjump::mpm {

namespace {

using namespace testing;  // mpm_test_support.hpp

TEST(FreeFall, ClampedShellAndContainerFallAtG) {
  const double g = 9.80665;
  const fem::Body shell(mesh::make_cap_mesh({.R = 0.030,
                                             .h = 0.002,
                                             .phi = 80.0 * std::numbers::pi / 180,
                                             .element_size = 0.006,
                                             .layers = 1}),
                        fem::Material::from_young(1.2e6, 0.45, 1160.0));
  BodyForces forces(shell, g);
  const double dt = shell.stable_time_step(0.3);
  Stepper s(particles_of(shell), forces, {dt, 0.003, 0.5});
  RigidBody container;
  container.mass = 0.05;
  container.applied_force = -container.mass * g;
  s.add_rule(std::make_unique<ClampRule>(container));
  s.add_rigid_body(container);
  const int apex = shell.mesh().apex;
  const double z0 = s.particles().x.z[apex];
  while (s.time() < 0.02) s.step();
  const double t = s.time();
  const double exact = -0.5 * g * t * t;
  EXPECT_NEAR(container.z / exact, 1.0, 1e-3) << "t = " << t;
  EXPECT_NEAR((s.particles().x.z[apex] - z0) / exact, 1.0, 1e-3);
  EXPECT_NEAR(container.vz / (-g * t), 1.0, 1e-3);
}

// A free body (no clamp, no plate) falls at g: z(t) = -g t^2 / 2 within 0.1 %.
TEST(FreeFall, BallFallsAtG) {
  const double g = 9.80665;
  const fem::Body ball(mesh::make_ball_mesh(0.01, 0.05, 0.005),
                       fem::Material::from_young(1.2e6, 0.3, 1160.0));
  BodyForces forces(ball, g);
  Stepper s(particles_of(ball), forces, {ball.stable_time_step(0.3), 0.002, 0.5});
  const auto z0 = s.particles().x.z;
  while (s.time() < 0.03) s.step();
  double dz = 0.0, m = 0.0;
  for (std::size_t i = 0; i < z0.size(); ++i) {
    dz += s.particles().mass[i] * (s.particles().x.z[i] - z0[i]);
    m += s.particles().mass[i];
  }
  const double t = s.time();
  EXPECT_NEAR(dz / m / (-0.5 * g * t * t), 1.0, 1e-3) << "t = " << t;
}

TEST(Stepper, TimeStepIsTheSmallerBound) {
  const auto a = choose_time_step(1e-6, 0.001, 10.0, 0.5);  // grid bound 5e-5 s
  EXPECT_DOUBLE_EQ(a.dt, 1e-6);
  EXPECT_STREQ(a.limiting, "elastic");
  const auto b = choose_time_step(1e-4, 0.001, 10.0, 0.5);
  EXPECT_DOUBLE_EQ(b.dt, 5e-5);
  EXPECT_STREQ(b.limiting, "grid CFL");
}

TEST(Stepper, RunawayParticleStopsTheRunWithWhenAndWhere) {
  NoForces none;
  auto p = random_particles(10, 3);
  p.v.x[4] = 1e4;  // far beyond the grid CFL
  for (auto& c : p.C) c = 0.0;
  Stepper s(std::move(p), none, {1e-5, 0.002, 0.5});
  try {
    s.step();
    FAIL() << "expected a StepError";
  } catch (const StepError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("t = 1e-05 s"), std::string::npos) << msg;
    EXPECT_NE(msg.find("grid cells per step"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace snapjump::mpm
