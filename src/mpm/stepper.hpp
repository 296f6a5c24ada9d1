// The hybrid step of the paper's "Contact analysis by MPM": particle forces from a force provider
// -> particle velocities -> particle to grid (APIC, quadratic B-splines) -> grid rules -> grid to
// particle -> advection, then the rigid bodies. The engine knows nothing about tetrahedra: the
// forces come from any ForceProvider.
//
// The transfers here are optimised (blocks, colours, separable stencils, Morton order, AVX2);
// their readable specification, one particle and one node at a time with the paper's equation
// numbers, is mpm/reference_transfer.hpp, and tests/mpm/test_transfers.cpp holds the two to each
// other.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/points.hpp"
#include "mpm/grid.hpp"
#include "mpm/rules.hpp"
#include "parallel/threads.hpp"

namespace snapjump::mpm {

// Material points: structure of arrays.
struct Particles {
  core::Points x, v;
  std::vector<double> mass;
  std::vector<double> C;  // affine velocity, 9 per particle, row-major
  std::vector<std::uint8_t> tags;
  [[nodiscard]] std::size_t size() const { return mass.size(); }
  // Particles at `positions` with `masses`, at rest.
  static Particles at_rest(const core::Points& positions, const std::vector<double>& masses);
};

// Forces on the particles at positions x and time t (overwrites f).
class ForceProvider {
 public:
  virtual ~ForceProvider() = default;
  virtual void forces(const core::Points& x, double t, core::Points& f) = 0;
};

// The run cannot go on: a non-finite value, a particle faster than the grid allows, an inverted
// element. The message says when and where.
class StepError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StepperOptions {
  double dt = 0.0;  // time step [s]
  double dx = 0.0;  // grid spacing [m]
  // A particle may move at most this fraction of dx in one step (grid CFL); beyond it the step
  // stops with a StepError.
  double max_cfl = 0.5;
  // Mass-proportional damping c [1/s] (m a = f - c m v), for quasi-static phases only; 0 for
  // physical runs.
  double damping = 0.0;
  // Let step() choose between one thread and the most allowed by timing both now and then
  // (parallel::ThreadTuner); false: always the most allowed. The results are the same either way.
  bool tune_threads = true;
  // The transfers' AVX2 version where the processor has one (x86-64); false: the baseline
  // version everywhere. The results are the same either way (a test compares them).
  bool wide_vectors = true;
};

// The time step: the smaller of the elastic bound (cfl_elastic * smallest node spacing / p-wave
// speed) and the grid bound (cfl_grid * dx / the fastest speed expected).
struct TimeStep {
  double dt = 0.0;
  double elastic = 0.0;  // elastic bound [s]
  double grid = 0.0;     // grid CFL bound [s]
  const char* limiting = "elastic";
};
TimeStep choose_time_step(double elastic_bound, double dx, double expected_speed, double cfl_grid);

class Stepper {
 public:
  Stepper(Particles particles, ForceProvider& forces, StepperOptions options);

  // Rules run in the order added. The stepper keeps them alive.
  GridRule& add_rule(std::unique_ptr<GridRule> rule);
  // Rigid bodies advanced after each step (their clamp forces come from the rules).
  void add_rigid_body(RigidBody& body) { bodies_.push_back(&body); }

  void step();

  // The stages of step(), in order (public for tests and probes).
  void update_particle_velocities();  // 1. v' = v + dt f / m (paper, Eq. S8)
  void particle_to_grid();            // 2. APIC mass, momentum (paper, Eqs. S14, S15): 2a, 2b
  void rebuild_grid();                //   2a. the grid's blocks where the particles are, zeroed
  void scatter_to_grid();             //   2b. the particles' mass and momentum onto the nodes
  void apply_grid_rules();            // 3. clamp, plate (paper, Eq. S16), ...
  void grid_to_particle();            // 4. v, C, x (paper, Eqs. S17, S18)
  void advance_rigid_bodies();        // 5.

  [[nodiscard]] const Particles& particles() const { return p_; }
  [[nodiscard]] Particles& particles() { return p_; }
  [[nodiscard]] const SparseGrid& grid() const { return grid_; }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] double dt() const { return options_.dt; }
  [[nodiscard]] double dx() const { return options_.dx; }
  void set_damping(double c) { options_.damping = c; }
  // Restarts the clock (the release defines t = 0).
  void reset_time() { restore_clock(0.0, 0); }
  void restore_clock(double time, long steps) {
    time_ = time;
    steps_ = steps;
  }
  [[nodiscard]] long steps() const { return steps_; }
  [[nodiscard]] double kinetic_energy() const;
  // Largest particle speed after the last step, and the grid CFL number it gives.
  [[nodiscard]] double max_speed() const { return max_speed_; }
  [[nodiscard]] double cfl() const { return max_speed_ * options_.dt / options_.dx; }
  [[nodiscard]] const parallel::ThreadTuner& thread_tuner() const { return tuner_; }
  // Whether the transfers run their AVX2 version (StepperOptions::wide_vectors).
  [[nodiscard]] bool wide_vectors() const { return wide_; }

 private:
  Particles p_;
  ForceProvider& forces_;
  StepperOptions options_;
  SparseGrid grid_;
  std::vector<std::unique_ptr<GridRule>> rules_;
  std::vector<RigidBody*> bodies_;
  parallel::ThreadTuner tuner_;
  core::Points f_;
  std::vector<std::uint64_t> cube_done_;  // per cube: the last scatter that finished it
  std::uint64_t scatter_epoch_ = 0;
  bool wide_ = false;  // the transfers' AVX2 version is used
  double time_ = 0.0;
  long steps_ = 0;
  double max_speed_ = 0.0;
};

}  // namespace snapjump::mpm
