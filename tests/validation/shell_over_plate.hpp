// The default popper's shell hanging apex-down from its clamped rim a little above the rigid
// plate, by default at the default preset's mesh (sqrt(hR)/2 elements, one quadratic element
// through h) and cells of 0.025 R (a fixed fraction of R, not the presets' h/4; the
// constructor takes another). The rim is a rigid body of huge mass: it moves at whatever speed
// the test sets, whatever the shell does. Shared by the shell-on-plate validations.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "fem/body.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/cap_mesher.hpp"
#include "mpm/rules.hpp"
#include "mpm/stepper.hpp"

namespace snapjump::testing {

struct ShellOverPlate {
  static constexpr double R = 0.030, h = 0.002, E = 1.2e6, nu = 0.45, rho = 1160.0;
  static constexpr double kDefaultDx = 0.025 * R;

  // mu: friction; cell: the grid spacing [m]; element_size: the mesh's [m].
  explicit ShellOverPlate(double mu, double cell = kDefaultDx,
                          double element_size = std::sqrt(h * R) / 2)
      : dx(cell), gap(2.0 * cell) {
    auto m = mesh::make_cap_mesh({.R = R,
                                  .h = h,
                                  .phi = 80.0 * std::numbers::pi / 180,
                                  .element_size = element_size,
                                  .layers = 1});
    const auto lowest = std::min_element(m.nodes.z.begin(), m.nodes.z.end());
    apex = static_cast<std::size_t>(lowest - m.nodes.z.begin());
    mesh::translate_z(m, gap - *lowest);
    shell = std::make_unique<fem::Body>(m, fem::Material::from_young(E, nu, rho));
    forces = std::make_unique<hybrid::BodyForces>(*shell, 0.0);
    // Light damping keeps the contact's ringing down; the rim moves slowly against the shell's
    // waves (centimetres per second against about 30 m/s), so the states are quasi-static.
    stepper = std::make_unique<mpm::Stepper>(
        hybrid::particles_of(*shell), *forces,
        mpm::StepperOptions{shell->stable_time_step(0.4), dx, 0.5, 0.05 * std::sqrt(E / rho) / R});
    rim.mass = 1e9;
    stepper->add_rule(std::make_unique<mpm::ClampRule>(rim));
    plate = &dynamic_cast<mpm::PlateRule&>(stepper->add_rule(std::make_unique<mpm::PlateRule>(mu)));
    stepper->add_rigid_body(rim);
  }
  ShellOverPlate(const ShellOverPlate&) = delete;  // the stepper holds the rim's address
  ShellOverPlate& operator=(const ShellOverPlate&) = delete;

  // Steps until the clock reaches t_end, calling each_step() after every step; returns the mean
  // plate force over those steps [N].
  template <typename EachStep>
  double mean_force_until(double t_end, EachStep&& each_step) {
    double sum = 0.0;
    int n = 0;
    while (stepper->time() < t_end) {
      stepper->step();
      sum += plate->force();
      ++n;
      each_step();
    }
    return n > 0 ? sum / n : 0.0;
  }

  // Height of the shell's outer apex above the plate [m].
  [[nodiscard]] double apex_height() const { return stepper->particles().x.z[apex]; }

  double dx;   // grid spacing [m]
  double gap;  // apex height above the plate at the start [m]
  std::unique_ptr<fem::Body> shell;
  std::unique_ptr<hybrid::BodyForces> forces;
  std::unique_ptr<mpm::Stepper> stepper;
  mpm::RigidBody rim;
  mpm::PlateRule* plate = nullptr;
  std::size_t apex = 0;  // particle at the outer apex
};

}  // namespace snapjump::testing
