// The axisymmetric popper (numerics.model = "axisymmetric"): the cost of one step of the default
// (30, 2.0) mm popper's shell at 2 and 4 elements through h, and the whole default popper's
// jump (buckle, set, ground, release to the apex of the flight) at each preset, on one core.
// Run: build/bench_axi (docs/performance.md).
#include <benchmark/benchmark.h>

#include <exception>
#include <string>

#include "popper/popper.hpp"

namespace {

using namespace snapjump;

config::Case axi_case(config::Resolution r) {
  auto c = config::default_case();
  c.numerics.model = config::Model::Axisymmetric;
  c.numerics.resolution = r;
  return c;
}

config::Resolution preset(std::int64_t through) {
  return through <= 2 ? config::Resolution::Coarse
                      : (through <= 4 ? config::Resolution::Default : config::Resolution::Fine);
}

// The preparation, or why it cannot be had: a shell that does not stay inverted, or one whose
// buckling folds an element (the default preset's, docs/axisymmetric.md "The fold at the clamp").
std::string prepare(popper::Popper& pop) {
  try {
    return pop.prepare().held ? "" : "the shell did not stay inverted";
  } catch (const std::exception& e) {
    return e.what();
  }
}

// One step on the plate, after the preparation (the state of the release).
void BM_AxiStep(benchmark::State& state) {
  const auto c = axi_case(preset(state.range(0)));
  popper::Popper pop(c, popper::resolve_numerics(c));
  if (const auto why = prepare(pop); !why.empty()) {
    state.SkipWithError(why.c_str());
    return;
  }
  pop.release();
  for (auto _ : state) pop.step();
  state.counters["elements_through_h"] = static_cast<double>(state.range(0));
  state.counters["dt_us"] = 1e6 * pop.dt();
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AxiStep)->Arg(2)->Arg(4)->Unit(benchmark::kMicrosecond);

// The whole run of `snapjump run --model axisymmetric` without its files: to the apex of the
// flight after the snap (off the plate for 5 ms and coming down, the apex having come down to
// w / R < 0.03 before) or 1 s.
void BM_AxiPopperJump(benchmark::State& state) {
  const auto c = axi_case(preset(state.range(0)));
  double simulated = 0.0;
  for (auto _ : state) {
    popper::Popper pop(c, popper::resolve_numerics(c));
    if (const auto why = prepare(pop); !why.empty()) {
      state.SkipWithError(why.c_str());
      break;
    }
    pop.release();
    popper::FlightWatch flight{c.shell.R};
    double next = 1e-4;
    while (pop.time() < 1.0) {
      pop.step();
      if (pop.time() + 1e-12 < next) continue;
      next += 1e-4;
      if (flight.apex_reached(pop.sample())) break;
    }
    simulated = pop.time();
  }
  state.counters["elements_through_h"] = static_cast<double>(state.range(0));
  state.counters["simulated_s"] = simulated;
}
BENCHMARK(BM_AxiPopperJump)->Arg(2)->Arg(4)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
