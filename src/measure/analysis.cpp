#include "measure/analysis.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

#include "config/plausibility.hpp"

namespace snapjump::measure {
namespace {

// y linearly interpolated at tq, held constant outside [t.front(), t.back()].
double interpolate(std::span<const double> t, std::span<const double> y, double tq) {
  if (tq <= t.front()) return y.front();
  if (tq >= t.back()) return y.back();
  const auto it = std::upper_bound(t.begin(), t.end(), tq);
  const auto i = static_cast<std::size_t>(it - t.begin());  // t[i - 1] <= tq < t[i]
  const double s = (tq - t[i - 1]) / (t[i] - t[i - 1]);
  return y[i - 1] + s * (y[i] - y[i - 1]);
}

// How much higher z goes after the last sample: a least-squares parabola through the last samples
// (up to 21) gives the velocity at the end and the deceleration. Infinity when z is not slowing
// down, or when the curvature is not clearly resolved (less than three standard errors, as on a
// noisy measured record): then the caller keeps its warning.
double rise_left(std::span<const double> t, std::span<const double> z) {
  const std::size_t n = z.size();
  const std::size_t k = std::min<std::size_t>(n, 21);
  constexpr double kUnknown = std::numeric_limits<double>::infinity();
  if (k < 5) return kUnknown;
  Eigen::MatrixXd X(k, 3);
  Eigen::VectorXd y(k);
  const double scale = t[n - 1] - t[n - k];  // tau in units of the window, for conditioning
  if (!(scale > 0.0)) return kUnknown;
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = n - k + i;
    const double tau = (t[j] - t[n - 1]) / scale;
    X(static_cast<Eigen::Index>(i), 0) = 1.0;
    X(static_cast<Eigen::Index>(i), 1) = tau;
    X(static_cast<Eigen::Index>(i), 2) = tau * tau;
    y(static_cast<Eigen::Index>(i)) = z[j];
  }
  const Eigen::Matrix3d inv = (X.transpose() * X).inverse();  // 3 x 3, tau scaled to [-1, 0]
  const Eigen::Vector3d c = inv * (X.transpose() * y);
  const double rss = (X * c - y).squaredNorm();
  const double var_c2 = rss / static_cast<double>(k - 3) * inv(2, 2);
  const double v_end = c(1) / scale;  // dz/dt at the last sample
  const double decel = -2.0 * c(2) / (scale * scale);
  if (!(decel > 0.0) || c(2) * c(2) <= 9.0 * var_c2) return kUnknown;
  return v_end > 0.0 ? v_end * v_end / (2.0 * decel) : 0.0;
}

// Time where the segment (i - 1, i) crosses `level`, assuming y[i - 1] and y[i] lie on either side.
double crossing_time(std::span<const double> t, std::span<const double> y, std::size_t i,
                     double level) {
  const double dy = y[i] - y[i - 1];
  if (dy == 0.0) return t[i];
  const double s = std::clamp((level - y[i - 1]) / dy, 0.0, 1.0);
  return t[i - 1] + s * (t[i] - t[i - 1]);
}

// A robust standard deviation: 1.4826 times the median absolute deviation from the median
// (equal to the standard deviation for Gaussian noise, blind to a few impact spikes).
double robust_sigma(std::vector<double> v) {
  const auto median = [](std::vector<double>& x) {
    const auto mid = x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2);
    std::nth_element(x.begin(), mid, x.end());
    double m = *mid;
    if (x.size() % 2 == 0) m = 0.5 * (m + *std::max_element(x.begin(), mid));
    return m;
  };
  const double m = median(v);
  for (auto& x : v) x = std::abs(x - m);
  return 1.4826 * median(v);
}

// The upper of the two middle values (the middle one for an odd count); v not empty.
double upper_median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The start of the rise of F that ends at sample `k`. The base F_b is the lowest F met walking
// back from k until F climbs again by more than a tenth of the rise F[k] - F_b (noise smaller than
// that does not stop the walk); the rise starts where F, walking back from k, first falls below
// F_b + 0.1 (F[k] - F_b): the index of that sample (k itself when F[k] is the base) and the level.
struct RiseStart {
  std::size_t index;
  double level;
};
constexpr double kTurnFraction = 0.1;

// Walking back from sample k, the extreme F met (the lowest for sign = +1, the highest for
// sign = -1) before F turns back by more than a tenth of the way from that extreme to F[k].
std::size_t extreme_behind(std::span<const double> F, std::size_t k, double sign) {
  std::size_t best = k;
  for (std::size_t i = k; i-- > 0;) {
    const double d = sign * (F[i] - F[best]);  // < 0: further along; > 0: turning back
    if (d < 0.0) {
      best = i;
    } else if (d > kTurnFraction * sign * (F[k] - F[best])) {
      break;
    }
  }
  return best;
}

RiseStart rise_start(std::span<const double> F, std::size_t k) {
  const std::size_t low = extreme_behind(F, k, +1.0);
  const double level = F[low] + kTurnFraction * (F[k] - F[low]);
  std::size_t i = k;
  while (i > low && F[i] > level) --i;
  return {i, level};
}

// The force peak that sample `k` lies on or after: walking back from k, the highest F met before F
// falls again by more than a tenth of (that peak - F[k]). k itself when F does not climb going
// back (k is on a rise or a plateau).
std::size_t peak_behind(std::span<const double> F, std::size_t k) {
  return extreme_behind(F, k, -1.0);
}

