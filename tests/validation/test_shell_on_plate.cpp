// The finite-element shell in the MPM engine pressed apex-down onto the rigid plate, against the
// shell-plane contact problem solved independently by the contact solver (shallow-shell theory,
// whose small-load slope is Reissner's point-load stiffness).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "support/disk_branch.hpp"
#include "validation/shell_over_plate.hpp"

namespace snapjump {
namespace {

// The default popper's shell at the default preset's mesh (sqrt(hR)/2 elements, one quadratic
// element through h) with cells of 0.025 R (a fixed fraction of R, not the presets' h/4), its rim
// lowered at 0.05 m/s onto the plate.
TEST(ShellOnPlate, ForceAgainstIndentationFollowsTheContactSolver) {
  using P = testing::ShellOverPlate;
  const double R = P::R, h = P::h, nu = P::nu, E = P::E, v0 = 0.05;
  P setup(0.3);
  const double dx = setup.dx;
  auto& rim = setup.rim;
  rim.vz = -v0;

  struct Sample {
    double lowered, F;  // rim lowered since the start [m], plate force (0.5 ms mean) [N]
  };
  std::vector<Sample> samples;
  for (double next = 0.5e-3; rim.z > -(2.0 * dx + 5.0e-3); next += 0.5e-3) {
    const double F = setup.mean_force_until(next, [] {});
    samples.push_back({-rim.z, F});
  }

  // The contact solver's disk branch in physical units.
  const test_support::DiskBranchForce F_theory(R, h, E, nu);

  // Where the contact starts is known only to about a grid cell (the plate acts on the grid
  // nodes within its reach), so the one free parameter is the rim height at first contact,
  // fitted over the samples with 0.5 N < F < 2 N (e from about 0.7 h to 2 h; below, the
  // uncertainty of where contact starts, a fraction of a cell, dominates the relative error).
  double best_rms = INFINITY, best_start = 0.0;
  for (double start = 0.5 * dx; start <= 4.0 * dx; start += 1e-6) {
    double ss = 0.0;
    int count = 0;
    for (const auto& q : samples) {
      if (q.F < 0.5 || q.F > 2.0) continue;
      const double f = F_theory(q.lowered - start);
      if (!std::isfinite(f)) continue;
      ss += (q.F - f) * (q.F - f);
      ++count;
    }
    if (count > 20 && std::sqrt(ss / count) < best_rms) {
      best_rms = std::sqrt(ss / count);
      best_start = start;
    }
  }
  double worst = 0.0;
  for (const auto& q : samples) {
    if (q.F < 0.5 || q.F > 2.0) continue;
    worst = std::max(worst, std::abs(q.F / F_theory(q.lowered - best_start) - 1.0));
  }
  // The surface first touched the plate's reach at lowered = 2 dx - (reach); the fit says where.
  const double reach = 2.0 * dx - best_start;
  std::printf(
      "shell on plate: rms %.4f N, worst %.2f %% over 0.5-2 N; fitted contact start %.3f mm "
      "(surface %.3f mm = %.2f cells above the plate when the force begins)\n",
      best_rms, 100 * worst, 1e3 * best_start, 1e3 * reach, reach / dx);
  for (double e_mm : {1.0, 2.0, 3.0, 4.0}) {
    const auto it = std::min_element(samples.begin(), samples.end(), [&](auto a, auto b) {
      return std::abs(a.lowered - best_start - e_mm * 1e-3) <
             std::abs(b.lowered - best_start - e_mm * 1e-3);
    });
    std::printf("  e = %.1f mm: F = %.3f N, contact solver %.3f N\n", e_mm, it->F,
                F_theory(e_mm * 1e-3));
  }
  EXPECT_LT(worst, 0.05);
  EXPECT_LT(std::abs(reach), 1.5 * dx);  // within the grid's reach of the plate
}

}  // namespace
}  // namespace snapjump
