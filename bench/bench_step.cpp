// One full MPM step of the default (30, 2.0) mm cap: particle forces, particle to grid, grid
// rules (clamp and plate), grid to particle, rigid body. Reports ms per step and particle-steps
// per second at 1 and 2 threads.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "config/case.hpp"
#include "fem/body.hpp"
#include "mesh/cap_mesher.hpp"
#include "mpm/body_forces.hpp"
#include "mpm/stepper.hpp"

namespace {

using namespace snapjump;

const fem::Body& default_cap() {
  static const fem::Body body = [] {
    const auto c = config::default_case();
    auto m = mesh::make_cap_mesh(mesh::cap_spec(c));
    mesh::translate_z(m, c.shell.R + c.shell.h);  // apex a little above the plate
    return fem::Body(std::move(m),
                     fem::Material::from_young(c.material.E, c.material.nu, c.material.rho));
  }();
  return body;
}

void BM_Step(benchmark::State& state) {
  const auto& body = default_cap();
  omp_set_num_threads(static_cast<int>(state.range(0)));
  mpm::BodyForces forces(body, 9.80665, [](double) { return 1000.0; });
  // Grid spacing: half the shell thickness (1 mm).
  mpm::Stepper stepper(mpm::particles_of(body), forces, {body.stable_time_step(0.3), 0.001, 0.5});
  mpm::RigidBody container;
  container.mass = 0.04;
  stepper.add_rule(std::make_unique<mpm::ClampRule>(container));
  stepper.add_rule(std::make_unique<mpm::PlateRule>(0.3));
  stepper.add_rigid_body(container);
  for (auto _ : state) stepper.step();
  const double n = static_cast<double>(body.num_nodes());
  state.counters["particles"] = n;
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Step)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