void check_options(const AnalysisOptions& o) {
  const auto bad = [](std::string_view what, double v) {
    return SeriesError(fmt::format("analysis option {} = {} must be positive", what, v));
  };
  if (o.R && !(*o.R > 0.0)) throw bad("R", *o.R);
  if (!(o.onset_ratio > 0.0)) throw bad("onset_ratio", o.onset_ratio);
  if (o.force_threshold && !(*o.force_threshold > 0.0)) {
    throw bad("force_threshold", *o.force_threshold);
  }
  if (!(o.settle_time >= 0.0) || !std::isfinite(o.force_offset)) {
    throw SeriesError(fmt::format(
        "analysis options: settle_time = {} must not be negative and force_offset = {} finite",
        o.settle_time, o.force_offset));
  }
  if (!(o.min_flight_time >= 0.0)) {
    throw SeriesError(fmt::format("analysis option min_flight_time = {} must not be negative",
                                  o.min_flight_time));
  }
  if (!(o.relative_threshold >= 0.0) || !(o.noise_multiple >= 0.0)) {
    throw SeriesError(
        "analysis options relative_threshold and noise_multiple must not be negative");
  }
  if (!(o.noise_window_fraction > 0.0 && o.noise_window_fraction <= 1.0)) {
    throw SeriesError(fmt::format("analysis option noise_window_fraction = {} must be in (0, 1]",
                                  o.noise_window_fraction));
  }
}

// Finds the onset; returns the index of the first sample at or after it.
std::optional<std::size_t> find_onset(const TimeSeries& s, const AnalysisOptions& o, Analysis& a) {
  const auto t = s.time();
  if (s.has(kApexGap) && a.R) {
    const auto w = s.column(kApexGap);
    const double level = o.onset_ratio * *a.R;
    const auto it = std::find_if(w.begin(), w.end(), [&](double v) { return v < level; });
    if (it == w.end()) return std::nullopt;
    const auto i = static_cast<std::size_t>(it - w.begin());
    a.onset_source = OnsetSource::ApexGap;
    if (i == 0) {
      a.t_onset = t[0];
      a.warnings.push_back(fmt::format(
          "w / R is below {} already at the first sample: the onset is taken at the start of the "
          "record, t = {} s",
          o.onset_ratio, t[0]));
    } else {
      a.t_onset = crossing_time(t, w, i, level);
    }
    return i;
  }
  if (s.has(kApexGap)) {
    a.warnings.push_back(
        "there is a w column but no shell radius R (give it in the options or with the case): "
        "the onset cannot use w / R");
  }
  if (s.has_contact()) {
    if (!s.has(kApexGap)) {
      a.warnings.push_back("no w column: the onset is the first row whose contact state is disk");
    }
    const auto c = s.contact();
    const auto it = std::find(c.begin(), c.end(), ContactState::Disk);
    if (it == c.end()) return std::nullopt;
    const auto i = static_cast<std::size_t>(it - c.begin());
    a.onset_source = OnsetSource::ContactDisk;
    a.t_onset = t[i];
    return i;
  }
  return std::nullopt;
}

// The noise of F: the robust spread over the final part of the record, counted only from the
// first sample after the peak where F is below kQuiet F* (so that a record ending soon after the
// launch does not count the falling flank as noise), and only if F is about zero there (in
// flight). When the record goes on past a landing (F back on the weight at its end), the longest
// stretch after the peak where F stays within kQuiet F* of zero is used instead, if its median is
// within relative_threshold F* of zero (a flight).
constexpr double kQuiet = 0.1;
constexpr std::size_t kMinNoiseSamples = 5;

void estimate_noise(std::span<const double> t, std::span<const double> F, const AnalysisOptions& o,
                    std::size_t peak, double F_star, Analysis& a) {
  const std::size_t n = t.size();
  const double t_from = t.back() - o.noise_window_fraction * (t.back() - t.front());
  std::size_t first = peak + 1;
  while (first < n && F[first] >= kQuiet * F_star) ++first;
  std::vector<double> tail;
  for (std::size_t i = first; i < n; ++i) {
    if (t[i] >= t_from) tail.push_back(F[i]);
  }
  std::optional<double> median;
  if (tail.size() >= kMinNoiseSamples) {
    median = upper_median(tail);
    if (std::abs(*median) <= kQuiet * F_star) {
      a.force_noise = robust_sigma(std::move(tail));
      return;
    }
  }
  // The longest stretch after the peak with |F| < kQuiet F*.
  std::size_t best_from = 0, best_len = 0;
  for (std::size_t i = peak + 1; i < n;) {
    if (std::abs(F[i]) >= kQuiet * F_star) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && std::abs(F[j]) < kQuiet * F_star) ++j;
    if (j - i > best_len) {
      best_from = i;
      best_len = j - i;
    }
    i = j;
  }
  if (best_len >= kMinNoiseSamples) {
    // A flight reads about zero: a stretch whose median is not (the popper resting lightly on
    // the plate, pulled by the suction) says nothing about the noise.
    std::vector<double> stretch(F.begin() + static_cast<std::ptrdiff_t>(best_from),
                                F.begin() + static_cast<std::ptrdiff_t>(best_from + best_len));
    if (std::abs(upper_median(stretch)) <= o.relative_threshold * F_star) {
      a.force_noise = robust_sigma(std::move(stretch));
      return;
    }
  }
  if (median) {
    a.warnings.push_back(fmt::format(
        "F is not near zero at the end of the record (median {} N) and never stays near zero "
        "after the peak: no noise estimate, the launch threshold is {} F* alone",
        *median, o.relative_threshold));
  }
}

double launch_level(const AnalysisOptions& o, double F_peak, const Analysis& a) {
  if (o.force_threshold) return *o.force_threshold;
  return std::max(o.relative_threshold * F_peak, o.noise_multiple * a.force_noise.value_or(0.0));
}

