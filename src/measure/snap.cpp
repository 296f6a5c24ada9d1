// The snap's stages: the record's preparation, the onset, and the snap's window with F*, the
// launch, the landing and the force's rise, read from the contact transition or from the force
// alone (docs/analysis.md, "Definitions" and "Force-plate records").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "config/plausibility.hpp"
#include "measure/signal.hpp"
#include "measure/stages.hpp"

namespace snapjump::measure::stages {

using signal::crossing_time;
using signal::interpolate;
using signal::kMinNoiseSamples;
using signal::robust_sigma;
using signal::upper_median;

Context::Context(const TimeSeries& s, const AnalysisOptions& o, const config::Case* cs,
                 Analysis& an)
    : series(s), options(o), c(cs), a(an), t(s.time()), F(s.column(kForce)), n(t.size()) {
  plate_noise = signal::sample_noise(F);
  rise_floor = o.noise_multiple * plate_noise;
}

void Context::put(std::string_view key, double value, std::string source) {
  const auto* q = find_quantity(key);
  a.*(q->field) = value;
  a.sources[std::string(key)] = std::move(source);
}

std::string merge_sources(std::string_view a, std::string_view b) {
  // "t, w" and "t, w, F, z; case h" -> "t, w, F, z; case h": the columns once each, in order.
  std::vector<std::string> columns;
  std::string rest;
  for (const auto text : {a, b}) {
    const auto semi = text.find(';');
    std::string_view cols = text.substr(0, semi);
    if (semi != std::string_view::npos) {
      rest += std::string(rest.empty() ? "" : ", ") + std::string(text.substr(semi + 2));
    }
    while (!cols.empty()) {
      const auto comma = cols.find(", ");
      const std::string item(cols.substr(0, comma));
      if (!item.empty() && std::find(columns.begin(), columns.end(), item) == columns.end()) {
        columns.push_back(item);
      }
      if (comma == std::string_view::npos) break;
      cols.remove_prefix(comma + 2);
    }
  }
  return fmt::format("{}{}{}", fmt::join(columns, ", "), rest.empty() ? "" : "; ", rest);
}

std::optional<double> Context::threshold_cap() const {
  if (!weight || !(*weight > 0.0)) return std::nullopt;
  return options.weight_fraction * *weight;
}

double LaunchRule::level(double F_peak) const {
  if (options->force_threshold) return *options->force_threshold;
  const double l =
      std::max(options->relative_threshold * F_peak, options->noise_multiple * noise.value_or(0.0));
  return cap ? std::min(l, *cap) : l;
}

double LaunchRule::flight_ceiling(double level, double deepest, double F_peak) const {
  double allowance = kQuiet * F_peak;
  if (cap) allowance = std::min(allowance, *cap);
  return std::min(level - deepest, std::max(level, allowance));
}

double LaunchRule::landing_ceiling(double F_peak) const {
  double c = kQuiet * F_peak;
  if (cap) c = std::min(c, *cap);
  return std::max(level(F_peak), c);
}

// From the window's first sample on, with the force peak so far as F*, the first crossing of F
// below the threshold after that peak such that, for min_flight_time (or to the end of the
// record), F stays below the threshold (raised by as much as F dips below zero then: a plate rings
// on after the launch) and below it on average, and, with a z column, the container is higher at
// the end of that time than at the crossing. The snap ends there: a landing later in the record,
// however hard, is not its force.
std::optional<Launch> find_launch(const TimeSeries& s, const LaunchRule& rule, std::size_t first,
                                  std::size_t last, std::vector<std::string>& warnings) {
  const auto& o = *rule.options;
  const auto t = s.time();
  const auto F = s.column(kForce);
  const std::size_t n = t.size();
  std::size_t peak = first;
  for (std::size_t k = first + 1; k < n && k <= last; ++k) {
    if (F[k] > F[peak]) {
      peak = k;
      continue;
    }
    const double level = rule.level(F[peak]);
    if (F[k] >= level || F[k - 1] < level || !(F[peak] > level)) continue;
    // F[k - 1] >= level > F[k]: the first sample of a candidate stretch below the threshold.
    const double t_cross = crossing_time(t, F, k, level);
    // In flight a plate rings on after the launch, swinging below zero as far as above it: F
    // must stay below the threshold raised by its deepest dip below zero in that time, and below
    // the threshold on average. A force that stays positive (the shell still touching, lightly)
    // gets no such allowance.
    double deepest = 0.0;
    for (std::size_t i = k; i < n && t[i] <= t_cross + o.min_flight_time; ++i) {
      deepest = std::min(deepest, F[i]);
    }
    const double ceiling = rule.flight_ceiling(level, deepest, F[peak]);
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
        warnings.push_back(fmt::format(
            "F falls below the launch threshold at t = {:.6g} s while the container is not rising "
            "(z from {:.4g} to {:.4g} mm in the next {:.3g} ms): not a launch",
            t_cross, 1e3 * z_at, 1e3 * z_after, 1e3 * (t_after - t_cross)));
        while (j < n && F[j] < ceiling) ++j;
        k = j - 1;  // the loop's ++k looks at sample j next: it may be a new peak
        continue;
      }
    }
    if (stays) {
      if (j == n && t.back() - t_cross < o.min_flight_time) {
        warnings.push_back(fmt::format(
            "the record ends {} ms after the launch, before F has stayed below the threshold "
            "for {} ms",
            1e3 * (t.back() - t_cross), 1e3 * o.min_flight_time));
      }
      return Launch{peak, t_cross};
    }
    // Not a launch from this crossing: the scan goes on with the next sample, so that a later
    // crossing inside the same stretch (a plate ringing down) and a new peak are both seen.
  }
  return std::nullopt;
}

