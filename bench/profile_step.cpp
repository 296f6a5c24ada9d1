// Where an MPM step of a popper's shell goes: times each stage of mpm::Stepper over 100 steps and
// prints milliseconds per step (and the fastest, 10th-percentile and median whole step). Usage:
// profile_step [coarse|default|fine] (default: default). The mesh's nodes are in the curve order
// the popper uses (mesh::sort_along_curve); with UNSORTED set in the environment, in gmsh's order.
//
// profile_step release [steps]: the phase a run spends its time in. The default popper prepared
// as `snapjump run` prepares it (about half a minute), released, 200 steps untimed, then `steps`
// (default 3000) whole popper steps (the MPM step, the gas) timed, with a sample every probe
// interval as a run takes it; prints milliseconds per step and what the thread tuner did.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "fem/body.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/cap_mesher.hpp"
#include "mpm/stepper.hpp"
#include "popper/mpm_shell.hpp"
#include "popper/popper.hpp"

namespace {

using Clock = std::chrono::steady_clock;

int profile_release(int steps) {
  using namespace snapjump;
  const auto c = config::default_case();
  const auto numerics = popper::resolve_numerics(c);
  popper::Popper pop(c, numerics);
  const auto prep = pop.prepare();
  if (!prep.held) {
    std::fprintf(stderr, "profile_step: the preparation failed: %s\n", prep.message.c_str());
    return 1;
  }
  pop.release();
  for (int k = 0; k < 200; ++k) pop.step();
  const auto& tuner = dynamic_cast<const popper::MpmShell&>(pop.model()).stepper().thread_tuner();
  const long trials_before = tuner.trials(), early_before = tuner.early_trials(),
             close_before = tuner.close_calls();
  const int every = std::max(1, static_cast<int>(std::lround(numerics.probe_interval / pop.dt())));
  std::vector<double> whole;
  long at_many = 0;
  const auto start = Clock::now();
  for (int k = 0; k < steps; ++k) {
    if (tuner.next() > 1) ++at_many;
    const auto a = Clock::now();
    pop.step();
    whole.push_back(std::chrono::duration<double, std::milli>(Clock::now() - a).count());
    if ((k + 1) % every == 0) (void)pop.sample();
  }
  const double total = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  std::sort(whole.begin(), whole.end());
  std::printf("release phase of the default popper: %d steps from t = %.4f s, a sample every %d\n",
              steps, pop.time() - steps * pop.dt(), every);
  std::printf(
      "ms per step (samples included): %.3f; whole steps: 10th percentile %.3f ms, median "
      "%.3f ms\n",
      total / steps, whole[whole.size() / 10], whole[whole.size() / 2]);
  std::printf(
      "threads: more than one in %ld of %d steps (at most %d); tuner trials %ld, of them "
      "started early %ld; one thread chosen by a close call %ld times\n",
      at_many, steps, tuner.max_threads(), tuner.trials() - trials_before,
      tuner.early_trials() - early_before, tuner.close_calls() - close_before);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace snapjump;
  auto c = config::default_case();
  const std::string preset = argc > 1 ? argv[1] : "default";
  if (preset == "release") {
    long steps = 3000;
    if (argc > 2) {
      char* end = nullptr;
      steps = std::strtol(argv[2], &end, 10);
      if (end == argv[2] || *end != '\0' || steps < 1 || steps > 10'000'000) {
        std::fprintf(stderr,
                     "profile_step release: the step count must be a whole number from 1 to "
                     "10000000 (got '%s')\n",
                     argv[2]);
        return 1;
      }
    }
    return profile_release(static_cast<int>(steps));
  }
  if (preset == "coarse") c.numerics.resolution = config::Resolution::Coarse;
  if (preset == "fine") c.numerics.resolution = config::Resolution::Fine;
  const auto numerics = popper::resolve_numerics(c);
  auto m = mesh::make_cap_mesh(numerics.cap);
  mesh::translate_z(m, c.shell.R + c.shell.h);
  if (!std::getenv("UNSORTED")) mesh::sort_along_curve(m);  // as the popper does
  const fem::Body body(std::move(m),
                       fem::Material::from_young(c.material.E, c.material.nu, c.material.rho));
  hybrid::BodyForces forces(body, config::kStandardGravity, [](double) { return 1000.0; });
  mpm::Stepper s(hybrid::particles_of(body), forces,
                 {body.stable_time_step(numerics.time_step_factor), numerics.dx, 0.5});
  mpm::RigidBody container;
  container.mass = 0.04;
  s.add_rule(std::make_unique<mpm::ClampRule>(container));
  s.add_rule(std::make_unique<mpm::PlateRule>(0.3));
  s.add_rigid_body(container);
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  // Twenty steps first, untimed: the grid's arrays grow to their size in the first steps, and
  // the page faults of new memory cost more than a step on a virtual machine.
  for (int k = 0; k < 20; ++k) s.step();
  double t[5] = {};
  constexpr int kSteps = 100;
  std::vector<double> whole;  // each step's time: its low percentiles are the time without
                              // the interruptions of a shared machine
  for (int k = 0; k < kSteps; ++k) {
    const auto a = Clock::now();
    s.update_particle_velocities();
    const auto b = Clock::now();
    s.rebuild_grid();
    const auto b2 = Clock::now();
    s.scatter_to_grid();
    const auto c2 = Clock::now();
    s.apply_grid_rules();
    const auto d = Clock::now();
    s.grid_to_particle();
    const auto e = Clock::now();
    s.advance_rigid_bodies();
    t[0] += ms(a, b);
    t[1] += ms(b, c2);
    t[4] += ms(b, b2);
    t[2] += ms(c2, d);
    t[3] += ms(d, e);
    whole.push_back(ms(a, Clock::now()));
  }
  std::sort(whole.begin(), whole.end());
  std::printf("%s cap: %zu particles, %zu elements, dx %.3g mm, %zu grid nodes\n", preset.c_str(),
              body.num_nodes(), body.num_elements(), 1e3 * numerics.dx, s.grid().num_nodes());
  std::size_t with_mass = 0;
  for (const auto& node : s.grid().nodes) with_mass += node.m > 0.0 ? 1 : 0;
  std::printf("grid nodes reached by a particle in the last step: %zu\n", with_mass);
  std::printf(
      "ms per step: forces %.2f, particle to grid %.2f (the grid's rebuild %.2f), grid rules "
      "%.2f, grid to particle %.2f, total %.2f\n",
      t[0] / kSteps, t[1] / kSteps, t[4] / kSteps, t[2] / kSteps, t[3] / kSteps,
      (t[0] + t[1] + t[2] + t[3]) / kSteps);
  std::printf("whole steps: fastest %.3f ms, 10th percentile %.3f ms, median %.3f ms\n", whole[0],
              whole[kSteps / 10], whole[kSteps / 2]);
  std::printf("the grid's blocks made again in %ld of %d steps (%zu blocks, %zu reached)\n",
              s.grid().full_rebuilds(), kSteps + 20, s.grid().num_blocks(),
              s.grid().live_blocks().size());
  return 0;
}
