// What this machine gives two threads, apart from snapjump: the limits a step's stages meet.
//   BM_Clear/<threads>       clear a buffer the size of the default popper's live grid nodes
//                            (216 k nodes of 32 bytes: 6.9 MB) with memsets of one block (2 KB)
//                            each, each thread its half: the cache bandwidth two threads get
//                            for the grid's bytes (the grid's zeroing clears runs of blocks,
//                            tags too; the transfers read and write the same bytes)
//   BM_Chains/<threads>      each thread the same chains of dependent multiply-adds (registers
//                            only): whether the threads get a core each (a hyperthread pair or
//                            a shared core would slow both)
//   BM_Triad/<threads>       a[i] = b[i] + s c[i] over three 32 MB arrays (beyond any cache):
//                            the main memory's bandwidth, counted as 24 bytes an element (the
//                            bytes read and written; a write-allocating cache moves 32)
//   BM_Flops/<threads>       independent AVX2 multiplies and adds (as the hot loops are compiled:
//                            no fused multiply-add), twelve vectors in registers: the arithmetic
//                            rate a thread can reach, in flops per second
//   BM_Region/<threads>      an empty OpenMP parallel region: what starting the threads costs
//   BM_Barrier/<threads>     one barrier inside a running region
// Reports the time per iteration, with bytes per second (BM_Clear, BM_Triad), flops per second
// (BM_Flops) or barriers per second
// (BM_Barrier, 10,000 barriers an iteration). docs/performance.md, "Threads", compares these
// with how the step's stages scale on the same machine.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/wide.hpp"

namespace {

constexpr std::size_t kGridBytes = 215872 * 32;
constexpr std::size_t kBlockBytes = 64 * 32;

void BM_Clear(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<unsigned char> buffer(kGridBytes, 1);
  unsigned char value = 0;
  for (auto _ : state) {
#pragma omp parallel num_threads(threads)
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const auto n = static_cast<std::size_t>(omp_get_num_threads());
      const std::size_t first = kGridBytes * t / n, end = kGridBytes * (t + 1) / n;
      // Block by block (64 nodes, 2 KB): one memset of megabytes would take the C library's
      // path for buffers beyond the cache, which the grid's runs of blocks do not reach.
      for (std::size_t b = first; b < end; b += kBlockBytes) {
        std::memset(buffer.data() + b, value, std::min(kBlockBytes, end - b));
      }
    }
    value = static_cast<unsigned char>(value + 1);  // each pass writes new bytes
    benchmark::DoNotOptimize(buffer.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(kGridBytes));
}
BENCHMARK(BM_Clear)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

// Four chains of dependent multiply-adds, 10 million steps each, per thread.
double chains() {
  double a = 1.0, b = 1.000001, c = 0.999999, d = 1.0000003;
  for (int i = 0; i < 10000000; ++i) {
    a = a * 0.9999999 + 1e-9;
    b = b * 0.9999998 + 1e-9;
    c = c * 0.9999997 + 1e-9;
    d = d * 0.9999996 + 1e-9;
  }
  return a + b + c + d;
}

void BM_Chains(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    double sum = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : sum)
    sum += chains();
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_Chains)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

constexpr std::size_t kTriadDoubles = std::size_t{32} << 17;  // 32 MB an array

void BM_Triad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<double> a(kTriadDoubles, 0.0), b(kTriadDoubles, 1.0), c(kTriadDoubles, 2.0);
  const auto n = static_cast<long>(kTriadDoubles);
  double s = 0.5;
  for (auto _ : state) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (long i = 0; i < n; ++i)
      a[static_cast<std::size_t>(i)] =
          b[static_cast<std::size_t>(i)] + s * c[static_cast<std::size_t>(i)];
    s = a[0] * 1e-3;  // the next pass depends on this one
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * 24 * n);
}
BENCHMARK(BM_Triad)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

using Wide = double __attribute__((vector_size(4 * sizeof(double))));
constexpr int kFlopVectors = 12;
constexpr long kFlopSteps = 10000000;

// Twelve independent chains of a multiply and an add on four lanes each: 96 flops a step.
#ifdef SNAPJUMP_HAS_AVX2
SNAPJUMP_AVX2
#endif
double flops() {
  Wide v[kFlopVectors];
  for (int k = 0; k < kFlopVectors; ++k) v[k] = Wide{1.0, 1.1, 1.2, 1.3} + 0.01 * k;
  const Wide m = {0.9999999, 0.9999998, 0.9999997, 0.9999996};
  const Wide add = {1e-9, 2e-9, 3e-9, 4e-9};
  for (long i = 0; i < kFlopSteps; ++i) {
    for (int k = 0; k < kFlopVectors; ++k) v[k] = v[k] * m + add;
  }
  double sum = 0.0;
  for (int k = 0; k < kFlopVectors; ++k) sum += v[k][0] + v[k][1] + v[k][2] + v[k][3];
  return sum;
}

void BM_Flops(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    double sum = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : sum)
    sum += flops();
    benchmark::DoNotOptimize(sum);
  }
  state.counters["flops"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * threads * kFlopSteps * kFlopVectors * 8,
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Flops)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_Region(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  int sink = 0;
  for (auto _ : state) {
#pragma omp parallel num_threads(threads)
    {
      if (omp_get_thread_num() == threads) sink = 1;  // never: the region does nothing
    }
  }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(BM_Region)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

void BM_Barrier(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  constexpr int kBarriers = 10000;
  for (auto _ : state) {
#pragma omp parallel num_threads(threads)
    for (int k = 0; k < kBarriers; ++k) {
#pragma omp barrier
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kBarriers);
}
BENCHMARK(BM_Barrier)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