std::optional<std::size_t> landing_after(const Context& x, std::size_t from, double t_launch,
                                         double ceiling) {
  std::size_t k = from;
  while (k < x.n && (x.t[k] <= t_launch + x.options.min_flight_time || x.F[k] < ceiling)) ++k;
  return k < x.n ? std::optional<std::size_t>(k) : std::nullopt;
}

namespace {

// The noise of F after the snap's peak: the robust spread over the final part of the record,
// counted only from the first sample after the peak where F is about zero (below kQuiet F* and
// the threshold cap), and only if F is about zero there (in flight). When the record goes on past
// a landing (F back on the weight at its end), the longest stretch of the window where F stays
// about zero is used instead, if its median is within relative_threshold F* of zero (a flight).
void estimate_noise(Context& x, std::size_t first, std::size_t peak, double F_star) {
  const auto t = x.t;
  const auto F = x.F;
  const auto& o = x.options;
  const std::size_t n = x.n;
  double quiet = kQuiet * F_star;
  if (const auto cap = x.threshold_cap()) quiet = std::min(quiet, *cap);
  const double t_from = t.back() - o.noise_window_fraction * (t.back() - t.front());
  std::size_t from = peak + 1;
  while (from < n && F[from] >= quiet) ++from;
  std::vector<double> tail;
  for (std::size_t i = from; i < n; ++i) {
    if (t[i] >= t_from) tail.push_back(F[i]);
  }
  std::optional<double> median;
  if (tail.size() >= kMinNoiseSamples) {
    median = upper_median(tail);
    if (std::abs(*median) <= quiet) {
      x.put("force_noise", robust_sigma(std::move(tail)), "t, F (the record's end, in flight)");
      return;
    }
  }
  // The longest stretch of the window with |F| about zero.
  std::size_t best_from = 0, best_len = 0;
  for (std::size_t i = first; i < n;) {
    if (std::abs(F[i]) >= quiet) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && std::abs(F[j]) < quiet) ++j;
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
      x.put("force_noise", robust_sigma(std::move(stretch)), "t, F (the flight)");
      return;
    }
  }
  if (median) {
    x.a.warnings.push_back(fmt::format(
        "F is not near zero at the end of the record (median {} N) and never stays near zero "
        "after the peak: no noise estimate, the launch threshold is {} F* alone",
        *median, o.relative_threshold));
  }
}

// The resting force: the median of F over [0, foot), and with it the weight the thresholds are
// held below (the case's net weight when it gives one).
void rest_before(Context& x, std::size_t foot) {
  if (foot >= kMinNoiseSamples) {
    x.put("F_rest", signal::median_of(x.F, 0, foot), "t, F");
  } else {
    x.a.F_rest.reset();
    x.a.sources.erase("F_rest");
  }
  if (x.c != nullptr && x.c->popper.net_weight > 0.0) {
    x.weight = x.c->popper.net_weight;
  } else if (x.a.F_rest && *x.a.F_rest > 0.0) {
    x.weight = *x.a.F_rest;
  } else {
    x.weight.reset();
  }
}

