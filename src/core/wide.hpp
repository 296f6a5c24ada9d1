// The hottest loops (the transfers, the elements' forces) are compiled a second time for AVX2 on
// x86-64, and the version for the processor is chosen when a stepper or body is made. AVX2 alone
// brings no fused multiply-add, and the build turns contraction off (-ffp-contract=off in
// CMakeLists.txt), so every lane of every vector does the IEEE operations of the scalar expression
// and both versions give the same bits (tests
// Threads.TheTransfersBaselineAndAvx2VersionsGiveTheSameBits and
// Threads.TheElementForcesBaselineAndAvx2VersionsGiveTheSameBits; both fail when the second
// version is compiled with "avx2,fma" and contraction allowed).
#pragma once

// On a function: compile it for AVX2 (x86-64), or for the baseline elsewhere (where has_avx2() is
// false and the function is never called).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SNAPJUMP_HAS_AVX2 1
#define SNAPJUMP_AVX2 __attribute__((target("avx2")))
#else
#define SNAPJUMP_AVX2
#endif

namespace snapjump::core {

// Whether this build has AVX2 versions and this processor runs them.
inline bool has_avx2() {
#ifdef SNAPJUMP_HAS_AVX2
  return __builtin_cpu_supports("avx2") != 0;
#else
  return false;
#endif
}

}  // namespace snapjump::core