// The launch: from the window's first sample on, with the force peak so far as F*, the first
// crossing of F below the threshold after that peak such that, for min_flight_time (or to the
// end of the record), F stays below the threshold (raised by as much as F dips below zero then:
// a plate rings on after the launch) and below it on average, and, with a z column, the container
// is higher at the end of that time than at the crossing. The snap ends there: a landing later in
// the record, however hard, is not its force. Crossings are looked for up to the sample `last`
// (inclusive); F staying below is checked on the whole record. Returns the peak before the launch
// and sets t_launch, or returns nothing when there is no launch.
std::optional<std::size_t> find_launch(const TimeSeries& s, const AnalysisOptions& o,
                                       std::size_t first, std::size_t last, Analysis& a) {
  const auto t = s.time();
  const auto F = s.column(kForce);
  const std::size_t n = t.size();
  std::size_t peak = first;
  for (std::size_t k = first + 1; k < n && k <= last; ++k) {
    if (F[k] > F[peak]) {
      peak = k;
      continue;
    }
    const double level = launch_level(o, F[peak], a);
    if (F[k] >= level || F[k - 1] < level || !(F[peak] > level)) continue;
    // F[k - 1] >= level > F[k]: the first sample of a candidate stretch below the threshold.
    const double t_cross = crossing_time(t, F, k, level);
    // In flight a plate rings on after the launch, swinging below zero as far as above it: F
    // must stay below the threshold raised by its deepest dip below zero in that time (at most
    // to kQuiet F*), and below the threshold on average. A force that stays positive (the shell
    // still touching, lightly) gets no such allowance.
    double deepest = 0.0;
    for (std::size_t i = k; i < n && t[i] <= t_cross + o.min_flight_time; ++i) {
      deepest = std::min(deepest, F[i]);
    }
    const double ceiling = std::min(level - deepest, std::max(level, kQuiet * F[peak]));
    std::size_t j = k;
    bool stays = true;
    double sum = 0.0;
    std::size_t count = 0;
    for (; j < n && t[j] <= t_cross + o.min_flight_time; ++j) {
      if (F[j] >= ceiling) {
        stays = false;
        break;
      }
      sum += F[j];
      ++count;
    }
    if (stays && count > 0 && sum / static_cast<double>(count) >= level) stays = false;
    if (stays && s.has(kHeight)) {
      // A launch leaves the plate going up. Contact lost while the container does not rise (the
      // suction pulling the everted shell back in as the popper settles) is not one.
      const auto z = s.column(kHeight);
      const double t_after = std::min(t_cross + o.min_flight_time, t.back());
      const double z_at = interpolate(t, z, t_cross);
      const double z_after = interpolate(t, z, t_after);
      if (!(z_after > z_at)) {
        a.warnings.push_back(fmt::format(
            "F falls below the launch threshold at t = {:.6g} s while the container is not rising "
            "(z from {:.4g} to {:.4g} mm in the next {:.3g} ms): not a launch",
            t_cross, 1e3 * z_at, 1e3 * z_after, 1e3 * (t_after - t_cross)));
        while (j < n && F[j] < ceiling) ++j;
        k = j - 1;  // the loop's ++k looks at sample j next: it may be a new peak
        continue;
      }
    }
    if (stays) {
      a.t_launch = t_cross;
      if (j == n && t.back() - t_cross < o.min_flight_time) {
        a.warnings.push_back(fmt::format(
            "the record ends {} ms after the launch, before F has stayed below the threshold "
            "for {} ms",
            1e3 * (t.back() - t_cross), 1e3 * o.min_flight_time));
      }
      return peak;
    }
    // Not a launch from this crossing: the scan goes on with the next sample, so that a later
    // crossing inside the same stretch (a plate ringing down) and a new peak are both seen.
  }
  return std::nullopt;
}

// The longest stretch of at least min_time where F < -level: a plate pushes and cannot pull, so a
// sustained negative force says its zero is off (a tared plate). Returns (first, last) indices.
std::optional<std::pair<std::size_t, std::size_t>> negative_stretch(std::span<const double> t,
                                                                    std::span<const double> F,
                                                                    double level, double min_time) {
  std::optional<std::pair<std::size_t, std::size_t>> best;
  double best_span = min_time;
  for (std::size_t i = 0; i < F.size();) {
    if (!(F[i] < -level)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < F.size() && F[j + 1] < -level) ++j;
    if (t[j] - t[i] >= best_span) {
      best = std::make_pair(i, j);
      best_span = t[j] - t[i];
    }
    i = j + 1;
  }
  return best;
}

// A stretch off the plate by the launch rule, from the lift-off (F's crossing below the threshold)
// to the landing (the first sample, min_flight_time or more after the lift-off, with F back above
// the launch's ceiling; the record's end when there is none), and how far z rose in it above its
// height at the lift-off (none without a z column).
struct Flight {
  double t_lift_off = 0.0;
  double t_landing = std::numeric_limits<double>::infinity();
  std::optional<double> rise;
};

// The plate's noise wherever the popper is (resting, rocking, in flight): the robust spread of F's
// changes from sample to sample over sqrt(2). A force that varies slowly against the sampling
// changes little between samples, and impacts are few. (The snap's launch takes the noise after
// its peak instead, where a flight follows it.)
double sample_noise(std::span<const double> F) {
  if (F.size() < kMinNoiseSamples + 1) return 0.0;
  std::vector<double> d(F.size() - 1);
  for (std::size_t i = 0; i + 1 < F.size(); ++i) d[i] = F[i + 1] - F[i];
  return robust_sigma(std::move(d)) / std::sqrt(2.0);
}

// Every flight in the record, in order: the launch rule (find_launch) from the record's start, and
// again from each landing, with the noise of F from sample_noise.
std::vector<Flight> find_flights(const TimeSeries& s, const AnalysisOptions& o) {
  const auto t = s.time();
  const auto F = s.column(kForce);
  const std::size_t n = t.size();
  std::vector<Flight> flights;
  const double noise = sample_noise(F);
  std::size_t start = 0;
  while (start + 1 < n) {
    Analysis probe;  // its warnings are the snap window's business, not the flights'
    probe.force_noise = noise;
    const auto peak = find_launch(s, o, start, n - 1, probe);
    if (!peak) break;
    Flight f;
    f.t_lift_off = *probe.t_launch;
    const double ceiling = std::max(launch_level(o, F[*peak], probe), kQuiet * F[*peak]);
    std::size_t k = *peak;
    while (k < n && t[k] < f.t_lift_off) ++k;
    const std::size_t first = k;
    while (k < n && (t[k] <= f.t_lift_off + o.min_flight_time || F[k] < ceiling)) ++k;
    if (k < n) f.t_landing = t[k];
    if (s.has(kHeight)) {
      const auto z = s.column(kHeight);
      const double z_lift_off = interpolate(t, z, f.t_lift_off);
      double z_top = z_lift_off;
      for (std::size_t i = first; i < k; ++i) z_top = std::max(z_top, z[i]);
      f.rise = z_top - z_lift_off;
    }
    flights.push_back(f);
    start = k;
  }
  return flights;
}

