#include "measure/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <vector>

#include "measure/stages.hpp"

namespace snapjump::measure {
namespace {

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
  if (!(o.weight_fraction > 0.0 && o.weight_fraction <= 1.0) || !(o.snap_fraction >= 0.0)) {
    throw SeriesError(fmt::format(
        "analysis options: weight_fraction = {} must be in (0, 1] and snap_fraction = {} not "
        "negative",
        o.weight_fraction, o.snap_fraction));
  }
  if (!(o.noise_window_fraction > 0.0 && o.noise_window_fraction <= 1.0)) {
    throw SeriesError(fmt::format("analysis option noise_window_fraction = {} must be in (0, 1]",
                                  o.noise_window_fraction));
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

std::string_view to_string(Basis b) { return b == Basis::ForceOnly ? "force only" : "transition"; }

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
  stages::Context x(series, options, c, a);
  stages::prepare(x);
  stages::find_onset(x);
  if (x.onset) {
    stages::snap_from_transition(x);
  } else if (!x.can_tell) {
    stages::snap_from_force(x);
  }
  stages::heights(x);
  stages::flight(x);
  stages::settle_no_snap(x);
  stages::onset_in_gaps(x);
  stages::check_tare(x);
  stages::decide(x);
  stages::prefactors(x);
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
      if (a.basis == Basis::Transition && !a.t_onset) return "Snap, but no onset was found";
      if (a.basis == Basis::ForceOnly && !(a.F_star && a.F_rest && *a.F_star > *a.F_rest)) {
        return "Snap, but no force peak above the resting force was found";
      }
      break;
  }
  return "";
}

nlohmann::json to_json(const Analysis& a) {
  using nlohmann::json;
  json quantities = json::object();
  for (const auto& q : quantity_table()) {
    const auto& v = a.*q.field;
    const bool has = v && std::isfinite(*v);
    quantities[std::string(q.key)] = {{"value", has ? json(*v) : json(nullptr)},
                                      {"unit", q.unit},
                                      {"label", q.label},
                                      {"definition", q.definition},
                                      {"source", has ? json(a.source(q.key)) : json(nullptr)}};
  }
  return json{
      {"units", "SI"},
      {"basis", to_string(a.basis)},
      {"outcome", a.outcome ? json(theory::to_string(*a.outcome)) : json(nullptr)},
      {"undetermined", a.undetermined.empty() ? json(nullptr) : json(a.undetermined)},
      {"onset_source",
       a.onset_source == OnsetSource::None ? json(nullptr) : json(to_string(a.onset_source))},
      {"flight_rule", a.flight_rule.empty() ? json(nullptr) : json(a.flight_rule)},
      {"quantities", quantities},
      {"warnings", a.warnings},
  };
}

void write_json(std::ostream& out, const Analysis& a) { out << to_json(a).dump(2) << '\n'; }

}  // namespace snapjump::measure
