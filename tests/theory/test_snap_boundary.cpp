// The Snap / No snap boundary (theory::snap_boundary_weight) against the closed form it inverts,
// U / (mg H_l) = 1 with U and H_l from the formulas themselves, against a brute-force scan of
// predict()'s snap margin, and where the theory has no boundary.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "config/case.hpp"
#include "theory/scaling.hpp"
#include "theory/snap_boundary.hpp"

namespace snapjump::theory {
namespace {

double margin_end(config::Case c, double mg, SnapMarginEnd end) {
  c.popper.net_weight = mg;
  const auto p = predict(c, contact_constants());
  return end == SnapMarginEnd::Lower ? p.snap_margin.lo : p.snap_margin.hi;
}

// The default popper with another thickness.
config::Case with_thickness(double h) {
  auto c = config::default_case();
  c.shell.h = h;
  return c;
}

constexpr SnapMarginEnd kEnds[] = {SnapMarginEnd::Lower, SnapMarginEnd::Upper};

TEST(TheorySnapBoundary, MarginIsOneThereAndTheWeightIsTheClosedForms) {
  const auto& k = contact_constants();
  for (const double h : {0.5e-3, 1.0e-3, 2.0e-3, 3.0e-3}) {
    const auto c = with_thickness(h);
    const double R = c.shell.R, phi = c.shell.phi, E = c.material.E, nu = c.material.nu;
    const auto alpha = prefactor_bounds(k, nu);
    const double U = mirror_energy(k.mirror_energy_prefactor, E, h, cap_depth(R, phi), nu, R);
    // margin.lo = U / (mg H_l.hi), H_l.hi from the lower alpha_e; margin.hi the other way round.
    const double expected[] = {U / lifting_height(R, phi, h, alpha.alpha_e.lo),
                               U / lifting_height(R, phi, h, alpha.alpha_e.hi)};
    for (int e = 0; e < 2; ++e) {
      const auto mg = snap_boundary_weight(c, kEnds[e], k);
      ASSERT_TRUE(mg.has_value()) << "h = " << h << ", end " << e;
      EXPECT_NEAR(*mg / expected[e], 1.0, 1e-10) << "h = " << h << ", end " << e;
      // The criterion changes sign there: lighter snaps, heavier does not.
      EXPECT_GT(margin_end(c, *mg * (1.0 - 1e-9), kEnds[e]), 1.0);
      EXPECT_LT(margin_end(c, *mg * (1.0 + 1e-9), kEnds[e]), 1.0);
    }
    // The upper end of the margin is the larger: its boundary lies at the heavier weight.
    EXPECT_LT(*snap_boundary_weight(c, SnapMarginEnd::Lower, k),
              *snap_boundary_weight(c, SnapMarginEnd::Upper, k));
  }
}

TEST(TheorySnapBoundary, MatchesABruteForceScanOfTheMargin) {
  const auto c = with_thickness(1.5e-3);
  for (const auto end : kEnds) {
    // The first sign change of margin - 1 on a log grid from 1 mN to 1 kN (0.23 % steps).
    const int n = 6000;
    std::optional<std::pair<double, double>> bracket;
    for (int i = 0; i < n && !bracket; ++i) {
      const double a = 1e-3 * std::pow(1e6, static_cast<double>(i) / n);
      const double b = 1e-3 * std::pow(1e6, static_cast<double>(i + 1) / n);
      if (margin_end(c, a, end) > 1.0 && !(margin_end(c, b, end) > 1.0)) bracket = {a, b};
    }
    ASSERT_TRUE(bracket.has_value());
    const auto mg = snap_boundary_weight(c, end, contact_constants());
    ASSERT_TRUE(mg.has_value());
    EXPECT_GE(*mg, bracket->first);
    EXPECT_LE(*mg, bracket->second);
  }
}

TEST(TheorySnapBoundary, DoesNotDependOnTheStartingWeight) {
  auto c = with_thickness(2.0e-3);
  const auto reference = snap_boundary_weight(c, SnapMarginEnd::Lower, contact_constants());
  ASSERT_TRUE(reference.has_value());
  for (const double start : {1e-4, 0.05, 3.0, 500.0, 0.0}) {
    c.popper.net_weight = start;
    const auto mg = snap_boundary_weight(c, SnapMarginEnd::Lower, contact_constants());
    ASSERT_TRUE(mg.has_value()) << "from " << start << " N";
    EXPECT_NEAR(*mg / *reference, 1.0, 1e-11) << "from " << start << " N";
  }
}

TEST(TheorySnapBoundary, NoneWhereTheTheoryGivesNoLift) {
  // At phi = 80 deg the cap's depth is 0.826 R. With h = 0.3 R the upper alpha_e (above 3)
  // indents past it, so H_l.lo has no value, while the lower one (below 2) does not; with
  // h = 0.6 R neither end of H_l has a value.
  const auto& k = contact_constants();
  auto c = config::default_case();
  c.shell.h = 0.3 * c.shell.R;
  EXPECT_TRUE(snap_boundary_weight(c, SnapMarginEnd::Lower, k).has_value());
  EXPECT_FALSE(snap_boundary_weight(c, SnapMarginEnd::Upper, k).has_value());
  c.shell.h = 0.6 * c.shell.R;
  EXPECT_FALSE(snap_boundary_weight(c, SnapMarginEnd::Lower, k).has_value());
  EXPECT_FALSE(snap_boundary_weight(c, SnapMarginEnd::Upper, k).has_value());
}

}  // namespace
}  // namespace snapjump::theory
