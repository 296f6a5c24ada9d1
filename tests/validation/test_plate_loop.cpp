// The shell-plane contact transition under the conditions the theory assumes: no gas, a rigid
// plate pressed quasi-statically onto the popper's shell, deep into the mirror-buckled (ring)
// state, and withdrawn again. The paper bounds the prefactors alpha_F and alpha_e of the
// transition between the disk branch's buckling point N+ and the crossing N- of the disk branch
// with the ring law; our contact solver computes both. Run with friction (mu = 0.3, the default)
// and without. A long validation (about five minutes per friction coefficient on one core):
// label `long`, not part of `make test`; `make validate-long` runs it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "theory/prefactors.hpp"
#include "validation/shell_over_plate.hpp"

namespace snapjump {
namespace {

struct Sample {
  double e;  // rim travel since the apex would touch the plate geometrically [m]
  double F;  // plate force, mean over the sample interval [N]
  double w;  // height of the outer apex above the plate [m]
  bool unloading;
};

class PlateLoop : public ::testing::TestWithParam<double> {};  // the friction coefficient

TEST_P(PlateLoop, TheRingToDiskTransitionFallsWithinTheContactBounds) {
  using P = testing::ShellOverPlate;
  const double v0 = 0.05, travel = 9.0e-3, interval = 0.5e-3, mu = GetParam();
  P setup(mu);
  setup.rim.vz = -v0;
  std::vector<Sample> samples;
  bool unloading = false;
  const auto turn_at_the_bottom = [&] {
    if (!unloading && -setup.rim.z > setup.gap + travel) {
      unloading = true;
      setup.rim.vz = v0;
    }
  };
  for (double next = interval; !unloading || setup.rim.z < 0.0; next += interval) {
    const double F = setup.mean_force_until(next, turn_at_the_bottom);
    samples.push_back({-setup.rim.z - setup.gap, F, setup.apex_height(), unloading});
  }
  if (const char* prefix = std::getenv("SNAPJUMP_PLATE_LOOP_CSV")) {
    const std::string path = std::string(prefix) + "-mu" + std::to_string(mu).substr(0, 3) + ".csv";
    if (std::FILE* out = std::fopen(path.c_str(), "w")) {
      std::fprintf(out, "# the default shell pressed by the plate and released, mu = %g\n", mu);
      std::fprintf(out, "e_m,F_N,w_m,unloading\n");
      for (const auto& q : samples) {
        std::fprintf(out, "%.6e,%.6e,%.6e,%d\n", q.e, q.F, q.w, q.unloading ? 1 : 0);
      }
      std::fclose(out);
    }
  }

  const auto bounds = theory::prefactor_bounds(theory::contact_constants(), P::nu);
  const double Fc = P::E * P::h * P::h * P::h / P::R;
  const double F_plus = bounds.alpha_F.hi * Fc;  // where the contact disk buckles (N+)

  // Loading: the flat contact disk holds the apex on the plate at least up to N+, then the
  // shell buckles into the ring state (apex lifted by more than h).
  double F_disk_max = 0.0, F_so_far = 0.0, e_buckle = NAN;
  bool lifted_below_plus = false;
  for (const auto& q : samples) {
    if (q.unloading) break;
    // The largest force so far: the force drops as the disk buckles, while the apex rises.
    F_so_far = std::max(F_so_far, q.F);
    if (F_so_far < F_plus && q.e > 0.5 * P::h && q.w > 0.25 * P::h) lifted_below_plus = true;
    if (q.w > P::h) {
      e_buckle = q.e;
      break;
    }
    F_disk_max = std::max(F_disk_max, q.F);
  }
  std::printf(
      "loading: the disk holds up to F = %.3f N (alpha_F %.2f; N+ gives %.2f) and buckles "
      "into the ring state at e = %.2f mm\n",
      F_disk_max, F_disk_max / Fc, bounds.alpha_F.hi, 1e3 * e_buckle);
  EXPECT_FALSE(lifted_below_plus) << "the apex left the plate below N+";
  ASSERT_TRUE(std::isfinite(e_buckle)) << "the shell never buckled into the ring state";

  // Unloading: the first time the apex comes down to w = 0.03 R (the onset criterion of the
  // popper runs), interpolated between samples.
  double e_on = NAN, F_on = NAN;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const auto& a = samples[i - 1];
    const auto& b = samples[i];
    if (a.unloading && b.unloading && a.w >= 0.03 * P::R && b.w < 0.03 * P::R) {
      const double f = (a.w - 0.03 * P::R) / (a.w - b.w);
      e_on = a.e + f * (b.e - a.e);
      F_on = a.F + f * (b.F - a.F);
      break;
    }
  }
  ASSERT_TRUE(std::isfinite(e_on)) << "the apex never came back down to the plate";
  const double alpha_F = F_on / Fc, alpha_e = e_on / P::h;
  std::printf(
      "unloading: w = 0.03 R at e = %.3f mm, F = %.3f N: alpha_e %.2f (bounds %.2f-%.2f), "
      "alpha_F %.2f (bounds %.2f-%.2f)\n",
      1e3 * e_on, F_on, alpha_e, bounds.alpha_e.lo, bounds.alpha_e.hi, alpha_F, bounds.alpha_F.lo,
      bounds.alpha_F.hi);
  for (double e_mm : {6.0, 5.0, 4.0, 3.0, 2.0}) {
    const auto nearest = [&](bool unload) {
      const Sample* best = nullptr;
      for (const auto& q : samples) {
        if (q.unloading != unload) continue;
        if (!best || std::abs(q.e - 1e-3 * e_mm) < std::abs(best->e - 1e-3 * e_mm)) best = &q;
      }
      return *best;
    };
    const auto l = nearest(false), u = nearest(true);
    std::printf("  e = %.0f mm: loading F = %.3f N (w %.2f mm), unloading F = %.3f N (w %.2f mm)\n",
                e_mm, l.F, 1e3 * l.w, u.F, 1e3 * u.w);
  }
  EXPECT_GE(alpha_F, bounds.alpha_F.lo);
  EXPECT_LE(alpha_F, bounds.alpha_F.hi);
  EXPECT_GE(alpha_e, bounds.alpha_e.lo);
  EXPECT_LE(alpha_e, bounds.alpha_e.hi);
  // The loop closes: with the rim back where it started, the plate carries nothing.
  EXPECT_LT(samples.back().F, 0.01 * F_disk_max);
}

INSTANTIATE_TEST_SUITE_P(Friction, PlateLoop, ::testing::Values(0.3, 0.0));

}  // namespace
}  // namespace snapjump
