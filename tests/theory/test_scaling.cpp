// Each closed form against numbers worked out by hand (the arithmetic is in the comments), and
// against limits that any correct implementation must reach.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "config/case.hpp"
#include "theory/scaling.hpp"

namespace snapjump::theory {
namespace {

constexpr double kPi = std::numbers::pi;
const double kPhi80 = 80.0 * kPi / 180.0;

TEST(CapGeometry, RimAndDepth) {
  // 30 mm * sin(80 deg) = 30 * 0.98480775 = 29.5442 mm; 30 * (1 - 0.17364818) = 24.7906 mm
  EXPECT_NEAR(rim_radius(0.030, kPhi80), 0.0295442326, 1e-9);
  EXPECT_NEAR(cap_depth(0.030, kPhi80), 0.0247905547, 1e-9);
  // A hemisphere: rim radius R, depth R.
  EXPECT_NEAR(rim_radius(0.02, kPi / 2), 0.02, 1e-15);
  EXPECT_NEAR(cap_depth(0.02, kPi / 2), 0.02, 1e-15);
}

TEST(CapGeometry, ShellVolumeAndMass) {
  // (2 pi / 3) (0.031^3 - 0.029^3) (1 - cos 80 deg) = 2.0944 * 5.4002e-6 * 0.82635 = 9.3493e-6 m^3
  EXPECT_NEAR(shell_volume(0.030, 0.002, kPhi80), 9.349280e-6, 1e-11);
  // times 1160 kg/m^3 = 10.845 g
  EXPECT_NEAR(shell_mass(0.030, 0.002, kPhi80, 1160.0), 0.0108452, 1e-7);
  // A thin hemisphere is area 2 pi R^2 times h.
  EXPECT_NEAR(shell_volume(1.0, 1e-4, kPi / 2) / (2 * kPi * 1e-4), 1.0, 1e-8);
}

TEST(CapGeometry, CavityVolume) {
  // A hemisphere of inner radius R - h/2 = 1: (2/3) pi.
  EXPECT_NEAR(cavity_volume(1.0 + 0.05, 0.1, kPi / 2), 2.0 * kPi / 3.0, 1e-12);
  // (30, 2.0) mm at 80 deg: Ri = 29 mm, d = 29 (1 - cos 80) = 23.964 mm,
  // pi d^2 (3 Ri - d) / 3 = pi * 574.29 * 63.036 / 3 mm^3 = 37908.96 mm^3
  EXPECT_NEAR(cavity_volume(0.030, 0.002, kPhi80), 3.79090e-5, 1e-9);
}

TEST(ClassicalShell, Zoelly) {
  // 2 * 1.2e6 * (2e-3)^2 / (0.03^2 * sqrt(3 * (1 - 0.45^2))) = 9.6 / (9e-4 * 1.546771) = 6896.09 Pa
  EXPECT_NEAR(zoelly_pressure(1.2e6, 0.002, 0.030, 0.45), 6896.09, 0.01);
  // nu = 0: 2 E h^2 / (sqrt(3) R^2)
  EXPECT_NEAR(zoelly_pressure(1.0, 1.0, 1.0, 0.0), 2.0 / std::sqrt(3.0), 1e-15);
}

TEST(ClassicalShell, Reissner) {
  // 4 * 1.2e6 * 4e-6 / (0.03 * 1.546771) = 19.2 / 0.0464031 = 413.765 N/m
  EXPECT_NEAR(reissner_stiffness(1.2e6, 0.002, 0.030, 0.45), 413.765, 1e-3);
}

TEST(Scales, PapersDefinitions) {
  EXPECT_NEAR(r_c(0.002, 0.030), std::sqrt(6e-5), 1e-15);  // 7.746 mm
  EXPECT_DOUBLE_EQ(e_c(0.002), 0.002);
  EXPECT_NEAR(F_c(1.2e6, 0.002, 0.030), 0.32, 1e-14);  // 1.2e6 * 8e-9 / 0.03
  // sqrt(0.0489464 * 0.03 / (1.2e6 * 4e-6)) = sqrt(3.059149e-4) = 17.4904 ms
  EXPECT_NEAR(t_c(0.0489464, 1.2e6, 0.002, 0.030), 0.0174904, 1e-7);
  EXPECT_NEAR(alpha_t(4.5, 8.5), std::sqrt(13.5 / 8.5), 1e-15);
}

TEST(Heights, LiftAndSnap) {
  // 24.7906 mm - 1.8 * 2 mm = 21.1906 mm
  EXPECT_NEAR(lifting_height(0.030, kPhi80, 0.002, 1.8), 0.0211906, 1e-7);
  // 8.5 * 4.5 * 1.2e6 * 1.6e-11 / (0.48 * 0.03) = 7.344e-4 / 0.0144 = 51.0 mm
  EXPECT_NEAR(snap_height(8.5, 4.5, 1.2e6, 0.002, 0.48, 0.030), 0.051, 1e-9);
}

TEST(Heights, MirrorEnergy) {
  // 2 * 1.2e6 * (2e-3)^2.5 * (0.01)^1.5 / ((1 - 0.25)^0.75 * 0.03)
  //   = 2 * 1.2e6 * 1.78885e-7 * 1e-3 / (0.805927 * 0.03) = 4.29325e-4 / 0.0241778 = 0.0177570 J
  EXPECT_NEAR(mirror_energy(2.0, 1.2e6, 0.002, 0.01, 0.5, 0.030), 0.0177570, 1e-6);
}

// These use the paper's published constants so that the hand computations stay independent of
// the contact solver; tests/contact checks the solver's own numbers.
TEST(Prefactors, PapersRangesAtNuOneHalf) {
  const auto p = prefactor_bounds(paper_constants(), 0.5);
  // The paper: 1.2 < alpha_r < 1.6, 1.8 < alpha_e < 4.5, alpha_F = N / 9 with N- = 46.8, N+ = 76.94
  EXPECT_NEAR(p.alpha_r.lo, 1.2, 1e-12);
  EXPECT_NEAR(p.alpha_r.hi, 1.6, 1e-12);
  EXPECT_NEAR(p.alpha_e.lo, 1.8, 1e-12);
  EXPECT_NEAR(p.alpha_e.hi, 4.5, 1e-12);
  EXPECT_NEAR(p.alpha_F.lo, 5.2, 1e-12);
  EXPECT_NEAR(p.alpha_F.hi, 8.548889, 1e-6);
  // alpha_t = sqrt(3 * 1.8 / 5.2) = 1.01905, sqrt(3 * 4.5 / 8.548889) = 1.25664
  EXPECT_NEAR(p.alpha_t.lo, 1.01905, 1e-5);
  EXPECT_NEAR(p.alpha_t.hi, 1.25664, 1e-5);
}

TEST(Prefactors, ConvertedAtAnotherNu) {
  // nu = 0.45: kappa = 12 * 0.7975 = 9.57; alpha_F = 46.8 / 9.57 = 4.89028, 76.94 / 9.57 = 8.03971
  // alpha_e = 5.4 / sqrt(9.57) = 1.74557; alpha_r = 1.2 sqrt(3) / 9.57^0.25 = 1.18172
  EXPECT_NEAR(kappa(0.45), 9.57, 1e-12);
  const auto p = prefactor_bounds(paper_constants(), 0.45);
  EXPECT_NEAR(p.alpha_F.lo, 4.89028, 1e-5);
  EXPECT_NEAR(p.alpha_F.hi, 8.03971, 1e-5);
  EXPECT_NEAR(p.alpha_e.lo, 1.74557, 1e-5);
  EXPECT_NEAR(p.alpha_r.lo, 1.18172, 1e-5);
}

config::Case default_case_with(double net_weight) {
  auto c = config::default_case();
  c.popper.net_weight = net_weight;
  return c;
}

TEST(Predict, DefaultPopperJumps) {
  const auto p = predict(config::default_case(), paper_constants());
  // F* = (4.89 .. 8.04) * 0.32 N = 1.565 .. 2.573 N against mg = 0.48 N
  EXPECT_NEAR(p.F_star.lo, 1.56489, 1e-4);
  EXPECT_NEAR(p.F_star.hi, 2.57271, 1e-4);
  EXPECT_NEAR(p.jump_margin.lo, 3.26019, 1e-4);
  // H_l = 24.7906 - (4.36393 .. 1.74557) * 2 mm = 16.0627 .. 21.2994 mm
  EXPECT_NEAR(p.H_l.lo, 0.0160627, 1e-6);
  EXPECT_NEAR(p.H_l.hi, 0.0212994, 1e-6);
  // H_s = (4.89028 * 1.74557 .. 8.03971 * 4.36393) * 1.2e6 * 1.6e-11 / (0.48 * 0.03)
  EXPECT_NEAR(p.H_s.lo, 0.0113818, 1e-6);
  EXPECT_NEAR(p.H_s.hi, 0.0467796, 1e-6);
  EXPECT_NEAR(p.H.lo, p.H_l.lo + p.H_s.lo, 1e-15);
  // p_c of the default case and delta_p_j = 0.5 p_c
  EXPECT_NEAR(p.delta_p_j, 0.5 * 6896.09, 0.01);
  EXPECT_TRUE(p.outcome.jump);
  EXPECT_FALSE(p.outcome.snap);
  EXPECT_FALSE(p.outcome.no_snap);
  EXPECT_EQ(p.outcome.text(), "Jump");
}

TEST(Predict, HeavierPopperSnapsThenStopsSnapping) {
  // F*_hi = 2.573 N: above that weight no jump within the bounds.
  const auto snap = predict(default_case_with(3.0), paper_constants());
  EXPECT_FALSE(snap.outcome.jump);
  EXPECT_TRUE(snap.outcome.snap);
  EXPECT_EQ(snap.outcome.text(), "Snap");
  // Between F*_lo and F*_hi either may happen.
  const auto either = predict(default_case_with(2.0), paper_constants());
  EXPECT_EQ(either.outcome.text(), "Jump or Snap");
  EXPECT_FALSE(either.outcome.certain());
  // U = 0.1008 J (C = 3.046) against mg H_l with H_l = 16.1 .. 21.3 mm: certainly no snap above
  // 0.1008 / 0.0161 = 6.3 N
  const auto heavy = predict(default_case_with(10.0), paper_constants());
  EXPECT_EQ(heavy.outcome.text(), "No snap");
  EXPECT_LT(heavy.snap_margin.hi, 1.0);
}

TEST(Predict, AThickShellLeavesTheContactTheorysRangeAndSaysWhere) {
  EXPECT_TRUE(predict(config::default_case(), paper_constants()).beyond_range.empty());
  // h / R = 0.2: e* = alpha_e h reaches 4.36 * 6 = 26.2 mm, past the cap's depth of 24.8 mm.
  auto c = config::default_case();
  c.shell.h = 0.006;
  const auto p = predict(c, paper_constants());
  for (const char* part :
       {"e* = alpha_e h, reaches 26.2 mm", "cap's depth R (1 - cos phi) = 24.8 mm",
        "h / R below 0.189", "this case has 0.2"}) {
    EXPECT_NE(p.beyond_range.find(part), std::string::npos) << p.beyond_range;
  }
  EXPECT_EQ(p.outcome_text().rfind("unknown: the indentation at the onset", 0), 0U)
      << p.outcome_text();
  EXPECT_FALSE(p.outcome.jump || p.outcome.snap || p.outcome.no_snap);
  // What rests on H_l has no value at the end beyond the range; the rest is computed.
  EXPECT_TRUE(std::isnan(p.H_l.lo));
  EXPECT_NEAR(p.H_l.hi, 0.0247906 - 1.74557 * 0.006, 1e-6);
  EXPECT_TRUE(std::isnan(p.H.lo));
  EXPECT_TRUE(std::isnan(p.snap_margin.hi));
  EXPECT_TRUE(std::isfinite(p.snap_margin.lo));
  EXPECT_TRUE(std::isfinite(p.F_star.hi) && std::isfinite(p.H_s.hi) && std::isfinite(p.H.hi));
  // A shallow cap leaves it at any thickness the theory considers: both ends of H_l.
  c = config::default_case();
  c.shell.phi = 10.0 * std::numbers::pi / 180.0;
  const auto shallow = predict(c, paper_constants());
  EXPECT_FALSE(shallow.beyond_range.empty());
  EXPECT_TRUE(std::isnan(shallow.H_l.lo) && std::isnan(shallow.H_l.hi));
}

TEST(Predict, UsesGivenJumpPressure) {
  auto c = config::default_case();
  c.protocol.delta_p_j = 2500.0;
  EXPECT_DOUBLE_EQ(jump_pressure(c), 2500.0);
}

}  // namespace
}  // namespace snapjump::theory
