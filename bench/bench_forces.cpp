// Internal-force loop of the default (30, 2.0) mm cap: elements per second at 1 and 2 threads.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "fem/body.hpp"
#include "mesh/cap_mesher.hpp"

namespace {

using namespace snapjump;

const fem::Body& default_cap() {
  // The default case's mesh at the default resolution: the (30, 2.0) mm cap, sqrt(hR)/3.5 =
  // 2.2 mm in-surface element size, 2 quadratic elements through the thickness.
  static const fem::Body body = [] {
    const auto c = config::default_case();
    return fem::Body(mesh::make_cap_mesh(mesh::cap_spec(c)),
                     fem::Material::from_young(c.material.E, c.material.nu, c.material.rho));
  }();
  return body;
}

void BM_InternalForces(benchmark::State& state) {
  const auto& body = default_cap();
  omp_set_num_threads(static_cast<int>(state.range(0)));
  auto x = body.mesh().nodes;
  for (std::size_t a = 0; a < x.size(); ++a) x.z[a] *= 1.001;  // a small stretch
  mesh::Points f;
  fem::Body::ForceScratch scratch;
  for (auto _ : state) {
    body.internal_forces(x, f, scratch);
    benchmark::DoNotOptimize(f.z.data());
  }
  state.counters["elements"] = static_cast<double>(body.num_elements());
  state.counters["nodes"] = static_cast<double>(body.num_nodes());
  state.counters["elements_per_s"] = benchmark::Counter(
      static_cast<double>(body.num_elements()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_InternalForces)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