// The least rise of z that says the popper flew: noise_multiple times the noise of z (the robust
// spread of its second differences over sqrt(6), which for independent noise of spread sigma
// spread by sqrt(6) sigma, while a smooth z adds only its acceleration times the sampling interval
// squared), and at least g min_flight_time^2 / 8, the top of a free fall that lasts
// min_flight_time, the shortest stretch off the plate the launch rule calls a flight.
double flight_threshold(std::span<const double> z, const AnalysisOptions& o) {
  double sigma = 0.0;
  if (z.size() >= kMinNoiseSamples + 2) {
    std::vector<double> d2(z.size() - 2);
    for (std::size_t i = 0; i + 2 < z.size(); ++i) d2[i] = z[i + 2] - 2.0 * z[i + 1] + z[i];
    sigma = robust_sigma(std::move(d2)) / std::sqrt(6.0);
  }
  const double T = o.min_flight_time;
  return std::max(o.noise_multiple * sigma, config::kStandardGravity * T * T / 8.0);
}

bool rose(const Flight& f, double threshold) { return f.rise && *f.rise > threshold; }

// The flight that makes a run Thrown: the highest that rose above the threshold with no contact
// transition on the plate before it, i.e. with no onset in the record, or with the onset inside
// the flight (the apex meeting the criterion in the air or on the way down onto it). A flight that
// landed before an onset on the plate (a hop as the shell unrolls in the ring stage, a throw after
// which the shell snaps on the plate) is not one.
const Flight* thrown_flight(const std::vector<Flight>& flights,
                            const std::optional<double>& t_onset, double threshold) {
  const Flight* best = nullptr;
  for (const auto& f : flights) {
    const bool no_transition = !t_onset || (f.t_lift_off < *t_onset && *t_onset <= f.t_landing);
    if (no_transition && rose(f, threshold) && (best == nullptr || *f.rise > *best->rise)) {
      best = &f;
    }
  }
  return best;
}

// A sustained negative force below this fraction of F's range (or the noise) says F's zero is off.
constexpr double kTareFraction = 0.05;

// No onset in the whole record: No snap is settled when the record covers the experiment
// (options.complete) or goes on for settle_time after delta_p has come down to zero (the paper's
// No snap: the rim stays on the plate even at delta_p = 0). Otherwise the reason goes into
// a.undetermined.
void no_snap_settled(const TimeSeries& s, const AnalysisOptions& o, Analysis& a) {
  if (o.complete) return;
  const auto t = s.time();
  if (!s.has(kPressure)) {
    a.undetermined = fmt::format(
        "no onset within the record (to t = {:.6g} s), and without a delta_p column the analysis "
        "cannot tell whether the suction was gone before it ended: the shell may still have "
        "snapped (say the record is complete if it covers the whole experiment)",
        t.back());
    return;
  }
  // The suction gone: delta_p down to zero after its largest value (a record that starts
  // before the suction is applied reads zero at first).
  const auto dp = s.column(kPressure);
  const auto top = std::max_element(dp.begin(), dp.end());
  const auto it = std::find_if(top, dp.end(), [](double v) { return v <= 0.0; });
  if (it == dp.end()) {
    a.undetermined = fmt::format(
        "no onset within the record, which ends at t = {:.6g} s with delta_p = {:.4g} Pa of "
        "suction still holding the shell: it may still snap",
        t.back(), dp.back());
    return;
  }
  const double t_zero = t[static_cast<std::size_t>(it - dp.begin())];
  if (t.back() - t_zero < o.settle_time) {
    a.undetermined = fmt::format(
        "no onset within the record, which ends {:.3g} ms after delta_p reached zero (at t = "
        "{:.6g} s): the analysis waits {:.3g} ms (option settle_time) before calling it No snap",
        1e3 * (t.back() - t_zero), t_zero, 1e3 * o.settle_time);
  }
}

// The record's flights, its highest one and the threshold of a flight put into the analysis.
std::vector<Flight> report_flights(const TimeSeries& s, const AnalysisOptions& o, Analysis& a) {
  auto flights = find_flights(s, o);
  if (!s.has(kHeight)) return flights;
  a.flight_threshold = flight_threshold(s.column(kHeight), o);
  for (const auto& f : flights) {
    if (f.rise && (!a.flight_rise || *f.rise > *a.flight_rise)) {
      a.flight_rise = f.rise;
      a.t_lift_off = f.t_lift_off;
    }
  }
  return flights;
}

// What the outcome needs beside the analysis so far.
struct OutcomeFacts {
  bool can_tell = false;      // an onset criterion: w with R, or a contact column
  bool snap_settled = false;  // an onset without a launch, on long enough to call it Snap
  bool force_trusted = true;  // F's zero is not off
  bool has_height = false;    // a z column
  const std::vector<Flight>& flights;
};

