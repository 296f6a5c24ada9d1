// One full MPM step of the default (30, 2.0) mm cap: particle forces, particle to grid, grid
// rules (clamp and plate), grid to particle, rigid body.
//   BM_Step/<threads>/<tuned>   the default cap and the popper's grid (h/4 = 0.5 mm) at 1 and 2
//                               threads, with the thread tuner off (0) or on (1)
//   BM_StepWithFace/<threads>   the same with the container's face around the rim as the popper
//                               has it (mpm::ContainerFaceRule after the clamp), untuned: its
//                               cost is the ratio to BM_Step/<threads>/0
//   BM_StepSize/<scale>         one thread, the cap meshed with element size sqrt(8)^-scale times
//                               the default's (scale -1, 0, 1: particle counts a factor of about 8
//                               apart), the same grid: the cost per particle-step should not grow
//   BM_StepGraded/<threads>     the default cap graded as docs/popper.md's example (1 mm within
//                               4 mm of the rim, 2 mm within 18 mm of the apex; 23,601 particles),
//                               untuned: its particle-steps per second against BM_StepSize/1's
//                               (a uniform cap of 1.38 mm, 36,927 particles) say what the
//                               irregular mesh costs in locality
//   BM_StepScaling/<threads>/<graded>  the default cap (0) and the graded one (1), untuned, at
//                               1, 2, 4, ... threads up to the machine's cores: the thread
//                               scaling table of scripts/thread_scaling.sh
// Reports ms per step and particle-steps per second.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <map>
#include <memory>

#include "config/case.hpp"
#include "fem/body.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/cap_mesher.hpp"
#include "mpm/stepper.hpp"
#include "popper/popper.hpp"

namespace {

using namespace snapjump;

// The default case's cap, element size scaled by sqrt(8)^-scale (or graded: kGraded), apex a
// little above the plate.
constexpr int kGraded = 100;
const fem::Body& cap(int scale) {
  static std::map<int, std::unique_ptr<fem::Body>> bodies;
  auto& b = bodies[scale];
  if (!b) {
    const auto c = config::default_case();
    auto spec = popper::resolve_numerics(c).cap;
    if (scale == kGraded) {
      spec.rim_size = 1e-3;
      spec.rim_band = 4e-3;
      spec.contact_size = 2e-3;
      spec.contact_band = 18e-3;
    } else {
      spec.element_size *= std::pow(std::sqrt(8.0), -scale);
    }
    auto m = mesh::make_cap_mesh(spec);
    mesh::translate_z(m, c.shell.R + c.shell.h);
    mesh::sort_along_curve(m);  // as the popper does
    b = std::make_unique<fem::Body>(
        std::move(m), fem::Material::from_young(c.material.E, c.material.nu, c.material.rho));
  }
  return *b;
}

// The same stretch of the trajectory for every benchmark: the stepper starts again from the cap
// at rest every kRestart steps (outside the timing).
constexpr int kRestart = 500;

struct Setup {
  Setup(const fem::Body& body, bool tuned, bool face)
      : forces(body, 9.80665, [](double) { return 1000.0; }),
        stepper(hybrid::particles_of(body), forces, options(body, tuned)) {
    container.mass = 0.04;
    stepper.add_rule(std::make_unique<mpm::ClampRule>(container));
    if (face) {
      const auto c = config::default_case();
      auto& rule = dynamic_cast<mpm::ContainerFaceRule&>(
          stepper.add_rule(std::make_unique<mpm::ContainerFaceRule>(
              container, core::container_face(c.shell.R, c.shell.h, c.shell.phi))));
      rule.set_dz(c.shell.R + c.shell.h);  // where cap() put the rim
    }
    stepper.add_rule(std::make_unique<mpm::PlateRule>(0.3));
    stepper.add_rigid_body(container);
  }
  static mpm::StepperOptions options(const fem::Body& body, bool tuned) {
    mpm::StepperOptions o{body.stable_time_step(popper::kTimeStepFactor),
                          popper::resolve_numerics(config::default_case()).dx, 0.5};
    o.tune_threads = tuned;
    return o;
  }
  hybrid::BodyForces forces;
  mpm::Stepper stepper;
  mpm::RigidBody container;
};

void run_steps(benchmark::State& state, const fem::Body& body, bool tuned, bool face = false) {
  auto setup = std::make_unique<Setup>(body, tuned, face);
  int chosen = 0;
  for (auto _ : state) {
    if (setup->stepper.steps() == kRestart) {
      state.PauseTiming();
      chosen = setup->stepper.thread_tuner().chosen();
      setup = std::make_unique<Setup>(body, tuned, face);
      state.ResumeTiming();
    }
    setup->stepper.step();
  }
  const double n = static_cast<double>(body.num_nodes());
  state.counters["particles"] = n;
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  // The threads the steps ran with: the tuner's choice (all allowed when it is off).
  state.counters["threads"] = chosen > 0 ? chosen : setup->stepper.thread_tuner().chosen();
}

void BM_Step(benchmark::State& state) {
  const auto& body = cap(0);
  omp_set_num_threads(static_cast<int>(state.range(0)));
  run_steps(state, body, state.range(1) != 0);
}
BENCHMARK(BM_Step)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

void BM_StepWithFace(benchmark::State& state) {
  const auto& body = cap(0);
  omp_set_num_threads(static_cast<int>(state.range(0)));
  run_steps(state, body, false, true);
}
BENCHMARK(BM_StepWithFace)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

void BM_StepSize(benchmark::State& state) {
  const auto& body = cap(static_cast<int>(state.range(0)));
  omp_set_num_threads(1);
  run_steps(state, body, false);
}
BENCHMARK(BM_StepSize)
    ->Arg(-1)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

void BM_StepGraded(benchmark::State& state) {
  const auto& body = cap(kGraded);
  omp_set_num_threads(static_cast<int>(state.range(0)));
  run_steps(state, body, false);
}
BENCHMARK(BM_StepGraded)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

// 1, 2, 4, ... threads and the machine's core count, for each mesh.
void scaling_arguments(benchmark::internal::Benchmark* b) {
  const int cores = omp_get_num_procs();
  for (int graded = 0; graded <= 1; ++graded) {
    for (int t = 1; t < cores; t *= 2) b->Args({t, graded});
    b->Args({cores, graded});
  }
}

void BM_StepScaling(benchmark::State& state) {
  const auto& body = cap(state.range(1) != 0 ? kGraded : 0);
  omp_set_num_threads(static_cast<int>(state.range(0)));
  run_steps(state, body, false);
}
BENCHMARK(BM_StepScaling)
    ->Apply(scaling_arguments)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