// The foot of the rise to F* at sample `peak` and t*_rise = launch - foot.
void force_rise(Context& x, std::size_t peak, const std::string& source) {
  const auto rise = signal::rise_start(x.F, peak, x.rise_floor);
  x.put("t_force_rise", signal::rise_time(x.t, x.F, peak, rise), source);
  if (x.a.t_launch) {
    x.put("t_star_rise", *x.a.t_launch - *x.a.t_force_rise, x.a.source("t_launch"));
  }
}

// The threshold for a launch, said when it stands above what it should detect.
void report_threshold(Context& x, const LaunchRule& rule, const std::string& source) {
  x.put("force_threshold", rule.level(*x.a.F_star), source);
  const double level = *x.a.force_threshold;
  if (x.options.force_threshold && x.weight && level >= x.options.weight_fraction * *x.weight) {
    x.a.warnings.push_back(fmt::format(
        "the launch threshold given, {:.4g} N, is not below half the net weight on the plate "
        "({:.4g} N): a popper standing on the plate can read as off it",
        level, *x.weight));
  }
  if (!x.a.t_launch && *x.a.F_star > 0.0 && level >= *x.a.F_star) {
    x.a.warnings.push_back(fmt::format(
        "the launch threshold {} N is not below the force peak F* = {} N: no launch can be found",
        level, *x.a.F_star));
  }
}

// Why a snap without a launch has no outcome yet: the record stops too soon after the peak.
std::string ends_before_settled(const Context& x) {
  return fmt::format(
      "the record ends {:.3g} ms after the force peak, before the popper can be seen to leave "
      "the plate or stay on it (the analysis waits {:.3g} ms, option settle_time; or say the "
      "record is complete)",
      1e3 * (x.t.back() - *x.a.t_F_star), 1e3 * x.options.settle_time);
}

}  // namespace

void prepare(Context& x) {
  auto& a = x.a;
  for (const auto& note : x.series.notes()) a.warnings.push_back(fmt::format("reading: {}", note));
  if (x.options.R) {
    x.put("R", *x.options.R, "option R");
  } else if (x.c != nullptr && x.c->shell.R > 0.0) {
    x.put("R", x.c->shell.R, "case shell.R");
  }
  // A radius outside a popper's is most likely a bare number taken as metres.
  if (const auto* range = config::plausible_range("shell.R"); a.R && !range->holds(*a.R)) {
    a.warnings.push_back(fmt::format(
        "R = {:.6g} m is not the radius of a popper's shell (that lies within {}): a bare number "
        "is read in SI units, metres: 30 means 30 m; write \"30 mm\"",
        *a.R, range->text));
  }
}

void find_onset(Context& x) {
  auto& a = x.a;
  const auto& s = x.series;
  const auto t = x.t;
  x.can_tell = (s.has(kApexGap) && a.R) || s.has_contact();
  if (s.has(kApexGap) && a.R) {
    const auto w = s.column(kApexGap);
    const double level = x.options.onset_ratio * *a.R;
    const auto it = std::find_if(w.begin(), w.end(), [&](double v) { return v < level; });
    if (it == w.end()) return;
    const auto i = static_cast<std::size_t>(it - w.begin());
    a.onset_source = OnsetSource::ApexGap;
    x.onset_columns = "t, w";
    if (i == 0) {
      x.put("t_onset", t[0], x.onset_columns);
      a.warnings.push_back(fmt::format(
          "w / R is below {} already at the first sample: the onset is taken at the start of the "
          "record, t = {} s",
          x.options.onset_ratio, t[0]));
    } else {
      x.put("t_onset", crossing_time(t, w, i, level), x.onset_columns);
    }
    x.onset = i;
    return;
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
    const auto cs = s.contact();
    const auto it = std::find(cs.begin(), cs.end(), ContactState::Disk);
    if (it == cs.end()) return;
    const auto i = static_cast<std::size_t>(it - cs.begin());
    a.onset_source = OnsetSource::ContactDisk;
    x.onset_columns = "t, contact";
    x.put("t_onset", t[i], x.onset_columns);
    x.onset = i;
  }
}