// The outcome, in one place. On entry a.undetermined says why the record cannot settle the outcome
// of a snap on the plate or of no onset (empty when it can); a flight without the contact
// transition on the plate before it overrides that (Thrown).
void decide_outcome(Analysis& a, const OutcomeFacts& f) {
  if (!f.can_tell || !f.force_trusted) return;  // a.undetermined says why
  const double threshold = a.flight_threshold.value_or(0.0);
  if (const auto* thrown = thrown_flight(f.flights, a.t_onset, threshold)) {
    a.outcome = theory::Outcome::Thrown;
    a.undetermined.clear();
    a.warnings.push_back(fmt::format(
        "thrown: the popper left the plate at t = {:.6g} s and z rose {:.4g} mm above its height "
        "there (a flight: more than {:.3g} mm), {}: it flew without the snap on the plate",
        thrown->t_lift_off, 1e3 * *thrown->rise, 1e3 * threshold,
        a.t_onset ? fmt::format("with the onset (t = {:.6g} s) in the air", *a.t_onset)
                  : std::string("with no contact transition in the record")));
    return;
  }
  if (a.t_onset && !a.t_launch) {
    for (const auto& fl : f.flights) {
      if (fl.t_landing < *a.t_onset && rose(fl, threshold)) {
        a.warnings.push_back(fmt::format(
            "the popper was off the plate from t = {:.6g} s to {:.6g} s, z rising {:.4g} mm, and "
            "landed before the onset: the snap is the one on the plate after it",
            fl.t_lift_off, fl.t_landing, 1e3 * *fl.rise));
        break;
      }
    }
  }
  if (!a.undetermined.empty()) return;
  if (a.t_launch) {
    a.outcome = theory::Outcome::Jump;
  } else if (a.t_onset) {
    if (f.snap_settled) a.outcome = theory::Outcome::Snap;
  } else if (!f.has_height && !f.flights.empty()) {
    a.undetermined = fmt::format(
        "no onset, and F says the popper was off the plate from t = {:.6g} s: without a z column "
        "the record cannot show whether it flew, so it is not called No snap",
        f.flights.front().t_lift_off);
  } else {
    a.outcome = theory::Outcome::NoSnap;
  }
}

}  // namespace

std::string_view to_string(OnsetSource s) {
  switch (s) {
    case OnsetSource::None:
      return "none";
    case OnsetSource::ApexGap:
      return "w/R";
    case OnsetSource::ContactDisk:
      return "contact=disk";
  }
  return "none";
}

std::string outcome_text(const std::optional<theory::Outcome>& o) {
  return o ? theory::to_string(*o) : std::string("undetermined");
}

