// The analysis on synthetic runs built from closed forms, whose characteristic quantities are
// worked out by hand below (not taken from this code).
//
// The reference run, sampled every 0.1 ms from 0 to 150 ms, R = 30 mm:
//   w(t) = 5 mm - c t with c = (5 - 0.9) mm / 20.05 ms: w / R = 0.03 (w = 0.9 mm) at t = 20.05 ms,
//          between the samples at 20.0 and 20.1 ms.
//   r(t) = 10 mm - 0.2 m/s t   -> r* = 10 - 0.2 * 20.05 = 5.99 mm
//   e(t) = 0.2 m/s t           -> e* = 4.01 mm
//   F(t) = 0.5 N before 21 ms, rising linearly to F* = 2 N at t0 = 22 ms, then the triangle
//          F* (1 - (t - t0) / tau), tau = 4 ms, down to 0 at 26 ms, and 0 after (free flight).
//          Default threshold 0.02 F* = 0.04 N (no noise): F = 0.04 N at t0 + tau (1 - 0.02)
//          = 25.92 ms, the launch; t* = 25.92 - 20.05 = 5.87 ms.
//   z(t) = v0 t up to t1 = 26 ms, then z(t1) + v0 (t - t1) - g (t - t1)^2 / 2, v0 = g * 80 ms, so
//          the apex is at t1 + 80 ms = 106 ms (a sample): H = v0 (26 + 40) ms = 66 ms * v0,
//          H_l = z(20.05 ms) = 20.05 ms * v0, H_s = 45.95 ms * v0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "measure/analysis.hpp"
#include "measure/time_series.hpp"