namespace {

// The snap's window on the contact transition: from the foot of the force's rise into the onset
// to the popper's leaving the plate (or the shell's return to a ring contact).
struct SnapWindow {
  std::size_t first = 0;        // the foot of the force's rise
  std::size_t last = 0;         // the window's end
  std::size_t search_last = 0;  // the launch's crossing is looked for up to here
  std::optional<std::size_t> contact_lost;
  bool ring_again = false;
  bool launch_from_contact = false;
  std::size_t peak = 0;  // F*'s sample
};

void snap_values_at_onset(Context& x) {
  const auto& series = x.series;
  const double t_on = *x.a.t_onset;
  const auto at_onset = [&](std::string_view key, std::string_view column) {
    if (series.has(column)) {
      x.put(key, interpolate(x.t, series.column(column), t_on),
            fmt::format("{}, {}", x.onset_columns, column));
    }
  };
  at_onset("r_star", kContactRadius);
  at_onset("e_star", kIndentation);
  at_onset("e_apex_star", kApexDisplacement);
  at_onset("H_l", kHeight);
  at_onset("delta_p_onset", kPressure);
}

// The first sample from `from` on that starts a run of samples meeting `holds` that lasts at
// least `least` [s] (to the sample after it, or to the last one where the record ends there).
template <typename Holds>
std::optional<std::size_t> first_lasting(std::span<const double> t, std::size_t from, double least,
                                         Holds holds) {
  const std::size_t n = t.size();
  for (std::size_t i = from; i < n; ++i) {
    if (!holds(i)) continue;
    std::size_t j = i;
    while (j + 1 < n && holds(j + 1)) ++j;
    const double until = j + 1 == n ? t[j] : t[j + 1];
    if (until - t[i] >= least) return i;
    i = j;
  }
  return std::nullopt;
}

// The end of the snap's window (SnapWindow::first is left to the caller).
SnapWindow snap_window_end(const Context& x) {
  const auto& a = x.a;
  const auto& series = x.series;
  const auto& options = x.options;
  const auto t = x.t;
  const auto F = x.F;
  const std::size_t n = x.n;
  SnapWindow win;
  // The snap lasts until the popper leaves the plate or the shell goes back to a ring contact:
  // the apex again above the onset level while the plate still pushes, for min_flight_time
  // (after a snap without a launch, the suction can pull the shell back in and the popper lands
  // on it again; that landing is not the snap's force; a flicker of w about the level as the
  // apex settles is no return). F* and the launch are looked for within it.
  win.last = n - 1;
  if (a.onset_source == OnsetSource::ApexGap) {
    const auto w = series.column(kApexGap);
    const double level = options.onset_ratio * *a.R;
    const auto ring = first_lasting(t, *x.onset + 1, options.min_flight_time,
                                    [&](std::size_t i) { return w[i] > level && F[i] > 0.0; });
    if (ring) {
      win.last = *ring;
      win.ring_again = true;
    }
  }
  // A contact column that says "none" for min_flight_time after the onset: the popper is off the
  // plate, whatever F reads (a plate ringing, an offset); the snap's window ends there.
  if (series.has_contact()) {
    const auto cs = series.contact();
    const auto lost = first_lasting(t, *x.onset + 1, options.min_flight_time,
                                    [&](std::size_t i) { return cs[i] == ContactState::None; });
    if (lost && *lost <= win.last) {
      win.contact_lost = *lost;
      win.last = *lost;
    }
  }
  // The launch's crossing of the threshold may come up to min_flight_time after the contact
  // is lost (the plate rings on).
  win.search_last = win.last;
  if (win.contact_lost) {
    while (win.search_last + 1 < n &&
           t[win.search_last + 1] <= t[win.last] + options.min_flight_time) {
      ++win.search_last;
    }
  }
  return win;
}

// F*'s sample and the launch within the window (from F, or else from the contact column).
void snap_peak_and_launch(Context& x, SnapWindow& win, LaunchRule& rule,
                          const std::string& force_columns) {
  auto& a = x.a;
  const auto t = x.t;
  const auto F = x.F;
  const auto window_peak = static_cast<std::size_t>(
      std::max_element(F.begin() + static_cast<std::ptrdiff_t>(win.first),
                       F.begin() + static_cast<std::ptrdiff_t>(win.last) + 1) -
      F.begin());
  win.peak = window_peak;
  if (!(F[window_peak] > 0.0)) {
    a.warnings.push_back(
        fmt::format("F is never positive after the onset (peak {} N): no launch", F[window_peak]));
    return;
  }
  estimate_noise(x, win.first, window_peak, F[window_peak]);
  rule.noise = a.force_noise;
  // The first launch ends the snap: the force peak is the largest before it (a landing later
  // in the record is not the snap's force).
  if (const auto launch = find_launch(x.series, rule, win.first, win.search_last, a.warnings)) {
    win.peak = launch->peak;
    x.put("t_launch", launch->t, force_columns);
    std::size_t k = win.peak + 1;
    while (k < x.n && t[k] < *a.t_launch) ++k;
    win.last = std::min(win.last, k);
  } else if (win.contact_lost) {
    win.launch_from_contact = true;
    x.put("t_launch", t[*win.contact_lost], "t, contact");
    a.warnings.push_back(fmt::format(
        "F does not stay below the launch threshold, but the contact column says the shell is "
        "off the plate from t = {:.6g} s: the launch is taken from the contact column",
        t[*win.contact_lost]));
  }
}

// The landing after the launch: from F, or from the contact column when F could not tell the
// flight.
void snap_landing(Context& x, const SnapWindow& win, const LaunchRule& rule) {
  auto& a = x.a;
  const auto t = x.t;
  const std::size_t n = x.n;
  if (!a.t_launch) return;
  if (win.launch_from_contact) {
    // F could not tell the flight (it never stayed low): the contact column tells the end.
    const auto cs = x.series.contact();
    std::size_t k = win.last;
    while (k < n &&
           (t[k] <= *a.t_launch + x.options.min_flight_time || cs[k] == ContactState::None)) {
      ++k;
    }
    if (k < n) x.landing = k;
    if (x.landing) x.put("t_landing", t[k], "t, contact");
  } else {
    x.landing = landing_after(x, win.last, *a.t_launch, rule.landing_ceiling(*a.F_star));
    if (x.landing) x.put("t_landing", t[*x.landing], "t, F");
  }
}

// F* as the plate model shows it, when the options give the plate's frequency.
void snap_plate_peak(Context& x, const SnapWindow& win) {
  const auto& options = x.options;
  if (!options.plate_frequency) return;
  const auto t = x.t;
  const auto plate = plate_response(t, x.F, *options.plate_frequency, options.plate_damping);
  // The plate lags: its peak may come up to a period after the raw window's end.
  const double until = t[win.last] + 1.0 / *options.plate_frequency;
  std::size_t end = win.last + 1;
  while (end < x.n && t[end] <= until) ++end;
  x.put("F_star_plate",
        *std::max_element(plate.begin() + static_cast<std::ptrdiff_t>(win.first),
                          plate.begin() + static_cast<std::ptrdiff_t>(end)),
        fmt::format("{}, F (through the plate model)", x.onset_columns));
}

// t*, or why the snap settles without a launch, or why the record cannot tell.
void snap_conclusion(Context& x, const SnapWindow& win) {
  auto& a = x.a;
  const auto& options = x.options;
  const auto t = x.t;
  const double t_on = *a.t_onset;
  // After a launch the apex rises with the popper (and a noisy F may be above 0): only without
  // one does the shell's return to a ring contact say something.
  if (win.ring_again && !a.t_launch) {
    a.warnings.push_back(fmt::format(
        "the shell is back on a ring contact at t = {:.6g} s (w / R above {} while F > 0) "
        "without having left the plate: F* is the largest force before that",
        t[win.last], options.onset_ratio));
  }
  if (a.t_launch && *a.t_launch < t_on) {
    // The popper left the plate before the apex came down: no snap from the plate. When z shows
    // the flight, the run is Thrown (decide); otherwise this stays the reason.
    a.undetermined = fmt::format(
        "the popper left the plate at t = {:.6g} s, before the onset (w / R < {} only at t = "
        "{:.6g} s): no snap from the plate to measure, and z does not show a flight (a rise "
        "above the flight threshold) that would make it Thrown",
        *a.t_launch, options.onset_ratio, t_on);
    a.t_star_rise.reset();
    a.sources.erase("t_star_rise");
  } else if (a.t_launch) {
    x.put("t_star", *a.t_launch - t_on, merge_sources(x.onset_columns, a.source("t_launch")));
  } else if (win.ring_again || options.complete || t.back() - *a.t_F_star >= options.settle_time) {
    x.snap_settled = true;
  } else {
    a.undetermined = ends_before_settled(x);
  }
}

}  // namespace

