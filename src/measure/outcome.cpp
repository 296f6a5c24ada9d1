// The stages after the snap: heights and the flight, the record's flights, a tared plate, the
// outcome and, with a case, the prefactors (docs/analysis.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "measure/signal.hpp"
#include "measure/stages.hpp"

namespace snapjump::measure::stages {

using signal::interpolate;
using signal::kMinNoiseSamples;
using signal::robust_sigma;

namespace {

// A stretch off the plate by the launch rule, from the lift-off (F's crossing below the threshold)
// to the landing (the first sample, min_flight_time or more after the lift-off, with F back above
// the launch's ceiling; the record's end when there is none), and how far z rose in it above its
// height at the lift-off (none without a z column).
struct Flight {
  double t_lift_off = 0.0;
  double t_landing = std::numeric_limits<double>::infinity();
  std::optional<double> rise;
};

// Every flight in the record, in order: the launch rule from the record's start, and again from
// each landing, with the plate's noise from its sample-to-sample changes. (The snap's launch takes
// the noise after its peak instead, where a flight follows it.)
std::vector<Flight> find_flights(const Context& x) {
  const auto t = x.t;
  const auto F = x.F;
  const std::size_t n = x.n;
  std::vector<Flight> flights;
  const LaunchRule rule{&x.options, x.plate_noise, x.threshold_cap()};
  std::size_t start = 0;
  while (start + 1 < n) {
    std::vector<std::string> ignored;  // the snap window's business, not the flights'
    const auto launch = find_launch(x.series, rule, start, n - 1, ignored);
    if (!launch) break;
    Flight f;
    f.t_lift_off = launch->t;
    std::size_t k = launch->peak;
    while (k < n && t[k] < f.t_lift_off) ++k;
    const std::size_t first = k;
    const auto landing = landing_after(x, k, f.t_lift_off, rule.landing_ceiling(F[launch->peak]));
    k = landing.value_or(n);
    if (landing) f.t_landing = t[k];
    if (x.series.has(kHeight)) {
      const auto z = x.series.column(kHeight);
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

// The record's flights, its highest one and the threshold of a flight put into the analysis.
std::vector<Flight> report_flights(Context& x) {
  auto flights = find_flights(x);
  if (!x.series.has(kHeight)) return flights;
  x.put("flight_threshold", flight_threshold(x.series.column(kHeight), x.options), "t, z");
  for (const auto& f : flights) {
    if (f.rise && (!x.a.flight_rise || *f.rise > *x.a.flight_rise)) {
      x.put("flight_rise", *f.rise, "t, F, z");
      x.put("t_lift_off", f.t_lift_off, "t, F, z");
    }
  }
  return flights;
}

// The outcome, in one place. On entry a.undetermined says why the record cannot settle the outcome
// of a snap on the plate or of no onset (empty when it can); a flight without the contact
// transition on the plate before it overrides that (Thrown), where the transition can be seen.
void decide_outcome(Context& x, const std::vector<Flight>& flights) {
  auto& a = x.a;
  if (!x.can_tell || !x.force_trusted) return;  // a.undetermined says why
  const double threshold = a.flight_threshold.value_or(0.0);
  const bool transition = a.basis == Basis::Transition;
  if (const auto* thrown = transition ? thrown_flight(flights, a.t_onset, threshold) : nullptr) {
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
    for (const auto& fl : flights) {
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
  } else if (x.snap_seen) {
    if (x.snap_settled) a.outcome = theory::Outcome::Snap;
  } else if (transition && !x.series.has(kHeight) && !flights.empty()) {
    a.undetermined = fmt::format(
        "no onset, and F says the popper was off the plate from t = {:.6g} s: without a z column "
        "the record cannot show whether it flew, so it is not called No snap",
        flights.front().t_lift_off);
  } else {
    a.outcome = theory::Outcome::NoSnap;
  }
}

}  // namespace

void heights(Context& x) {
  auto& a = x.a;
  if (!x.series.has(kHeight)) return;
  // The highest z of the first flight (up to the landing, when the record goes on past it).
  const auto z = x.series.column(kHeight);
  const auto top = std::max_element(
      z.begin(), x.landing ? z.begin() + static_cast<std::ptrdiff_t>(*x.landing) + 1 : z.end());
  x.put("H", *top, x.landing ? "t, F, z" : "t, z");
  if (a.H_l) x.put("H_s", *a.H - *a.H_l, merge_sources(a.source("H_l"), a.source("H")));
  if (a.t_launch) {
    const double z_launch = interpolate(x.t, z, *a.t_launch);
    const auto from = static_cast<std::size_t>(
        std::lower_bound(x.t.begin(), x.t.end(), *a.t_launch) - x.t.begin());
    const std::size_t to = x.landing.value_or(x.n - 1);
    double z_top = z_launch;
    for (std::size_t i = from; i <= to; ++i) z_top = std::max(z_top, z[i]);
    x.put("H_flight", z_top - z_launch, "t, F, z");
    a.flight_rule = "from z: the highest z of the flight less z at the launch";
  }
  if (a.t_launch && static_cast<std::size_t>(top - z.begin()) == x.n - 1 &&
      signal::rise_left(x.t, z) > 0.01 * (a.H_s ? *a.H_s : *a.H)) {
    a.warnings.push_back(
        "z is highest at the last sample: the record may end before the top of the flight, so H "
        "and H_s are lower bounds, and H_flight too");
  }
}

void flight(Context& x) {
  auto& a = x.a;
  if (!a.t_launch || !a.t_landing) return;
  const double T = *a.t_landing - *a.t_launch;
  x.put("flight_time", T, a.source("t_landing"));
  if (x.series.has(kHeight)) return;  // H_flight from z (heights)
  // A ballistic flight that leaves and lands at one height rises a T^2 / 8.
  constexpr double g = config::kStandardGravity;
  double decel = g;
  std::string source = "t, F; free flight, g";
  if (x.c == nullptr) {
    a.flight_rule =
        "free flight, a = g (no case: a counterweight on a pulley would make the deceleration "
        "(m_popper - m_counterweight) g / (m_popper + m_counterweight), smaller than g; give the "
        "case for its masses)";
    a.warnings.push_back(fmt::format(
        "H_flight = g T^2 / 8 = {:.4g} mm assumes a free flight (no case): with a counterweight on "
        "a pulley the flight decelerates at (m_popper - m_counterweight) g / (m_popper + "
        "m_counterweight) and rises less; give the case (its popper.net_weight and popper.mass)",
        1e3 * g * T * T / 8.0));
  } else {
    const auto& p = x.c->popper;
    const double m = p.moving_mass();
    decel = m > 0.0 ? p.net_weight / m : g;
    source = "t, F; case popper.net_weight, popper.mass";
    const bool defaulted =
        std::any_of(x.c->defaults_used.begin(), x.c->defaults_used.end(),
                    [](const std::string& d) { return d.starts_with("popper.mass"); });
    a.flight_rule = fmt::format(
        "a = net_weight / (popper + counterweight) = (m_popper - m_counterweight) g / (m_popper + "
        "m_counterweight) = {:.4g} m/s^2 (m_popper {:.4g} kg, m_counterweight {:.4g} kg{}; a "
        "rigid wire, the rail's friction neglected)",
        decel, p.mass, p.counterweight(), defaulted ? ", the case's default mass" : "");
    if (p.wire_stiffness) {
      a.warnings.push_back(
          "the case gives the wire a stiffness: H_flight uses the rigid wire's deceleration, "
          "which a stretching wire does not hold to");
    }
    if (defaulted) {
      a.warnings.push_back(fmt::format(
          "H_flight uses the case's default popper.mass ({:.4g} kg, an estimate): the "
          "counterweight's inertia sets the flight's deceleration; give the popper's mass",
          p.mass));
    }
  }
  x.put("flight_deceleration", decel, source);
  x.put("H_flight", decel * T * T / 8.0, source);
}

void settle_no_snap(Context& x) {
  auto& a = x.a;
  const auto& s = x.series;
  const auto& o = x.options;
  if (o.complete || x.snap_seen || !x.can_tell || !a.undetermined.empty()) return;
  const auto t = x.t;
  const char* none = a.basis == Basis::ForceOnly ? "no snap in the force" : "no onset";
  if (!s.has(kPressure)) {
    a.undetermined = fmt::format(
        "{} within the record (to t = {:.6g} s), and without a delta_p column the analysis "
        "cannot tell whether the suction was gone before it ended: the shell may still have "
        "snapped (say the record is complete if it covers the whole experiment)",
        none, t.back());
    return;
  }
  // The suction gone: delta_p down to zero after its largest value (a record that starts
  // before the suction is applied reads zero at first).
  const auto dp = s.column(kPressure);
  const auto top = std::max_element(dp.begin(), dp.end());
  const auto it = std::find_if(top, dp.end(), [](double v) { return v <= 0.0; });
  if (it == dp.end()) {
    a.undetermined = fmt::format(
        "{} within the record, which ends at t = {:.6g} s with delta_p = {:.4g} Pa of "
        "suction still holding the shell: it may still snap",
        none, t.back(), dp.back());
    return;
  }
  const double t_zero = t[static_cast<std::size_t>(it - dp.begin())];
  if (t.back() - t_zero < o.settle_time) {
    a.undetermined = fmt::format(
        "{} within the record, which ends {:.3g} ms after delta_p reached zero (at t = "
        "{:.6g} s): the analysis waits {:.3g} ms (option settle_time) before calling it No snap",
        none, 1e3 * (t.back() - t_zero), t_zero, 1e3 * o.settle_time);
  }
}

void onset_in_gaps(Context& x) {
  auto& a = x.a;
  if (!a.t_onset) return;
  // A value at the onset read from inside a sensor's dropout is an interpolation across it.
  for (const auto& g : x.series.gaps()) {
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

void check_tare(Context& x) {
  // A plate pushes and cannot pull: F held below zero says its zero is off (tared with the popper
  // standing on it, or offset), and then neither F* nor the launch threshold nor the outcome can be
  // trusted.
  auto& a = x.a;
  const auto F = x.F;
  const double range =
      *std::max_element(F.begin(), F.end()) - *std::min_element(F.begin(), F.end());
  const double level =
      std::max(kTareFraction * range, x.options.noise_multiple * a.force_noise.value_or(0.0));
  const auto neg = signal::negative_stretch(x.t, F, level, x.options.min_flight_time);
  if (!neg) return;
  const double median = signal::median_of(F, neg->first, neg->second + 1);
  std::string hint;
  if (x.c != nullptr && x.c->popper.net_weight > 0.0) {
    hint = fmt::format(" (the case's net weight is {:.4g} N)", x.c->popper.net_weight);
  }
  a.warnings.push_back(fmt::format(
      "F stays below zero (median {:.4g} N) for {:.3g} ms from t = {:.6g} s: a plate pushes "
      "and cannot pull, so the record looks tared or offset (the popper's weight subtracted?). "
      "F*, the launch and the outcome need F about 0 in flight: add the offset back "
      "(force_offset, --force-offset){}",
      median, 1e3 * (x.t[neg->second] - x.t[neg->first]), x.t[neg->first], hint));
  a.undetermined = "F's zero is off (the record looks tared): the force cannot tell a launch";
  x.force_trusted = false;
}

void decide(Context& x) {
  const auto flights = report_flights(x);
  decide_outcome(x, flights);
  if (const auto why = contradiction(x.a); !why.empty()) {
    x.a.warnings.push_back(
        fmt::format("the outcome {} is withdrawn: {}", outcome_text(x.a.outcome), why));
    x.a.outcome.reset();
    x.a.undetermined = why;
  }
}

void prefactors(Context& x) {
  auto& a = x.a;
  if (x.c == nullptr) return;
  const auto& c = *x.c;
  const double R = c.shell.R;
  const double h = c.shell.h;
  const double E = c.material.E;
  const double mg = c.popper.net_weight;
  const double m = c.popper.moving_mass();
  const auto with = [&](std::string_view key, const char* keys) {
    return merge_sources(a.source(key), fmt::format("; case {}", keys));
  };
  if (R > 0.0 && h > 0.0 && E > 0.0) {
    if (a.r_star) x.put("alpha_r", *a.r_star / theory::r_c(h, R), with("r_star", "h, R"));
    if (a.e_star) x.put("alpha_e", *a.e_star / theory::e_c(h), with("e_star", "h"));
    if (a.F_star) x.put("alpha_F", *a.F_star / theory::F_c(E, h, R), with("F_star", "E, h, R"));
    if (a.F_star_plate) {
      x.put("alpha_F_plate", *a.F_star_plate / theory::F_c(E, h, R),
            with("F_star_plate", "E, h, R"));
    }
    const char* masses = "E, h, R, popper.mass, popper.net_weight";
    if (a.t_star && m > 0.0) {
      x.put("alpha_t", *a.t_star / theory::t_c(m, E, h, R), with("t_star", masses));
    }
    if (a.t_star_rise && m > 0.0) {
      x.put("alpha_t_rise", *a.t_star_rise / theory::t_c(m, E, h, R), with("t_star_rise", masses));
    }
    if (a.t_star && c.popper.mass > 0.0) {
      x.put("alpha_t_own", *a.t_star / theory::t_c(c.popper.mass, E, h, R),
            with("t_star", "E, h, R, popper.mass"));
    }
    if (a.t_star && mg > 0.0) {
      x.put("alpha_t_net", *a.t_star / theory::t_c(mg / config::kStandardGravity, E, h, R),
            with("t_star", "E, h, R, popper.net_weight"));
    }
    if (a.H_s && mg > 0.0) {
      x.put("H_s_scaled", *a.H_s / (E * h * h * h * h / (mg * R)),
            with("H_s", "E, h, R, popper.net_weight"));
    }
  }
  if (a.F_star && mg > 0.0) {
    x.put("F_star_over_mg", *a.F_star / mg, with("F_star", "popper.net_weight"));
    if (a.outcome == theory::Outcome::Jump && *a.F_star < mg) {
      a.warnings.push_back(fmt::format(
          "suspicious Jump: F* = {} N is below the net weight mg = {} N, which the popper "
          "cannot leave the plate with; check the force offset and the threshold",
          *a.F_star, mg));
    }
  }
}

}  // namespace snapjump::measure::stages