namespace snapjump::measure {
namespace {

constexpr double g = config::kStandardGravity;
constexpr double kR = 0.030;
constexpr double kDt = 1e-4;
constexpr double kOnset = 20.05e-3;
constexpr double kT0 = 22e-3;  // force peak
constexpr double kTau = 4e-3;
constexpr double kFStar = 2.0;
constexpr double kV0 = g * 0.080;
constexpr double kT1 = 26e-3;  // force reaches 0; flight starts

double w_ref(double t) {
  const double c = (5e-3 - 0.9e-3) / kOnset;
  return std::max(5e-3 - c * t, 0.0);
}

// The jump's force: rest, rise, triangle, flight.
double F_jump(double t) {
  if (t < 21e-3) return 0.5;
  if (t < kT0) return 0.5 + 1.5 * (t - 21e-3) / 1e-3;
  if (t < kT0 + kTau) return kFStar * (1.0 - (t - kT0) / kTau);
  return 0.0;
}

double z_jump(double t) {
  if (t <= kT1) return kV0 * t;
  const double s = t - kT1;
  return kV0 * kT1 + kV0 * s - 0.5 * g * s * s;
}

struct Spec {
  std::function<double(double)> F = F_jump;
  std::function<double(double)> z = z_jump;
  std::function<double(double)> w = w_ref;
  bool with_w = true;
  bool with_r_e = true;
  bool with_z = true;
  bool with_contact = false;
  bool with_dp = false;  // a delta_p column: 2 kPa falling by 10 Pa per ms unless dp says
  std::function<double(double)> dp = [](double t) { return 2000.0 - 1e4 * t; };
  double t_disk = 21e-3;  // contact column: ring before, disk from here unless contact says
  std::function<ContactState(double)> contact;
  double t_end = 150e-3;
};

TimeSeries make(const Spec& spec) {
  std::vector<std::string> names{"t", "F"};
  if (spec.with_z) names.emplace_back("z");
  if (spec.with_w) names.emplace_back("w");
  if (spec.with_r_e) {
    names.emplace_back("r");
    names.emplace_back("e");
  }
  if (spec.with_dp) names.emplace_back("delta_p");
  TimeSeries s(names, spec.with_contact);
  const auto n = static_cast<int>(std::lround(spec.t_end / kDt));
  std::vector<double> row;
  for (int i = 0; i <= n; ++i) {
    const double t = i * kDt;
    row = {t, spec.F(t)};
    if (spec.with_z) row.push_back(spec.z(t));
    if (spec.with_w) row.push_back(spec.w(t));
    if (spec.with_r_e) {
      row.push_back(10e-3 - 0.2 * t);
      row.push_back(0.2 * t);
    }
    if (spec.with_dp) row.push_back(spec.dp(t));
    if (spec.with_contact) {
      const auto state = spec.contact
                             ? spec.contact(t)
                             : (t >= spec.t_disk - 1e-12 ? ContactState::Disk : ContactState::Ring);
      s.add_row(row, state);
    } else {
      s.add_row(row);
    }
  }
  return s;
}

AnalysisOptions with_R() {
  AnalysisOptions o;
  o.R = kR;
  return o;
}

bool has_warning(const Analysis& a, std::string_view text) {
  for (const auto& w : a.warnings) {
    if (w.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(Analysis, Jump) {
  const auto a = analyze(make({}), with_R());
  ASSERT_TRUE(a.t_onset && a.F_star && a.t_launch && a.t_star && a.H && a.H_l && a.H_s);
  EXPECT_EQ(a.onset_source, OnsetSource::ApexGap);
  EXPECT_NEAR(*a.t_onset, 20.05e-3, 1e-12);
  EXPECT_NEAR(*a.r_star, 5.99e-3, 1e-12);
  EXPECT_NEAR(*a.e_star, 4.01e-3, 1e-12);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_NEAR(*a.t_F_star, 22e-3, 1e-12);
  EXPECT_NEAR(*a.force_threshold, 0.04, 1e-12);
  EXPECT_NEAR(*a.force_noise, 0.0, 1e-15);
  EXPECT_NEAR(*a.t_launch, 25.92e-3, 1e-10);
  EXPECT_NEAR(*a.t_star, 5.87e-3, 1e-10);
  // F rises linearly from 0.5 N at 21 ms to 2 N at 22 ms: a tenth of the rise at 21.1 ms.
  ASSERT_TRUE(a.t_force_rise && a.t_star_rise);
  EXPECT_NEAR(*a.t_force_rise, 21.1e-3, 1e-9);
  EXPECT_NEAR(*a.t_star_rise, 25.92e-3 - 21.1e-3, 1e-9);
  EXPECT_NEAR(*a.H, 66e-3 * kV0, 1e-12);
  EXPECT_NEAR(*a.H_l, 20.05e-3 * kV0, 1e-12);
  EXPECT_NEAR(*a.H_s, 45.95e-3 * kV0, 1e-12);
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  EXPECT_TRUE(a.warnings.empty()) << a.warnings.front();
  // Without a case there are no prefactors.
  EXPECT_FALSE(a.alpha_F);
}

// The force plate: a second-order low-pass, checked against its closed forms.
std::vector<double> times(double dt, double end) {
  std::vector<double> t;
  for (int k = 0; k * dt <= end; ++k) t.push_back(k * dt);
  return t;
}

TEST(ForcePlate, StepResponseOvershootsAsTheClosedFormSays) {
  const double f = 170.0, w = 2.0 * std::numbers::pi * f;
  const auto t = times(1e-6, 0.03);
  std::vector<double> F(t.size(), 1.0);
  F[0] = 0.0;  // a step of 1 N after the first microsecond
  for (const double zeta : {0.3, 0.7}) {
    const auto y = plate_response(t, F, f, zeta);
    const auto peak = std::max_element(y.begin(), y.end()) - y.begin();
    const double wd = w * std::sqrt(1.0 - zeta * zeta);
    EXPECT_NEAR(y[peak], 1.0 + std::exp(-std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta)),
                2e-4)
        << zeta;
    EXPECT_NEAR(t[peak], 1e-6 + std::numbers::pi / wd, 2e-5) << zeta;
    EXPECT_NEAR(y.back(), 1.0, 1e-4) << "static gain, " << zeta;
  }
}

TEST(ForcePlate, AShortImpulseComesOutAsThePlatesImpulseResponse) {
  // An impulse J = 1 mN s over 20 us: the plate's peak is J w exp(-zeta/sqrt(1 - zeta^2)
  // atan(sqrt(1 - zeta^2)/zeta)), whatever the pulse's own height (50 N).
  const double f = 170.0, w = 2.0 * std::numbers::pi * f, zeta = 0.7, J = 1e-3;
  const auto t = times(2e-6, 0.02);
  std::vector<double> F(t.size(), 0.0);
  for (std::size_t k = 1; k < t.size() && t[k] <= 20e-6 + 1e-12; ++k) F[k] = J / 20e-6;
  const auto y = plate_response(t, F, f, zeta);
  const double s = std::sqrt(1.0 - zeta * zeta);
  const double expected = J * w * std::exp(-zeta / s * std::atan(s / zeta));
  EXPECT_NEAR(*std::max_element(y.begin(), y.end()) / expected, 1.0, 0.02);
  EXPECT_THROW((void)plate_response(t, F, 0.0, zeta), SeriesError);
  EXPECT_THROW((void)plate_response(t, F, f, -1.0), SeriesError);
}

TEST(Analysis, ForceThroughThePlateIsReportedBeside) {
  auto o = with_R();
  o.plate_frequency = kPaperPlateFrequency;
  const auto a = analyze(make({}), o);
  ASSERT_TRUE(a.F_star && a.F_star_plate);
  // The synthetic snap's 2 N peak lasts about 4 ms, shorter than the plate's 5.9 ms period.
  EXPECT_GT(*a.F_star_plate, 0.3);
  EXPECT_LT(*a.F_star_plate, 1.2 * *a.F_star);
  EXPECT_FALSE(analyze(make({}), with_R()).F_star_plate);  // off unless asked
}

// A gradual eversion: the force rises and peaks before the apex criterion fires. F* is the snap's
// peak all the same, and the rise's start comes before the onset.
TEST(Analysis, ForcePeakBeforeTheApexOnset) {
  Spec spec;
  // Rest at 0.5 N, a linear rise from 15 ms to a 2.5 N peak at 19 ms, then down to 0 at 24 ms
  // (the onset is at 20.05 ms, after the peak).
  spec.F = [](double t) {
    if (t < 15e-3) return 0.5;
    if (t < 19e-3) return 0.5 + 2.0 * (t - 15e-3) / 4e-3;
    if (t < 24e-3) return 2.5 * (1.0 - (t - 19e-3) / 5e-3);
    return 0.0;
  };
  const auto a = analyze(make(spec), with_R());
  ASSERT_TRUE(a.F_star && a.t_F_star && a.t_force_rise && a.t_launch);
  EXPECT_NEAR(*a.F_star, 2.5, 1e-12);
  EXPECT_NEAR(*a.t_F_star, 19e-3, 1e-12);
  EXPECT_NEAR(*a.t_force_rise, 15.4e-3, 1e-9);  // 0.5 + 0.1 * 2 N = 0.7 N
  EXPECT_LT(*a.t_force_rise, *a.t_onset);
  // Launch where F falls below 0.02 F* = 0.05 N: 19 ms + 5 ms * 0.98.
  EXPECT_NEAR(*a.t_launch, 23.9e-3, 1e-9);
}

// e is the indentation (the theory's plane displacement); e_apex, when given, is reported beside.
TEST(Analysis, IndentationAndApexDisplacement) {
  TimeSeries s({"t", "F", "w", "e", "e_apex"}, false);
  for (int i = 0; i <= 400; ++i) {
    const double t = i * kDt;
    const double w = w_ref(t), e = 0.1 * t;
    s.add_row({t, F_jump(t), w, e, e + w});
  }
  const auto a = analyze(s, with_R());
  ASSERT_TRUE(a.e_star && a.e_apex_star);
  EXPECT_NEAR(*a.e_star, 0.1 * kOnset, 1e-12);
  EXPECT_NEAR(*a.e_apex_star, 0.1 * kOnset + 0.9e-3, 1e-12);  // w = 0.03 R at the onset
}

TEST(Analysis, ExplicitThreshold) {
  auto o = with_R();
  o.force_threshold = 0.2;  // 0.1 F*: F = 0.2 N at 22 + 4 * 0.9 = 25.6 ms
  const auto a = analyze(make({}), o);
  ASSERT_TRUE(a.t_launch);
  EXPECT_NEAR(*a.t_launch, 25.6e-3, 1e-10);
  EXPECT_NEAR(*a.t_star, 25.6e-3 - 20.05e-3, 1e-10);
}

TEST(Analysis, SnapWhenForceSettlesOnTheWeight) {
  // After the peak F falls to the weight 0.5 N and stays: the popper snapped but did not leave.
  Spec spec;
  spec.F = [](double t) {
    if (t < kT0) return F_jump(t);
    if (t < kT1) return 2.0 - 1.5 * (t - kT0) / kTau;
    return 0.5;
  };
  spec.z = [](double t) { return kV0 * std::min(t, kT1); };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Snap);
  ASSERT_TRUE(a.t_onset && a.F_star && a.H && a.H_l && a.H_s);
  EXPECT_NEAR(*a.t_onset, 20.05e-3, 1e-12);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_FALSE(a.t_launch);
  EXPECT_FALSE(a.t_star);
  EXPECT_NEAR(*a.H, 26e-3 * kV0, 1e-12);
  EXPECT_NEAR(*a.H_l, 20.05e-3 * kV0, 1e-12);
  EXPECT_NEAR(*a.H_s, 5.95e-3 * kV0, 1e-12);
}

TEST(Analysis, ShortDipIsNotALaunch) {
  // F drops to 0 from 26 to 28 ms (2 ms < 5 ms) and comes back to 0.5 N: Snap.
  Spec spec;
  spec.F = [](double t) { return t < 28e-3 ? F_jump(t) : 0.5; };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Snap);
  EXPECT_FALSE(a.t_launch);
}

TEST(Analysis, LaunchAfterAShortDip) {
  // The dip of 25.92..28 ms is rejected; from 40 ms F falls linearly from 0.5 N to 0 at 41 ms and
  // stays there: F = 0.04 N at 40 + 0.92 = 40.92 ms.
  Spec spec;
  spec.F = [](double t) {
    if (t < 28e-3) return F_jump(t);
    if (t < 40e-3) return 0.5;
    if (t < 41e-3) return 0.5 * (1.0 - (t - 40e-3) / 1e-3);
    return 0.0;
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(a.t_launch);
  EXPECT_NEAR(*a.t_launch, 40.92e-3, 1e-10);
  EXPECT_NEAR(*a.t_star, 40.92e-3 - 20.05e-3, 1e-10);
}

TEST(Analysis, ContactLostWhileComingDownIsNotALaunch) {
  // After the snap the popper settles on the plate (F = weight), then from 60 ms the container
  // sinks while F falls to 0 and stays there: the shell is pulled off the plate from above, the
  // popper never leaves it going up. Snap, with a note saying why.
  Spec spec;
  spec.F = [](double t) {
    if (t < 28e-3) return F_jump(t);
    if (t < 60e-3) return 0.5;
    if (t < 61e-3) return 0.5 * (1.0 - (t - 60e-3) / 1e-3);
    return 0.0;
  };
  spec.z = [](double t) {
    const double top = kV0 * kT1;
    if (t <= kT1) return kV0 * t;
    if (t <= 60e-3) return top;
    return top - 0.05 * (t - 60e-3);  // coming down at 5 cm/s
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Snap);
  EXPECT_FALSE(a.t_launch);
  EXPECT_TRUE(has_warning(a, "while the container is not rising")) << a.warnings.size();
  // The same force record with the container rising from 60 ms is a jump.
  spec.z = [](double t) {
    if (t <= kT1) return kV0 * t;
    if (t <= 60e-3) return kV0 * kT1;
    return kV0 * kT1 + 0.05 * (t - 60e-3);
  };
  const auto b = analyze(make(spec), with_R());
  EXPECT_EQ(b.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(b.t_launch);
  EXPECT_NEAR(*b.t_launch, 60.92e-3, 1e-10);
}

TEST(Analysis, LandingAfterTheShellIsPulledBackInIsNotTheSnap) {
  // A snap without a launch (F settles on the weight); from 60 ms the shell is pulled back in (w
  // above the onset level while the plate still pushes), the popper drops onto it (3 N at 70 ms)
  // and bounces off for 10 ms going up. Neither that peak nor that hop belongs to the snap.
  Spec spec;
  spec.F = [](double t) {
    if (t < 28e-3) return F_jump(t);
    if (t < 68e-3) return 0.5;
    if (t < 70e-3) return 0.5 + 2.5 * (t - 68e-3) / 2e-3;
    if (t < 72e-3) return 3.0 * (1.0 - (t - 70e-3) / 2e-3);
    if (t < 82e-3) return 0.0;
    return 0.5;
  };
  spec.w = [](double t) { return t < 60e-3 ? w_ref(t) : 2e-3; };  // w / R = 0.067 from 60 ms
  spec.z = [](double t) { return t < 72e-3 ? kV0 * std::min(t, kT1) : kV0 * kT1 + (t - 72e-3); };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Snap);
  ASSERT_TRUE(a.F_star);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_FALSE(a.t_launch);
  EXPECT_TRUE(has_warning(a, "back on a ring contact at t = 0.06 s")) << a.warnings.size();
}

TEST(Analysis, AFlickerOfTheApexAboutTheOnsetLevelIsNoReturnToARing) {
  // w crosses the onset level, is above it again by a tenth for 0.5 ms while the plate pushes
  // (the apex settling on a coarse mesh), and stays below from then on: the popper then
  // launches. That is the jump of Analysis.Jump, not a snap ended by a ring contact.
  Spec spec;
  spec.w = [](double t) { return t >= 20.5e-3 && t < 21e-3 ? 0.99e-3 : w_ref(t); };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(a.F_star && a.t_launch);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_FALSE(has_warning(a, "back on a ring contact")) << a.warnings.size();
}

TEST(Analysis, NoSnapWhenApexStaysAway) {
  Spec spec;
  spec.w = [](double) { return 1.0e-3; };  // w / R = 0.0333 > 0.03 throughout
  spec.F = [](double) { return 0.5; };
  spec.z = [](double t) { return 1e-3 * std::sin(100.0 * t); };  // max 1 mm (t = 15.7 ms)
  // Without a delta_p column nothing says the suction was gone before the record ended.
  const auto open = analyze(make(spec), with_R());
  EXPECT_FALSE(open.outcome);
  EXPECT_NE(open.undetermined.find("without a delta_p column"), std::string::npos)
      << open.undetermined;
  AnalysisOptions complete = with_R();
  complete.complete = true;  // the user says the record covers the experiment
  const auto a = analyze(make(spec), complete);
  EXPECT_EQ(a.outcome, theory::Outcome::NoSnap);
  EXPECT_FALSE(a.t_onset);
  EXPECT_FALSE(a.r_star);
  EXPECT_FALSE(a.F_star);
  EXPECT_FALSE(a.H_l);
  ASSERT_TRUE(a.H);
  EXPECT_NEAR(*a.H, 1e-3, 1e-9);  // sampled within 0.05 ms of the top: error < 1.3e-11 m
}

TEST(Analysis, OnsetFromContactWhenNoW) {
  Spec spec;
  spec.with_w = false;
  spec.with_contact = true;  // disk from the sample at 21 ms
  const auto a = analyze(make(spec));
  EXPECT_EQ(a.onset_source, OnsetSource::ContactDisk);
  ASSERT_TRUE(a.t_onset && a.t_star && a.r_star);
  EXPECT_NEAR(*a.t_onset, 21e-3, 1e-12);
  EXPECT_NEAR(*a.r_star, 10e-3 - 0.2 * 21e-3, 1e-12);
  EXPECT_NEAR(*a.t_star, 25.92e-3 - 21e-3, 1e-10);
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  EXPECT_TRUE(has_warning(a, "no w column"));
}

TEST(Analysis, WithoutRTheWColumnIsNotUsed) {
  Spec spec;
  spec.with_contact = true;
  const auto a = analyze(make(spec));  // no R, no case
  EXPECT_EQ(a.onset_source, OnsetSource::ContactDisk);
  EXPECT_TRUE(has_warning(a, "no shell radius R"));
}

// Without w and contact the snap is read from the force alone: F* and the launch as with w, t*
// from the force's rise (no onset), the flight's rise from z.
TEST(Analysis, FromTheForceAloneWithoutWOrContact) {
  Spec spec;
  spec.with_w = false;
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.basis, Basis::ForceOnly);
  EXPECT_EQ(a.outcome, theory::Outcome::Jump) << a.undetermined;
  EXPECT_FALSE(a.t_onset || a.t_star || a.r_star);
  EXPECT_TRUE(has_warning(a, "the snap is read from the force alone"));
  ASSERT_TRUE(a.F_star && a.t_launch && a.t_star_rise && a.F_rest && a.H && a.H_flight);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_NEAR(*a.F_rest, 0.5, 1e-12);  // the median before the rise
  EXPECT_NEAR(*a.t_launch, 25.92e-3, 1e-10);
  EXPECT_NEAR(*a.t_star_rise, 25.92e-3 - 21.1e-3, 1e-9);
  EXPECT_NEAR(*a.H, 66e-3 * kV0, 1e-12);  // heights need no onset
  // The flight's rise above the launch: z at the launch (25.92 ms) to the apex at 106 ms.
  EXPECT_NEAR(*a.H_flight, 66e-3 * kV0 - z_jump(25.92e-3), 1e-9);
  EXPECT_EQ(a.source("t_star_rise"), "t, F, z");
  EXPECT_EQ(a.source("F_star"), "t, F");
}

TEST(Analysis, OnsetAtFirstSample) {
  Spec spec;
  spec.w = [](double) { return 0.5e-3; };
  const auto a = analyze(make(spec), with_R());
  ASSERT_TRUE(a.t_onset);
  EXPECT_EQ(*a.t_onset, 0.0);
  EXPECT_TRUE(has_warning(a, "already at the first sample"));
}

TEST(Analysis, RecordEndingSoonAfterLaunch) {
  Spec spec;
  spec.t_end = 27e-3;  // 1.08 ms after the launch at 25.92 ms
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(a.t_launch);
  EXPECT_NEAR(*a.t_launch, 25.92e-3, 1e-10);
  EXPECT_TRUE(has_warning(a, "the record ends"));
  EXPECT_TRUE(has_warning(a, "z is highest at the last sample"));
}

// The suction left at the onset, read off the delta_p column when there is one.
TEST(Analysis, PressureDifferenceAtTheOnset) {
  Spec spec;
  EXPECT_FALSE(analyze(make(spec), with_R()).delta_p_onset);
  spec.with_dp = true;
  const auto a = analyze(make(spec), with_R());
  ASSERT_TRUE(a.t_onset);
  ASSERT_TRUE(a.delta_p_onset);
  EXPECT_NEAR(*a.delta_p_onset, 2000.0 - 1e4 * kOnset, 1e-6);
}

// A record that stops at the top of the flight (as `snapjump run` does), its last sample the
// highest: H is the jump's height, not a lower bound.
TEST(Analysis, RecordEndingAtTheTopOfTheFlight) {
  Spec spec;
  spec.t_end = kT1 + kV0 / g;  // the apex of z_jump
  const auto a = analyze(make(spec), with_R());
  ASSERT_TRUE(a.H);
  EXPECT_NEAR(*a.H, kV0 * kT1 + 0.5 * kV0 * kV0 / g, 1e-9);
  EXPECT_FALSE(has_warning(a, "z is highest at the last sample"));
}

// Heights with 10 um of noise (a laser sensor), the record cut at the top of the flight and
// half-way up: at the top the curvature is lost in the noise, so the warning stays (H may be low
// by the noise only); half-way up it must stay too.
TEST(Analysis, NoisyHeightKeepsTheLowerBoundWarning) {
  std::mt19937 gen(7u);
  const auto uniform = [&] { return (static_cast<double>(gen()) + 0.5) / 4294967296.0; };
  std::vector<double> noise;
  for (int i = 0; i <= 1100; ++i) {
    noise.push_back(10e-6 * std::sqrt(-2.0 * std::log(uniform())) *
                    std::cos(2.0 * std::numbers::pi * uniform()));
  }
  Spec spec;
  spec.z = [&](double t) {
    return z_jump(t) + noise[static_cast<std::size_t>(std::lround(t / kDt))];
  };
  for (const double t_end : {60e-3, kT1 + kV0 / g}) {
    spec.t_end = t_end;
    const auto a = analyze(make(spec), with_R());
    ASSERT_TRUE(a.H);
    const auto z = make(spec).column("z");
    if (std::max_element(z.begin(), z.end()) == z.end() - 1) {
      EXPECT_TRUE(has_warning(a, "z is highest at the last sample")) << t_end;
    }
  }
}

// Gaussian noise of standard deviation 1% F* (Box-Muller on std::mt19937, which the standard
// specifies bit for bit, so the series is the same everywhere).
TEST(Analysis, NoiseRobustness) {
  std::mt19937 gen(20240611u);
  const auto uniform = [&] { return (static_cast<double>(gen()) + 0.5) / 4294967296.0; };
  const double sigma = 0.01 * kFStar;
  std::vector<double> noise;
  for (int i = 0; i <= 1500; ++i) {
    noise.push_back(sigma * std::sqrt(-2.0 * std::log(uniform())) *
                    std::cos(2.0 * std::numbers::pi * uniform()));
  }
  Spec spec;
  spec.F = [&](double t) {
    return F_jump(t) + noise[static_cast<std::size_t>(std::lround(t / kDt))];
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(a.force_noise && a.force_threshold && a.t_launch && a.F_star);
  EXPECT_NEAR(*a.force_noise, sigma, 0.25 * sigma);  // from ~150 samples
  // Threshold 4 sigma = 0.08 N (above 0.02 F*): F* (1 - (t - t0)/tau) = 0.08 at
  // 22 + 4 (1 - 0.04) = 25.84 ms. F falls 0.05 N per sample, so noise moves it by about a sample.
  EXPECT_NEAR(*a.force_threshold, 4 * sigma, 4 * 0.25 * sigma);
  const double expected = kT0 + kTau * (1.0 - *a.force_threshold / kFStar);
  EXPECT_NEAR(*a.t_launch, expected, 3 * kDt);
  EXPECT_NEAR(*a.t_launch, 25.84e-3, 4 * kDt);
  EXPECT_NEAR(*a.F_star, kFStar, 4 * sigma);
  EXPECT_NEAR(*a.t_onset, 20.05e-3, 1e-12);  // w is clean
}

config::Case paper_case(double net_weight) {
  config::Case c;
  c.shell.R = 0.030;
  c.shell.h = 0.002;
  c.shell.phi = 80.0 * std::numbers::pi / 180.0;
  c.material.E = 1.2e6;
  c.material.nu = 0.5;
  c.popper.net_weight = net_weight;
  c.popper.mass = 0.300;
  return c;
}

TEST(Analysis, PrefactorsWithCase) {
  const auto c = paper_case(0.48);
  const auto a = analyze(make({}), {}, &c);  // R from the case
  ASSERT_TRUE(a.R);
  EXPECT_EQ(*a.R, 0.030);
  ASSERT_TRUE(a.alpha_r && a.alpha_e && a.alpha_F && a.alpha_t && a.H_s_scaled);
  // sqrt(h R) = sqrt(6e-5 m^2) = 7.745967 mm
  EXPECT_NEAR(*a.alpha_r, 5.99e-3 / 7.7459666924148e-3, 1e-9);
  EXPECT_NEAR(*a.alpha_e, 4.01 / 2.0, 1e-9);
  // E h^3 / R = 1.2e6 * 8e-9 / 0.03 = 0.32 N
  EXPECT_NEAR(*a.alpha_F, 2.0 / 0.32, 1e-9);
  // m = popper + counterweight = 0.3 kg + (0.3 kg - 0.48 N / g) = 0.551054 kg:
  // sqrt(m R / (E h^2)) = sqrt(0.551054 * 0.03 / (1.2e6 * 4e-6)) = 58.6860 ms
  EXPECT_NEAR(*a.alpha_t, 5.87 / 58.6860, 1e-5);
  // the popper alone: sqrt(0.3 * 0.03 / 4.8) = 43.3013 ms
  ASSERT_TRUE(a.alpha_t_own);
  EXPECT_NEAR(*a.alpha_t_own, 5.87 / 43.3013, 1e-5);
  // m = mg / g = 0.0489464 kg: sqrt(0.0489464 * 0.03 / 4.8) = 17.4904 ms
  ASSERT_TRUE(a.alpha_t_net);
  EXPECT_NEAR(*a.alpha_t_net, 5.87 / 17.4904, 1e-5);
  // E h^4 / (m g R) = 1.2e6 * 1.6e-11 / (0.48 * 0.03) = 1.3333 mm
  EXPECT_NEAR(*a.H_s_scaled, 45.95e-3 * kV0 / (1.92e-5 / 0.0144), 1e-9);
  EXPECT_NEAR(*a.F_star_over_mg, 2.0 / 0.48, 1e-12);
  EXPECT_TRUE(a.warnings.empty());
}

TEST(Analysis, SuspiciousJumpBelowWeight) {
  const auto c = paper_case(3.0);  // mg = 3 N > F* = 2 N
  const auto a = analyze(make({}), {}, &c);
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  EXPECT_TRUE(has_warning(a, "suspicious Jump"));
}

TEST(Analysis, BadInput) {
  TimeSeries no_force({"t", "z"});
  no_force.add_row({0.0, 0.0});
  EXPECT_THROW((void)analyze(no_force, with_R()), SeriesError);
  AnalysisOptions bad;
  bad.R = -1.0;
  EXPECT_THROW((void)analyze(make({}), bad), SeriesError);
  // A header alone: nothing to analyse is an error, not an outcome.
  try {
    (void)analyze(TimeSeries({"t", "F"}), with_R());
    ADD_FAILURE() << "no error for a series without rows";
  } catch (const SeriesError& e) {
    EXPECT_NE(std::string(e.what()).find("no rows"), std::string::npos) << e.what();
  }
  AnalysisOptions negative_wait = with_R();
  negative_wait.settle_time = -1.0;
  EXPECT_THROW((void)analyze(make({}), negative_wait), SeriesError);
}

TEST(Analysis, Json) {
  const auto c = paper_case(0.48);
  Spec spec;
  spec.with_r_e = false;
  const auto j = to_json(analyze(make(spec), {}, &c));
  EXPECT_EQ(j["units"], "SI");
  EXPECT_EQ(j["outcome"], "Jump");
  EXPECT_EQ(j["onset_source"], "w/R");
  EXPECT_NEAR(j["quantities"]["t_star"]["value"].get<double>(), 5.87e-3, 1e-10);
  EXPECT_EQ(j["quantities"]["t_star"]["unit"], "s");
  EXPECT_EQ(j["quantities"]["F_star"]["unit"], "N");
  EXPECT_TRUE(j["quantities"]["r_star"]["value"].is_null());
  EXPECT_TRUE(j["quantities"]["alpha_r"]["value"].is_null());
  EXPECT_NEAR(j["quantities"]["alpha_F"]["value"].get<double>(), 6.25, 1e-9);
  EXPECT_TRUE(j["warnings"].is_array());
  std::ostringstream out;
  write_json(out, analyze(make(spec), {}, &c));
  EXPECT_EQ(nlohmann::json::parse(out.str()), j);
  EXPECT_EQ(j["basis"], "transition");
  EXPECT_EQ(j["quantities"]["t_star"]["source"], "t, w, F, z");
  EXPECT_EQ(j["quantities"]["alpha_F"]["source"], "t, w, F; case E, h, R");
  EXPECT_TRUE(j["quantities"]["r_star"]["source"].is_null());
}

// Every quantity an analysis gives says where it came from, and every source is a quantity of
// the one table, on records of every kind.
TEST(Analysis, EveryQuantitySaysItsSource) {
  const auto c = paper_case(0.48);
  Spec no_w;
  no_w.with_w = false;
  Spec contact;
  contact.with_w = false;
  contact.with_contact = true;
  for (const auto& spec : {Spec{}, no_w, contact}) {
    const auto a = analyze(make(spec), with_R(), &c);
    for (const auto& q : quantity_table()) {
      EXPECT_EQ((a.*q.field).has_value(), !a.source(q.key).empty()) << q.key;
    }
    for (const auto& [key, source] : a.sources) {
      EXPECT_NE(find_quantity(key), nullptr) << key;
    }
  }
  for (const auto key : record_table_keys()) EXPECT_NE(find_quantity(key), nullptr) << key;
}

// A measured CSV goes through the same analysis: the reference run written in ms / mm / mN.
TEST(Analysis, FromCsvInOtherUnits) {
  const auto s = make({});
  std::ostringstream csv;
  csv << "# force plate export\nt [ms],F [mN],z [mm],w [mm],r [mm],e [mm]\n";
  for (std::size_t i = 0; i < s.size(); ++i) {
    csv << 1e3 * s.time()[i] << ',' << 1e3 * s.column("F")[i] << ',' << 1e3 * s.column("z")[i]
        << ',' << 1e3 * s.column("w")[i] << ',' << 1e3 * s.column("r")[i] << ','
        << 1e3 * s.column("e")[i] << '\n';
  }
  std::istringstream in(csv.str());
  const units::UnitParser parser;
  const auto read = TimeSeries::read_csv(in, "plate.csv", parser);
  const auto a = analyze(read, with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  // Six significant digits in the text: microsecond-level agreement.
  EXPECT_NEAR(*a.t_onset, 20.05e-3, 1e-7);
  EXPECT_NEAR(*a.t_star, 5.87e-3, 1e-6);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-6);
  EXPECT_NEAR(*a.H, 66e-3 * kV0, 1e-7);
}

// --- Outcomes the record cannot settle, and records that go on past the landing ---------------

// The reference jump, then a landing at 120 ms: F rises to 5 N within 1 ms (harder than the
// snap's 2 N), falls back to the weight 0.5 N within 2 ms and stays there; z comes back down to
// the place it left from. The flight's top is at 106 ms (as the reference), H = 66 ms * v0.
constexpr double kLand = 120e-3;
double F_landing(double t) {
  if (t < kLand) return F_jump(t);
  if (t < kLand + 1e-3) return 5.0 * (t - kLand) / 1e-3;
  if (t < kLand + 3e-3) return 5.0 - 4.5 * (t - kLand - 1e-3) / 2e-3;
  return 0.5;
}
double z_landing(double t) { return t < kLand ? z_jump(t) : z_jump(kLand); }

TEST(Analysis, AFlightEndsAtTheLanding) {
  Spec spec;
  spec.F = F_landing;
  spec.z = z_landing;
  spec.t_end = 200e-3;
  // (a) With the apex gap w: the landing's 5 N is not F*, and the popper jumped.
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(a.F_star && a.t_launch && a.H && a.t_landing);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_NEAR(*a.t_launch, 25.92e-3, 1e-10);
  EXPECT_NEAR(*a.H, 66e-3 * kV0, 1e-12);
  EXPECT_NEAR(*a.t_landing, kLand + kDt, kDt + 1e-12);  // first sample above 0.04 N
  // (b) Without w: the contact column (disk from 21 ms, none in flight, disk again on landing).
  spec.with_w = false;
  spec.with_contact = true;
  spec.contact = [](double t) {
    if (t < 21e-3) return ContactState::Ring;
    if (t < 26e-3 || t >= kLand) return ContactState::Disk;
    return ContactState::None;
  };
  const auto b = analyze(make(spec), with_R());
  EXPECT_EQ(b.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(b.F_star && b.t_launch);
  EXPECT_NEAR(*b.F_star, 2.0, 1e-12);
  EXPECT_NEAR(*b.t_launch, 25.92e-3, 1e-10);
  // (c) Neither w nor contact nor z: the force alone. The first launch still ends the snap, the
  // landing's 5 N is still not F*, and the flight to the landing says it jumped.
  spec.with_contact = false;
  spec.with_z = false;
  const auto c = analyze(make(spec), with_R());
  EXPECT_EQ(c.basis, Basis::ForceOnly);
  EXPECT_EQ(c.outcome, theory::Outcome::Jump) << c.undetermined;
  ASSERT_TRUE(c.F_star && c.t_launch && c.t_landing && c.flight_time);
  EXPECT_NEAR(*c.F_star, 2.0, 1e-12);
  EXPECT_NEAR(*c.t_launch, 25.92e-3, 1e-10);
  EXPECT_NEAR(*c.flight_time, *c.t_landing - *c.t_launch, 1e-12);
  EXPECT_FALSE(c.t_star);
  EXPECT_EQ(c.source("F_star"), "t, F");
}

TEST(Analysis, ContactLostEndsTheSnapWhenThePlateRingsOn) {
  // The plate rings at 170 Hz after the launch (amplitude 0.3 N, decaying in 20 ms), so F does
  // not stay below the threshold; the contact column says the shell left at 26 ms.
  Spec spec;
  spec.with_w = false;
  spec.with_contact = true;
  spec.F = [](double t) {
    if (t < kT0 + kTau) return F_jump(t);
    const double s = t - kT0 - kTau;
    return 0.3 * std::exp(-s / 20e-3) * std::sin(2.0 * std::numbers::pi * 170.0 * s);
  };
  spec.contact = [](double t) {
    if (t < 21e-3) return ContactState::Ring;
    return t < 26e-3 ? ContactState::Disk : ContactState::None;
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(a.t_launch && a.F_star);
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_GE(*a.t_launch, 25.0e-3);
  EXPECT_LE(*a.t_launch, 26.0e-3 + 1e-12);
}

TEST(Analysis, ARecordCutInTheRingStageIsUndetermined) {
  Spec spec;
  spec.with_dp = true;
  spec.t_end = 15e-3;  // before the onset at 20.05 ms; delta_p still 1.85 kPa
  const auto a = analyze(make(spec), with_R());
  EXPECT_FALSE(a.outcome);
  EXPECT_EQ(outcome_text(a.outcome), "undetermined");
  EXPECT_NE(a.undetermined.find("suction"), std::string::npos) << a.undetermined;
  // Told that the record is complete, the analysis calls it No snap.
  AnalysisOptions complete = with_R();
  complete.complete = true;
  EXPECT_EQ(analyze(make(spec), complete).outcome, theory::Outcome::NoSnap);
}

TEST(Analysis, NoSnapOnceTheSuctionHasBeenGoneForTheSettleTime) {
  Spec spec;
  spec.w = [](double) { return 1.0e-3; };  // the apex never comes down
  spec.F = [](double) { return 0.5; };
  spec.with_dp = true;
  spec.dp = [](double t) { return 2000.0 - 4e4 * t; };  // zero at 50 ms
  spec.t_end = 150e-3;                                  // 100 ms after: settled
  EXPECT_EQ(analyze(make(spec), with_R()).outcome, theory::Outcome::NoSnap);
  spec.t_end = 80e-3;  // 30 ms after, less than the 50 ms settle time
  const auto a = analyze(make(spec), with_R());
  EXPECT_FALSE(a.outcome);
  EXPECT_NE(a.undetermined.find("after delta_p reached zero"), std::string::npos) << a.undetermined;
}

TEST(Analysis, ARecordCutDuringTheSnapIsUndetermined) {
  Spec spec;
  spec.t_end = 24e-3;  // after the peak at 22 ms, F still 1 N
  const auto a = analyze(make(spec), with_R());
  EXPECT_FALSE(a.outcome);
  ASSERT_TRUE(a.t_onset && a.F_star);  // what the record holds is still reported
  EXPECT_NEAR(*a.F_star, 2.0, 1e-12);
  EXPECT_NE(a.undetermined.find("after the force peak"), std::string::npos) << a.undetermined;
  // A simulated run paused at 20 ms (before the onset, suction left): undetermined too.
  spec.t_end = 20e-3;
  spec.with_dp = true;
  EXPECT_FALSE(analyze(make(spec), with_R()).outcome);
}

TEST(Analysis, ATaredPlateIsNamedAndItsOffsetCanBePutBack) {
  // The plate zeroed with the popper standing on it: F reads 0 at rest and -0.5 N in flight.
  Spec spec;
  spec.F = [](double t) { return F_jump(t) - 0.5; };
  const auto a = analyze(make(spec), with_R());
  EXPECT_FALSE(a.outcome);
  EXPECT_TRUE(has_warning(a, "looks tared")) << a.warnings.size();
  AnalysisOptions fixed = with_R();
  fixed.force_offset = 0.5;
  const auto b = analyze(make(spec), fixed);
  EXPECT_EQ(b.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(b.F_star && b.t_launch);
  EXPECT_NEAR(*b.F_star, 2.0, 1e-12);
  EXPECT_NEAR(*b.t_launch, 25.92e-3, 1e-10);
  EXPECT_FALSE(has_warning(b, "looks tared"));
}

TEST(Analysis, AFlightWithTheOnsetInTheAirIsThrown) {
  // Thrown up by the inflow at 10 ms while the apex is still 5 mm up (v0 = g 45 ms, landing at
  // 100 ms, top v0^2 / 2g = 9.93 mm); in the air the shell everts (w = z + 1.0 mm, sagging to
  // 0.8 mm), so w / R < 0.03 (w < 0.9 mm) only just before the landing, where a 3 N impact
  // follows: the contact transition never happened on the plate.
  constexpr double v0 = g * 45e-3;
  const auto z_of = [v0](double t) {
    const double s = t - 10e-3;
    return t < 10e-3 || t > 100e-3 ? 0.0 : v0 * s - 0.5 * g * s * s;
  };
  Spec spec;
  spec.F = [](double t) {
    if (t < 10e-3) return 0.5;
    if (t < 100e-3) return 0.0;
    if (t < 102e-3) return 3.0;
    return 0.5;
  };
  spec.z = z_of;
  spec.w = [z_of](double t) {
    return t < 10e-3 ? 5e-3 : 1.0e-3 - 0.2e-3 * (t - 10e-3) / 90e-3 + z_of(t);
  };
  spec.t_end = 200e-3;
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Thrown)
      << a.undetermined << " onset " << a.t_onset.value_or(-1) << " launch "
      << a.t_launch.value_or(-1) << " F* " << a.F_star.value_or(-1) << " at "
      << a.t_F_star.value_or(-1);
  EXPECT_TRUE(a.undetermined.empty()) << a.undetermined;
  EXPECT_FALSE(a.t_star);
  ASSERT_TRUE(a.t_lift_off && a.flight_rise);
  EXPECT_NEAR(*a.t_lift_off, 10e-3, kDt);
  EXPECT_NEAR(*a.flight_rise, 0.5 * v0 * v0 / g, 1e-6);  // the top sampled within 0.05 ms
  EXPECT_TRUE(has_warning(a, "in the air")) << a.warnings.size();
  // Without z nothing shows the flight: the launch before the onset leaves it undetermined.
  spec.with_z = false;
  const auto b = analyze(make(spec), with_R());
  EXPECT_FALSE(b.outcome);
  EXPECT_NE(b.undetermined.find("before the onset"), std::string::npos) << b.undetermined;
}

TEST(Analysis, APeakRightAfterAFailedCrossingIsStillThePeak) {
  // 1 N, a dip to 0.01 N for 0.3 ms (not a flight), a single 5 N sample, then 3 N until 30 ms,
  // a fall to 0 at 34 ms and a flight: F* is the 5 N sample.
  Spec spec;
  spec.F = [](double t) {
    if (t < 21e-3) return 0.5;
    if (t < 22e-3) return 0.5 + 0.5 * (t - 21e-3) / 1e-3;
    if (t < 22.35e-3) return 0.01;
    if (t < 22.45e-3) return 5.0;
    if (t < 30e-3) return 3.0;
    if (t < 34e-3) return 3.0 * (1.0 - (t - 30e-3) / 4e-3);
    return 0.0;
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump);
  ASSERT_TRUE(a.F_star);
  EXPECT_NEAR(*a.F_star, 5.0, 1e-12);
}

TEST(Analysis, ARecordThatStartsBeforeTheSuctionIsNotNoSnapWhileItHolds) {
  // delta_p 0 at the start, up to 5 kPa by 50 ms and held; the apex stays away.
  Spec spec;
  spec.w = [](double) { return 1.0e-3; };
  spec.F = [](double) { return 0.5; };
  spec.with_dp = true;
  spec.dp = [](double t) { return 5000.0 * std::min(1.0, t / 50e-3); };
  const auto a = analyze(make(spec), with_R());
  EXPECT_FALSE(a.outcome) << outcome_text(a.outcome);
  EXPECT_NE(a.undetermined.find("suction still holding"), std::string::npos) << a.undetermined;
}

TEST(Analysis, OneSampleWithoutContactAtTheEndIsNoFlight) {
  // The contact column loses the shell on the last row only (a camera losing track).
  Spec spec;
  spec.with_w = false;
  spec.with_contact = true;
  spec.F = [](double t) { return t < 28e-3 ? F_jump(t) : 0.5; };  // settles on the weight
  spec.contact = [](double t) {
    if (t < 21e-3) return ContactState::Ring;
    return t > 149.95e-3 ? ContactState::None : ContactState::Disk;
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Snap);
  EXPECT_FALSE(a.t_launch);
}

TEST(Analysis, ABareNumberForRIsNamed) {
  AnalysisOptions o;
  o.R = 30.0;  // "--R 30": 30 m
  const auto a = analyze(make({}), o);
  EXPECT_TRUE(has_warning(a, "not the radius of a popper's shell")) << a.warnings.size();
  EXPECT_FALSE(has_warning(analyze(make({}), with_R()), "not the radius"));
}

// One series per outcome, each with plain physics: the popper rests on the plate with its weight
// mg = 0.5 N (z = 0), the plate's force is a triangle spike, and after a lift-off z follows a free
// flight z = v s - g s^2 / 2 (s from the lift-off); the contact column says ring on the plate,
// disk once the apex is down, none in flight; delta_p falls from 2 kPa through zero at 50 ms.
constexpr double kMg = 0.5;

// A triangle of height `top` from t0 to t0 + 2 ms (peak at t0 + 1 ms) over the weight.
double spike(double t, double t0, double top) {
  const double s = std::abs(t - t0 - 1e-3) / 1e-3;
  return s < 1.0 ? kMg + (top - kMg) * (1.0 - s) : kMg;
}

// A push that rises from the weight at t0 to `top` at t0 + 1 ms and falls to zero at t0 + 2 ms,
// where the popper leaves the plate.
double push(double t, double t0, double top) {
  if (t < t0) return kMg;
  if (t < t0 + 1e-3) return kMg + (top - kMg) * (t - t0) / 1e-3;
  return std::max(0.0, top * (t0 + 2e-3 - t) / 1e-3);
}

// Off the plate in a flight of apex height `top` from lift-off at t0, back on it after 2 v / g.
bool airborne(double t, double t0, double top) {
  const double s = t - t0;
  return s >= 0.0 && s < 2.0 * std::sqrt(2.0 * g * top) / g;
}

// The height in that flight.
double flight(double t, double t0, double top) {
  const double v = std::sqrt(2.0 * g * top), s = t - t0;
  return airborne(t, t0, top) ? v * s - 0.5 * g * s * s : 0.0;
}

Spec plain_spec() {
  Spec spec;
  spec.with_contact = true;
  spec.with_dp = true;
  spec.dp = [](double t) { return 2000.0 - 4e4 * t; };
  spec.t_end = 300e-3;
  return spec;
}

TEST(AnalysisClasses, JumpLeavesThePlateAfterTheSnap) {
  // Onset at 20.05 ms (w_ref), a 5 N push from 21 to 23 ms, lift-off when it is over, a 40 mm
  // flight (v = 0.886 m/s, 181 ms long, landing at 204 ms).
  Spec spec = plain_spec();
  spec.F = [](double t) {
    return t < 23e-3 ? push(t, 21e-3, 5.0) : airborne(t, 23e-3, 0.04) ? 0.0 : kMg;
  };
  spec.z = [](double t) { return flight(t, 23e-3, 0.04); };
  spec.contact = [](double t) {
    if (t < 20.05e-3) return ContactState::Ring;
    return airborne(t, 23e-3, 0.04) ? ContactState::None : ContactState::Disk;
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Jump) << a.undetermined;
  ASSERT_TRUE(a.t_launch && a.flight_rise && a.t_lift_off && a.flight_threshold);
  EXPECT_NEAR(*a.t_launch, 23e-3 - 0.02 * 1e-3, 1e-9);  // F = 0.02 F* on the flank
  EXPECT_EQ(*a.t_lift_off, *a.t_launch);                // the highest flight is the jump
  EXPECT_NEAR(*a.flight_rise, 0.04, 1e-6);
  EXPECT_TRUE(contradiction(a).empty()) << contradiction(a);
}

TEST(AnalysisClasses, SnapStaysOnThePlate) {
  // The same snap without a lift-off: after the spike the weight is back on the plate, z stays.
  Spec spec = plain_spec();
  spec.F = [](double t) { return spike(t, 21e-3, 5.0); };
  spec.z = [](double) { return 0.0; };
  spec.contact = [](double t) { return t < 20.05e-3 ? ContactState::Ring : ContactState::Disk; };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Snap) << a.undetermined;
  EXPECT_FALSE(a.t_launch);
  EXPECT_FALSE(a.flight_rise);
  EXPECT_TRUE(contradiction(a).empty()) << contradiction(a);
}

TEST(AnalysisClasses, NoSnapStaysInvertedOnThePlate) {
  // The apex stays 20 mm up, the weight on the plate throughout, the suction gone at 50 ms.
  Spec spec = plain_spec();
  spec.w = [](double) { return 20e-3; };
  spec.F = [](double) { return kMg; };
  spec.z = [](double) { return 0.0; };
  spec.contact = [](double) { return ContactState::Ring; };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::NoSnap) << a.undetermined;
  EXPECT_FALSE(a.flight_rise);
  ASSERT_TRUE(a.flight_threshold);
  EXPECT_NEAR(*a.flight_threshold, g * 5e-3 * 5e-3 / 8.0, 1e-15);  // z has no noise
  EXPECT_TRUE(contradiction(a).empty()) << contradiction(a);
}

// The inverted popper thrown by a 100 N push at 100-102 ms (the inflow's overpressure pressing the
// shell onto the plate), flying 84 mm high (v = 1.284 m/s) while the apex stays 20 mm above the
// plate, the shell inverted; the suction was gone at 50 ms.
Spec thrown_spec() {
  Spec spec = plain_spec();
  spec.F = [](double t) { return push(t, 100e-3, 100.0); };
  spec.z = [](double t) { return flight(t, 102e-3, 0.084); };
  spec.w = [](double t) { return 20e-3 + flight(t, 102e-3, 0.084); };
  spec.contact = [](double t) { return t < 102e-3 ? ContactState::Ring : ContactState::None; };
  return spec;
}

TEST(AnalysisClasses, AFlightWithoutTheContactTransitionIsThrownNotNoSnap) {
  // The analysis had no onset, the suction gone for 250 ms, and called it No snap.
  const auto a = analyze(make(thrown_spec()), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Thrown)
      << outcome_text(a.outcome) << ": " << a.undetermined;
  EXPECT_FALSE(a.t_onset);
  ASSERT_TRUE(a.t_lift_off && a.flight_rise && a.flight_threshold && a.H);
  EXPECT_NEAR(*a.t_lift_off, 102e-3 - 0.02 * 1e-3, 1e-9);  // F = 0.02 F* on the spike's flank
  EXPECT_NEAR(*a.flight_rise, 0.084, 1e-6);
  EXPECT_NEAR(*a.H, 0.084, 1e-6);
  EXPECT_TRUE(has_warning(a, "no contact transition in the record")) << a.warnings.size();
  EXPECT_TRUE(contradiction(a).empty()) << contradiction(a);
  // The check the analysis applies to itself: this series can never be No snap.
  Analysis forced = a;
  forced.outcome = theory::Outcome::NoSnap;
  EXPECT_NE(contradiction(forced).find("the popper flew"), std::string::npos);
}

TEST(AnalysisClasses, AThrowThatLandsBeforeTheSnapOnThePlateIsNotThrown) {
  // Thrown 5 mm at 10 ms (back at 73.9 ms), then the apex comes down on the plate at 120.05 ms
  // with a 5 N spike and the popper stays: the snap happened on the plate.
  Spec spec = plain_spec();
  spec.F = [](double t) {
    if (t < 10e-3) return spike(t, 8e-3, 2.0);
    if (airborne(t, 10e-3, 5e-3)) return 0.0;
    return spike(t, 121e-3, 5.0);
  };
  spec.z = [](double t) { return flight(t, 10e-3, 5e-3); };
  spec.w = [](double t) { return w_ref(t - 100e-3) + flight(t, 10e-3, 5e-3); };
  spec.contact = [](double t) {
    if (t >= 120.05e-3) return ContactState::Disk;
    return airborne(t, 10e-3, 5e-3) ? ContactState::None : ContactState::Ring;
  };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::Snap) << outcome_text(a.outcome) << ": " << a.undetermined;
  ASSERT_TRUE(a.t_onset && a.flight_rise);
  EXPECT_NEAR(*a.t_onset, 120.05e-3, 1e-9);
  EXPECT_NEAR(*a.flight_rise, 5e-3, 1e-6);
  EXPECT_TRUE(has_warning(a, "landed before the onset")) << a.warnings.size();
}

TEST(AnalysisClasses, AHopBelowTheFlightThresholdIsNoFlight) {
  // Off the plate for 8 ms at 100 ms, z rising 10 um (a counterweighted popper barely lifting,
  // deceleration 1.25 m/s^2): less than g (5 ms)^2 / 8 = 30.7 um, so No snap stands.
  Spec spec = plain_spec();
  spec.w = [](double) { return 20e-3; };
  spec.F = [](double t) { return t > 100e-3 && t < 108e-3 ? 0.0 : kMg; };
  spec.z = [](double t) {
    const double s = t - 100e-3;
    return s > 0.0 && s < 8e-3 ? 5e-3 * s - 0.5 * 1.25 * s * s : 0.0;
  };
  spec.contact = [](double) { return ContactState::Ring; };
  const auto a = analyze(make(spec), with_R());
  EXPECT_EQ(a.outcome, theory::Outcome::NoSnap) << a.undetermined;
  ASSERT_TRUE(a.flight_rise && a.flight_threshold);
  EXPECT_NEAR(*a.flight_rise, 1e-5, 1e-6);  // less z at the lift-off, 0.1 ms in
  EXPECT_LT(*a.flight_rise, *a.flight_threshold);
}

TEST(AnalysisClasses, WithoutZAPopperOffThePlateIsNotNoSnap) {
  // The thrown series without its z column: F alone says the popper left the plate, not whether
  // it flew. The analysis had called it No snap.
  Spec spec = thrown_spec();
  spec.with_z = false;
  const auto a = analyze(make(spec), with_R());
  EXPECT_FALSE(a.outcome) << outcome_text(a.outcome);
  EXPECT_NE(a.undetermined.find("without a z column"), std::string::npos) << a.undetermined;
}

TEST(AnalysisClasses, AContradictedOrUnexplainedOutcomeIsNamed) {
  Analysis a;
  EXPECT_NE(contradiction(a).find("no reason"), std::string::npos);  // no outcome, no reason
  a.undetermined = "the record ends too soon";
  EXPECT_TRUE(contradiction(a).empty());
  a = {};
  a.outcome = theory::Outcome::Thrown;
  EXPECT_FALSE(contradiction(a).empty());  // no flight
  a.flight_rise = 1e-3;
  a.flight_threshold = 3e-5;
  EXPECT_TRUE(contradiction(a).empty());
  a.outcome = theory::Outcome::Jump;
  EXPECT_NE(contradiction(a).find("no launch"), std::string::npos);
  a.outcome = theory::Outcome::Snap;
  EXPECT_NE(contradiction(a).find("no onset"), std::string::npos);
  a.outcome = theory::Outcome::NoSnap;
  EXPECT_NE(contradiction(a).find("the popper flew"), std::string::npos);
  a.flight_rise = 1e-5;  // a hop below the threshold
  EXPECT_TRUE(contradiction(a).empty());
}

TEST(AnalysisClasses, EveryUndeterminedOutcomeCarriesItsReason) {
  std::vector<Spec> specs(6, plain_spec());
  specs[1] = thrown_spec();
  specs[1].with_z = false;
  specs[2].t_end = 24e-3;  // cut during the snap
  specs[3].with_w = false;
  specs[3].with_contact = false;                          // no onset criterion
  specs[4].F = [](double t) { return F_jump(t) - 0.5; };  // tared
  specs[5].with_dp = false;
  specs[5].w = [](double) { return 20e-3; };  // no onset and no delta_p
  specs[5].F = [](double) { return kMg; };
  specs[5].z = [](double) { return 0.0; };
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto a = analyze(make(specs[i]), with_R());
    EXPECT_TRUE(a.outcome || !a.undetermined.empty()) << "series " << i;
    EXPECT_TRUE(contradiction(a).empty()) << "series " << i << ": " << contradiction(a);
  }
}

}  // namespace
}  // namespace snapjump::measure