std::vector<double> plate_response(std::span<const double> t, std::span<const double> F, double f,
                                   double zeta) {
  if (!(f > 0.0) || !(zeta > 0.0)) {
    throw SeriesError(fmt::format(
        "force plate: needs a positive frequency and damping ratio (got {} Hz, {})", f, zeta));
  }
  if (t.size() != F.size()) {
    throw SeriesError(fmt::format("force plate: {} times for {} forces", t.size(), F.size()));
  }
  const double w = 2.0 * std::numbers::pi * f;
  std::vector<double> y(F.size(), 0.0);
  if (F.empty()) return y;
  // y'' + 2 zeta w y' + w^2 y = w^2 F(t): state (y, y'), from rest at F[0].
  double q = F[0], v = 0.0;
  y[0] = q;
  for (std::size_t i = 1; i < F.size(); ++i) {
    const double span = t[i] - t[i - 1];
    if (!(span > 0.0)) {
      throw SeriesError(
          fmt::format("force plate: times must increase (t = {} s after {} s)", t[i], t[i - 1]));
    }
    const int sub = std::max(1, static_cast<int>(std::ceil(span * w / 0.05)));
    const double h = span / sub;
    const auto load = [&](double s) { return F[i - 1] + (F[i] - F[i - 1]) * s / span; };
    const auto acc = [&](double s, double qq, double vv) {
      return w * w * (load(s) - qq) - 2.0 * zeta * w * vv;
    };
    for (int k = 0; k < sub; ++k) {
      const double s = k * h;
      const double k1q = v, k1v = acc(s, q, v);
      const double k2q = v + 0.5 * h * k1v, k2v = acc(s + 0.5 * h, q + 0.5 * h * k1q, k2q);
      const double k3q = v + 0.5 * h * k2v, k3v = acc(s + 0.5 * h, q + 0.5 * h * k2q, k3q);
      const double k4q = v + h * k3v, k4v = acc(s + h, q + h * k3q, k4q);
      q += h / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
      v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
    y[i] = q;
  }
  return y;
}

Analysis analyze(const TimeSeries& series, const AnalysisOptions& options, const config::Case* c) {
  check_options(options);
  if (!series.has(kForce)) {
    throw SeriesError(fmt::format(
        "analysis: the time series has no force column 'F' (the plate reaction); it has: {}",
        fmt::join(series.columns(), ", ")));
  }
  if (series.empty()) {
    throw SeriesError(
        "analysis: the time series has no rows (a header alone?): nothing to analyse");
  }
  if (options.force_offset != 0.0) {
    TimeSeries shifted = series;
    shifted.add_to_column(kForce, options.force_offset);
    AnalysisOptions rest = options;
    rest.force_offset = 0.0;
    auto a = analyze(shifted, rest, c);
    a.warnings.insert(
        a.warnings.begin(),
        fmt::format("F is the record's force plus the offset {} N", options.force_offset));
    return a;
  }
  Analysis a;
  for (const auto& note : series.notes()) a.warnings.push_back(fmt::format("reading: {}", note));
  a.R = options.R;
  if (!a.R && c != nullptr && c->shell.R > 0.0) a.R = c->shell.R;
  // A radius outside a popper's is most likely a bare number taken as metres.
  if (const auto* range = config::plausible_range("shell.R"); a.R && !range->holds(*a.R)) {
    a.warnings.push_back(fmt::format(
        "R = {:.6g} m is not the radius of a popper's shell (that lies within {}): a bare number "
        "is read in SI units, metres: 30 means 30 m; write \"30 mm\"",
        *a.R, range->text));
  }
  const auto t = series.time();
  const auto F = series.column(kForce);
  const std::size_t n = t.size();
  std::optional<std::size_t> landing;  // the first sample back on the plate after the launch
  bool snap_settled = false;

  const auto onset = find_onset(series, options, a);
  const bool can_tell = (series.has(kApexGap) && a.R) || series.has_contact();
  if (!can_tell) {
    a.warnings.push_back(
        "no onset can be found: the series has neither a w column (with R) nor a contact column, "
        "so the outcome is undetermined");
    a.undetermined = "no w column (with R) and no contact column: no onset can be found";
  }

  if (onset) {
    const double t_on = *a.t_onset;
    if (series.has(kContactRadius)) a.r_star = interpolate(t, series.column(kContactRadius), t_on);
    if (series.has(kIndentation)) a.e_star = interpolate(t, series.column(kIndentation), t_on);
    if (series.has(kApexDisplacement)) {
      a.e_apex_star = interpolate(t, series.column(kApexDisplacement), t_on);
    }
    if (series.has(kHeight)) a.H_l = interpolate(t, series.column(kHeight), t_on);
    if (series.has(kPressure)) a.delta_p_onset = interpolate(t, series.column(kPressure), t_on);

    // The snap lasts until the popper leaves the plate or the shell goes back to a ring contact:
    // the apex again above the onset level while the plate still pushes (after a snap without a
    // launch, the suction can pull the shell back in and the popper lands on it again; that
    // landing is not the snap's force). F* and the launch are looked for within it.
    std::size_t last = n - 1;
    bool ring_again = false;
    if (a.onset_source == OnsetSource::ApexGap) {
      const auto w = series.column(kApexGap);
      const double level = options.onset_ratio * *a.R;
      for (std::size_t i = *onset + 1; i < n; ++i) {
        if (w[i] > level && F[i] > 0.0) {
          last = i;
          ring_again = true;
          break;
        }
      }
    }
    // A contact column that says "none" for min_flight_time after the onset (a record that ends
    // sooner does not count): the popper is off the plate, whatever F reads (a plate ringing, an
    // offset); the snap's window ends there.
    std::optional<std::size_t> contact_lost;
    bool launch_from_contact = false;
    if (series.has_contact()) {
      const auto cs = series.contact();
      for (std::size_t i = *onset + 1; i <= last; ++i) {
        if (cs[i] != ContactState::None) continue;
        std::size_t j = i;
        while (j + 1 < n && cs[j + 1] == ContactState::None) ++j;
        const double until = j + 1 == n ? t[j] : t[j + 1];
        if (until - t[i] >= options.min_flight_time) {
          contact_lost = i;
          last = i;
          break;
        }
        i = j;
      }
    }
    // The launch's crossing of the threshold may come up to min_flight_time after the contact
    // is lost (the plate rings on).
    std::size_t search_last = last;
    if (contact_lost) {
      while (search_last + 1 < n && t[search_last + 1] <= t[last] + options.min_flight_time) {
        ++search_last;
      }
    }
    // The snap's force can rise, and even peak, before the apex criterion fires (a gradual
    // eversion): the window starts at the foot of the force's rise into the onset.
    // (When the onset lies on the falling flank of a peak, the rise to that peak.)
    const std::size_t first = rise_start(F, peak_behind(F, *onset)).index;
    const auto window_peak = static_cast<std::size_t>(
        std::max_element(F.begin() + static_cast<std::ptrdiff_t>(first),
                         F.begin() + static_cast<std::ptrdiff_t>(last) + 1) -
        F.begin());
    std::size_t peak = window_peak;
    if (F[window_peak] > 0.0) {
      estimate_noise(t, F, options, window_peak, F[window_peak], a);
      // The first launch ends the snap: the force peak is the largest before it (a landing later
      // in the record is not the snap's force).
      if (const auto p = find_launch(series, options, first, search_last, a)) {
        peak = *p;
        std::size_t k = peak + 1;
        while (k < n && t[k] < *a.t_launch) ++k;
        last = std::min(last, k);
      } else if (contact_lost) {
        launch_from_contact = true;
        a.t_launch = t[*contact_lost];
        a.warnings.push_back(fmt::format(
            "F does not stay below the launch threshold, but the contact column says the shell is "
            "off the plate from t = {:.6g} s: the launch is taken from the contact column",
            t[*contact_lost]));
      }
    } else {
      a.warnings.push_back(fmt::format("F is never positive after the onset (peak {} N): no launch",
                                       F[window_peak]));
    }
    a.F_star = F[peak];
    a.t_F_star = t[peak];
    a.force_threshold = launch_level(options, *a.F_star, a);
    if (!a.t_launch && *a.F_star > 0.0 && *a.force_threshold >= *a.F_star) {
      a.warnings.push_back(fmt::format(
          "the launch threshold {} N is not below the force peak F* = {} N: no launch can be found",
          *a.force_threshold, *a.F_star));
    }
    if (a.t_launch) {
      // The landing: F back above the launch's ceiling (the threshold, or kQuiet F* above a
      // ringing plate) after the flight.
      const double ceiling = std::max(*a.force_threshold, kQuiet * *a.F_star);
      std::size_t k = last;
      if (launch_from_contact) {
        // F could not tell the flight (it never stayed low): the contact column tells the end.
        const auto cs = series.contact();
        while (k < n &&
               (t[k] <= *a.t_launch + options.min_flight_time || cs[k] == ContactState::None)) {
          ++k;
        }
      } else {
        while (k < n && (t[k] <= *a.t_launch + options.min_flight_time || F[k] < ceiling)) ++k;
      }
      if (k < n) {
        a.t_landing = t[k];
        landing = k;
      }
    }
    if (options.plate_frequency) {
      const auto plate = plate_response(t, F, *options.plate_frequency, options.plate_damping);
      // The plate lags: its peak may come up to a period after the raw window's end.
      const double until = t[last] + 1.0 / *options.plate_frequency;
      std::size_t end = last + 1;
      while (end < n && t[end] <= until) ++end;
      a.F_star_plate = *std::max_element(plate.begin() + static_cast<std::ptrdiff_t>(first),
                                         plate.begin() + static_cast<std::ptrdiff_t>(end));
    }
    const auto rise = rise_start(F, peak);
    a.t_force_rise = rise.index < peak ? crossing_time(t, F, rise.index + 1, rise.level) : t[peak];
    // After a launch the apex rises with the popper (and a noisy F may be above 0): only without
    // one does the shell's return to a ring contact say something.
    if (ring_again && !a.t_launch) {
      a.warnings.push_back(fmt::format(
          "the shell is back on a ring contact at t = {:.6g} s (w / R above {} while F > 0) "
          "without having left the plate: F* is the largest force before that",
          t[last], options.onset_ratio));
    }
    if (a.t_launch && *a.t_launch < t_on) {
      // The popper left the plate before the apex came down: no snap from the plate. When z shows
      // the flight, the run is Thrown (decide_outcome); otherwise this stays the reason.
      a.undetermined = fmt::format(
          "the popper left the plate at t = {:.6g} s, before the onset (w / R < {} only at t = "
          "{:.6g} s): no snap from the plate to measure, and z does not show a flight (a rise "
          "above the flight threshold) that would make it Thrown",
          *a.t_launch, options.onset_ratio, t_on);
    } else if (a.t_launch) {
      a.t_star = *a.t_launch - t_on;
      a.t_star_rise = *a.t_launch - *a.t_force_rise;
    } else if (ring_again || options.complete || t.back() - *a.t_F_star >= options.settle_time) {
      snap_settled = true;
    } else {
      a.undetermined = fmt::format(
          "the record ends {:.3g} ms after the force peak, before the popper can be seen to leave "
          "the plate or stay on it (the analysis waits {:.3g} ms, option settle_time; or say the "
          "record is complete)",
          1e3 * (t.back() - *a.t_F_star), 1e3 * options.settle_time);
    }
  }

  if (series.has(kHeight)) {
    // The highest z of the first flight (up to the landing, when the record goes on past it).
    const auto z = series.column(kHeight);
    const auto top = std::max_element(
        z.begin(), landing ? z.begin() + static_cast<std::ptrdiff_t>(*landing) + 1 : z.end());
    a.H = *top;
    if (a.H_l) a.H_s = *a.H - *a.H_l;
    if (a.t_launch && static_cast<std::size_t>(top - z.begin()) == n - 1 &&
        rise_left(t, z) > 0.01 * (a.H_s ? *a.H_s : *a.H)) {
      a.warnings.push_back(
          "z is highest at the last sample: the record may end before the top of the flight, so H "
          "and H_s are lower bounds");
    }
  }

  if (!a.t_onset && can_tell) no_snap_settled(series, options, a);

  // A value at the onset read from inside a sensor's dropout is an interpolation across it.
  if (a.t_onset) {
    for (const auto& g : series.gaps()) {
      const bool used = g.column == kApexGap || g.column == kContactRadius ||
                        g.column == kIndentation || g.column == kHeight ||
                        g.column == kApexDisplacement;
      if (used && *a.t_onset > g.from && *a.t_onset < g.to) {
        a.warnings.push_back(fmt::format(
            "the onset (t = {:.6g} s) falls inside the gap of column '{}' ({:.6g} .. {:.6g} s): "
            "{} there is interpolated across the gap{}",
            *a.t_onset, g.column, g.from, g.to, g.column,
            g.column == kApexGap ? ", and so is the onset's time" : ""));
      }
    }
  }

  // A plate pushes and cannot pull: F held below zero says its zero is off (tared with the popper
  // standing on it, or offset), and then neither F* nor the launch threshold nor the outcome can be
  // trusted.
  bool force_trusted = true;
  {
    const double range =
        *std::max_element(F.begin(), F.end()) - *std::min_element(F.begin(), F.end());
    const double level =
        std::max(kTareFraction * range, options.noise_multiple * a.force_noise.value_or(0.0));
    if (const auto neg = negative_stretch(t, F, level, options.min_flight_time)) {
      const double median = upper_median(
          std::vector<double>(F.begin() + static_cast<std::ptrdiff_t>(neg->first),
                              F.begin() + static_cast<std::ptrdiff_t>(neg->second) + 1));
      std::string hint;
      if (c != nullptr && c->popper.net_weight > 0.0) {
        hint = fmt::format(" (the case's net weight is {:.4g} N)", c->popper.net_weight);
      }
      a.warnings.push_back(fmt::format(
          "F stays below zero (median {:.4g} N) for {:.3g} ms from t = {:.6g} s: a plate pushes "
          "and cannot pull, so the record looks tared or offset (the popper's weight subtracted?). "
          "F*, "
          "the launch and the outcome need F about 0 in flight: add the offset back (force_offset, "
          "--force-offset){}",
          median, 1e3 * (t[neg->second] - t[neg->first]), t[neg->first], hint));
      a.undetermined = "F's zero is off (the record looks tared): the force cannot tell a launch";
      force_trusted = false;
    }
  }

  const auto flights = report_flights(series, options, a);
  decide_outcome(a, {.can_tell = can_tell,
                     .snap_settled = snap_settled,
                     .force_trusted = force_trusted,
                     .has_height = series.has(kHeight),
                     .flights = flights});
  if (const auto why = contradiction(a); !why.empty()) {
    a.warnings.push_back(
        fmt::format("the outcome {} is withdrawn: {}", outcome_text(a.outcome), why));
    a.outcome.reset();
    a.undetermined = why;
  }

  if (c != nullptr) {
    const double R = c->shell.R;
    const double h = c->shell.h;
    const double E = c->material.E;
    const double mg = c->popper.net_weight;
    const double m = c->popper.moving_mass();
    if (R > 0.0 && h > 0.0 && E > 0.0) {
      if (a.r_star) a.alpha_r = *a.r_star / theory::r_c(h, R);
      if (a.e_star) a.alpha_e = *a.e_star / theory::e_c(h);
      if (a.F_star) a.alpha_F = *a.F_star / theory::F_c(E, h, R);
      if (a.F_star_plate) a.alpha_F_plate = *a.F_star_plate / theory::F_c(E, h, R);
      if (a.t_star && m > 0.0) a.alpha_t = *a.t_star / theory::t_c(m, E, h, R);
      if (a.t_star && c->popper.mass > 0.0)
        a.alpha_t_own = *a.t_star / theory::t_c(c->popper.mass, E, h, R);
      if (a.t_star && mg > 0.0)
        a.alpha_t_net = *a.t_star / theory::t_c(mg / config::kStandardGravity, E, h, R);
      if (a.H_s && mg > 0.0) a.H_s_scaled = *a.H_s / (E * h * h * h * h / (mg * R));
    }
    if (a.F_star && mg > 0.0) {
      a.F_star_over_mg = *a.F_star / mg;
      if (a.outcome == theory::Outcome::Jump && *a.F_star < mg) {
        a.warnings.push_back(fmt::format(
            "suspicious Jump: F* = {} N is below the net weight mg = {} N, which the popper "
            "cannot leave the plate with; check the force offset and the threshold",
            *a.F_star, mg));
      }
    }
  }
  return a;
}

std::string contradiction(const Analysis& a) {
  if (!a.outcome) {
    return a.undetermined.empty() ? "no outcome, and no reason for it was recorded" : "";
  }
  const bool flew = a.flight_rise && a.flight_threshold && *a.flight_rise > *a.flight_threshold;
  switch (*a.outcome) {
    case theory::Outcome::NoSnap:
      if (flew) {
        return fmt::format(
            "No snap, but the popper flew: z rose {:.4g} mm above its height at the lift-off "
            "(t = {:.6g} s), more than the {:.3g} mm that make a flight",
            1e3 * *a.flight_rise, a.t_lift_off.value_or(NAN), 1e3 * *a.flight_threshold);
      }
      break;
    case theory::Outcome::Thrown:
      if (!flew) return "Thrown, but no flight in the record rose above the flight threshold";
      break;
    case theory::Outcome::Jump:
      if (!a.t_launch) return "Jump, but no launch was found";
      break;
    case theory::Outcome::Snap:
      if (!a.t_onset) return "Snap, but no onset was found";
      break;
  }
  return "";
}

nlohmann::json to_json(const Analysis& a) {
  using nlohmann::json;
  const auto num = [](const std::optional<double>& v) {
    return v && std::isfinite(*v) ? json(*v) : json(nullptr);
  };
  struct Row {
    const char* key;
    const std::optional<double>& value;
    const char* unit;
    const char* label;
  };
  const Row rows[] = {
      {"R", a.R, "m", "shell radius used for w / R"},
      {"t_onset", a.t_onset, "s", "transition onset"},
      {"r_star", a.r_star, "m", "r*, contact radius at the onset"},
      {"e_star", a.e_star, "m", "e*, apex displacement at the onset"},
      {"F_star", a.F_star, "N", "F*, force peak after the onset"},
      {"t_F_star", a.t_F_star, "s", "time of the force peak"},
      {"F_star_plate", a.F_star_plate, "N", "F* through a force plate (plate_frequency)"},
      {"force_noise", a.force_noise, "N", "noise of F at the end of the record"},
      {"force_threshold", a.force_threshold, "N", "launch threshold on F"},
      {"t_launch", a.t_launch, "s", "launch"},
      {"t_star", a.t_star, "s", "t*, onset to launch"},
      {"H", a.H, "m", "H, maximum height of the container"},
      {"H_l", a.H_l, "m", "H_l, container height at the onset"},
      {"H_s", a.H_s, "m", "H_s = H - H_l"},
      {"delta_p_onset", a.delta_p_onset, "Pa", "delta_p at the onset"},
      {"e_apex_star", a.e_apex_star, "m", "apex displacement at the onset (e* + w)"},
      {"t_force_rise", a.t_force_rise, "s", "foot of the force's rise to F*"},
      {"t_star_rise", a.t_star_rise, "s", "force rise to launch"},
      {"t_landing", a.t_landing, "s", "first sample back on the plate after the flight"},
      {"t_lift_off", a.t_lift_off, "s", "lift-off of the record's highest flight"},
      {"flight_rise", a.flight_rise, "m", "rise of z in that flight above its lift-off height"},
      {"flight_threshold", a.flight_threshold, "m", "least rise of z that makes a flight"},
      {"alpha_r", a.alpha_r, "1", "r* / sqrt(h R)"},
      {"alpha_e", a.alpha_e, "1", "e* / h"},
      {"alpha_F", a.alpha_F, "1", "F* / (E h^3 / R)"},
      {"alpha_F_plate", a.alpha_F_plate, "1", "F* through the plate / (E h^3 / R)"},
      {"alpha_t", a.alpha_t, "1", "t* / sqrt(m R / (E h^2)), m = popper + counterweight"},
      {"alpha_t_own", a.alpha_t_own, "1", "t* / sqrt(m_p R / (E h^2)), m_p = the popper alone"},
      {"alpha_t_net", a.alpha_t_net, "1", "t* / sqrt((mg / g) R / (E h^2)), the net weight's mass"},
      {"H_s_scaled", a.H_s_scaled, "1", "H_s / (E h^4 / (m g R))"},
      {"F_star_over_mg", a.F_star_over_mg, "1", "F* / (m g)"},
  };
  json quantities = json::object();
  for (const auto& r : rows) {
    quantities[r.key] = {{"value", num(r.value)}, {"unit", r.unit}, {"label", r.label}};
  }
  return json{
      {"units", "SI"},
      {"outcome", a.outcome ? json(theory::to_string(*a.outcome)) : json(nullptr)},
      {"undetermined", a.undetermined.empty() ? json(nullptr) : json(a.undetermined)},
      {"onset_source",
       a.onset_source == OnsetSource::None ? json(nullptr) : json(to_string(a.onset_source))},
      {"quantities", quantities},
      {"warnings", a.warnings},
  };
}

void write_json(std::ostream& out, const Analysis& a) { out << to_json(a).dump(2) << '\n'; }

}  // namespace snapjump::measure
