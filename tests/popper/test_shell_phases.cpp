#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "config/case.hpp"
#include "core/rigid_body.hpp"
#include "popper/mpm_shell.hpp"
#include "popper/popper.hpp"

namespace snapjump::popper {
namespace {

// Calls `f` and expects the std::logic_error that names `method`.
void expect_refused(const std::function<void()>& f, const std::string& method) {
  try {
    f();
    ADD_FAILURE() << method << " was not refused";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("MpmShell::" + method), std::string::npos) << e.what();
  }
}

// What only the 3D shell on the plate has (its stepper, the plate's force and contact, the
// checkpoint's state, the snapshot, the clock and velocities the release resets, the weight's
// potential energy) is refused with a logic_error naming the method before start_on_plate, in
// the held phase as before any phase; what every phase has answers in each.
TEST(MpmShellPhases, ThePlatesQuantitiesAreRefusedUntilTheShellIsOnThePlate) {
  auto c = config::default_case();
  c.numerics.resolution = config::Resolution::Coarse;
  MpmShell shell(c, resolve_numerics(c), [] { return 0.0; });
  const auto refused_off_the_plate = [&] {
    std::ostringstream out;
    expect_refused([&] { (void)shell.stepper(); }, "stepper");
    expect_refused([&] { (void)shell.plate_force(); }, "plate_force");
    expect_refused([&] { (void)shell.contact(); }, "contact");
    expect_refused([&] { shell.save_state(out); }, "save_state");
    expect_refused([&] { shell.report().write_snapshot("never.vtu", 0.0); }, "write_snapshot");
    expect_refused([&] { shell.reset_time(); }, "reset_time");
    expect_refused([&] { shell.zero_velocities(); }, "zero_velocities");
    expect_refused([&] { shell.set_damping(1.0); }, "set_damping");
    expect_refused([&] { (void)shell.potential_energy(9.81); }, "potential_energy");
  };

  // Built: at rest in the reference state at t = 0, and no step without a phase.
  EXPECT_EQ(shell.time(), 0.0);
  EXPECT_EQ(shell.steps(), 0);
  EXPECT_EQ(shell.kinetic_energy(), 0.0);
  EXPECT_EQ(shell.dt(), shell.time_step());
  EXPECT_NEAR(shell.cavity_volume(), shell.undeformed_cavity_volume(), 0.0);
  EXPECT_THROW(shell.step(), std::logic_error);
  refused_off_the_plate();

  // Held: the finite elements step alone.
  shell.start_held(0.0);
  shell.step();
  EXPECT_EQ(shell.steps(), 1);
  EXPECT_GT(shell.time(), 0.0);
  refused_off_the_plate();

  // On the plate everything answers.
  core::RigidBody container{.mass = 0.1};
  shell.start_on_plate(container, 0.5, 0.0);
  shell.step();
  EXPECT_TRUE(std::isfinite(shell.plate_force()));
  EXPECT_TRUE(std::isfinite(shell.potential_energy(9.81)));
  (void)shell.contact();
  std::ostringstream out;
  shell.save_state(out);
  EXPECT_FALSE(out.str().empty());
  shell.set_damping(2.0);
  shell.zero_velocities();
  EXPECT_EQ(shell.kinetic_energy(), 0.0);
  shell.reset_time();
  EXPECT_EQ(shell.time(), 0.0);
  EXPECT_EQ(&shell.stepper(), &shell.stepper());
}

}  // namespace
}  // namespace snapjump::popper