void snap_from_transition(Context& x) {
  const auto& on = x.onset_columns;
  const auto F = x.F;
  x.snap_seen = true;
  snap_values_at_onset(x);
  SnapWindow win = snap_window_end(x);
  // The snap's force can rise, and even peak, before the apex criterion fires (a gradual
  // eversion): the window starts at the foot of the force's rise into the onset.
  // (When the onset lies on the falling flank of a peak, the rise to that peak.)
  win.first =
      signal::rise_start(F, signal::peak_behind(F, *x.onset, x.rise_floor), x.rise_floor).index;
  rest_before(x, win.first);
  const std::string force_columns = fmt::format("{}, F{}", on, x.series.has(kHeight) ? ", z" : "");
  LaunchRule rule{&x.options, std::nullopt, x.threshold_cap()};
  snap_peak_and_launch(x, win, rule, force_columns);
  x.put("F_star", F[win.peak], fmt::format("{}, F", on));
  x.put("t_F_star", x.t[win.peak], fmt::format("{}, F", on));
  report_threshold(x, rule, "t, F");
  snap_landing(x, win, rule);
  snap_plate_peak(x, win);
  force_rise(x, win.peak, "t, F");
  snap_conclusion(x, win);
}

void snap_from_force(Context& x) {
  auto& a = x.a;
  const auto& options = x.options;
  const auto t = x.t;
  const auto F = x.F;
  const std::size_t n = x.n;
  a.basis = Basis::ForceOnly;
  x.can_tell = true;
  a.warnings.push_back(
      "no w column (with R) and no contact column: the snap is read from the force alone (no "
      "onset, r*, e* or t*; t* from the force's rise, t_star_rise), and a throw without the snap "
      "cannot be told from a Jump");
  // The plate's noise from its sample-to-sample changes: the force alone says nothing of where
  // the popper is before the snap is found.
  x.put("force_noise", x.plate_noise, "t, F (sample-to-sample changes)");
  if (x.c != nullptr && x.c->popper.net_weight > 0.0) x.weight = x.c->popper.net_weight;
  LaunchRule rule{&options, a.force_noise, x.threshold_cap()};
  // The first launch in the record, and the peak before it; then the resting force before that
  // peak's rise holds the thresholds below the weight, and the launch is looked for again.
  std::vector<std::string> first_try;
  auto launch = find_launch(x.series, rule, 0, n - 1, first_try);
  const auto peak_of = [&](const std::optional<Launch>& l) {
    return l ? l->peak : static_cast<std::size_t>(std::max_element(F.begin(), F.end()) - F.begin());
  };
  rest_before(x, signal::rise_start(F, peak_of(launch), x.rise_floor).index);
  if (!rule.cap && x.threshold_cap()) {
    rule.cap = x.threshold_cap();
    first_try.clear();
    launch = find_launch(x.series, rule, 0, n - 1, first_try);
  }
  a.warnings.insert(a.warnings.end(), first_try.begin(), first_try.end());
  const std::size_t peak = peak_of(launch);
  rest_before(x, signal::rise_start(F, peak, x.rise_floor).index);
  x.put("F_star", F[peak], "t, F");
  x.put("t_F_star", t[peak], "t, F");
  const std::string launch_columns = x.series.has(kHeight) ? "t, F, z" : "t, F";
  if (launch) x.put("t_launch", launch->t, launch_columns);
  report_threshold(x, rule, "t, F");
  force_rise(x, peak, "t, F");
  if (launch) {
    std::size_t k = peak + 1;
    while (k < n && t[k] < launch->t) ++k;
    x.landing = landing_after(x, k, launch->t, rule.landing_ceiling(*a.F_star));
    if (x.landing) x.put("t_landing", t[*x.landing], "t, F");
  }
  // A snap's peak stands clear of the resting force.
  const double margin = std::max(2.0 * options.noise_multiple * x.plate_noise,
                                 options.snap_fraction * a.F_rest.value_or(0.0));
  x.snap_seen = a.F_rest && *a.F_star - *a.F_rest > margin;
  if (!a.F_rest) {
    a.undetermined = fmt::format(
        "the record starts with the force's rise (fewer than {} samples before it): no resting "
        "force to tell a snap's peak from",
        kMinNoiseSamples);
  } else if (a.t_launch && !x.snap_seen) {
    a.undetermined = fmt::format(
        "F falls to about zero at t = {:.6g} s (the popper off the plate) without a force peak "
        "before it that stands clear of the resting force {:.4g} N (by more than {:.3g} N): no "
        "snap to read from the force",
        *a.t_launch, *a.F_rest, margin);
  } else if (!a.t_launch && x.snap_seen) {
    if (options.complete || t.back() - *a.t_F_star >= options.settle_time) {
      x.snap_settled = true;
    } else {
      a.undetermined = ends_before_settled(x);
    }
  } else if (!a.t_launch) {
    a.warnings.push_back(fmt::format(
        "no force peak stands clear of the resting force {:.4g} N (F* = {:.4g} N, by less than "
        "{:.3g} N): no snap in the force",
        *a.F_rest, *a.F_star, margin));
  }
}

}  // namespace snapjump::measure::stages
