#include "measure/comparison.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace snapjump::measure {
namespace {

using theory::Prediction;
using theory::Range;

// How a quantity's stated uncertainty follows from the record's instruments.
enum class Rule {
  None,           // nothing stated for it
  Force,          // F's resolution
  Ring,           // the ring's width
  Length,         // one laser reading
  TwoLengths,     // a difference of two laser readings
  TwoForceTimes,  // two events on the force's clock (the launch, the foot, the landing)
  OnsetToLaunch,  // one event on the onset column's clock, one on the force's
  Flight,         // from z: two laser readings; from T: 2 (2 dt_F) / T of it
  Scaled,         // a prefactor: its quantity's, relative
};

struct RowDef {
  const char* key;
  const char* run_key;  // the run's quantity to compare with; nullptr: the same key
  Rule rule;
  const char* base;  // Rule::Scaled: the quantity it scales
  const char* bounds_of;
  std::function<std::optional<Range>(const Prediction&)> bounds;
};

std::optional<Range> none(const Prediction&) { return std::nullopt; }

const std::vector<RowDef>& row_defs() {
  static const std::vector<RowDef> defs = {
      {"F_star", "F_star_plate", Rule::Force, nullptr, "F_star",
       [](const Prediction& p) { return std::optional(p.F_star); }},
      {"F_rest", nullptr, Rule::Force, nullptr, "", none},
      {"r_star", nullptr, Rule::Ring, nullptr, "r_star",
       [](const Prediction& p) { return std::optional(p.r_star); }},
      {"e_star", nullptr, Rule::Length, nullptr, "e_star",
       [](const Prediction& p) { return std::optional(p.e_star); }},
      {"t_star", nullptr, Rule::OnsetToLaunch, nullptr, "t_star",
       [](const Prediction& p) { return std::optional(p.t_star); }},
      {"t_star_rise", nullptr, Rule::TwoForceTimes, nullptr, "t_star",
       [](const Prediction& p) { return std::optional(p.t_star); }},
      {"flight_time", nullptr, Rule::TwoForceTimes, nullptr, "", none},
      {"H_flight", nullptr, Rule::Flight, nullptr, "H_s",
       [](const Prediction& p) { return std::optional(p.H_s); }},
      {"H", nullptr, Rule::Length, nullptr, "H",
       [](const Prediction& p) { return std::optional(p.H); }},
      {"H_l", nullptr, Rule::Length, nullptr, "H_l",
       [](const Prediction& p) { return std::optional(p.H_l); }},
      {"H_s", nullptr, Rule::TwoLengths, nullptr, "H_s",
       [](const Prediction& p) { return std::optional(p.H_s); }},
      {"delta_p_onset", nullptr, Rule::None, nullptr, "", none},
      {"alpha_r", nullptr, Rule::Scaled, "r_star", "alpha_r",
       [](const Prediction& p) { return std::optional(p.alpha.alpha_r); }},
      {"alpha_e", nullptr, Rule::Scaled, "e_star", "alpha_e",
       [](const Prediction& p) { return std::optional(p.alpha.alpha_e); }},
      {"alpha_F", "alpha_F_plate", Rule::Scaled, "F_star", "alpha_F",
       [](const Prediction& p) { return std::optional(p.alpha.alpha_F); }},
      {"alpha_t", nullptr, Rule::Scaled, "t_star", "alpha_t",
       [](const Prediction& p) { return std::optional(p.alpha.alpha_t); }},
      {"alpha_t_rise", nullptr, Rule::Scaled, "t_star_rise", "alpha_t",
       [](const Prediction& p) { return std::optional(p.alpha.alpha_t); }},
      {"F_star_over_mg", nullptr, Rule::Scaled, "F_star", "jump_margin",
       [](const Prediction& p) { return std::optional(p.jump_margin); }},
  };
  return defs;
}

std::optional<double> value(const Analysis& a, std::string_view key) {
  const auto* q = find_quantity(key);
  if (q == nullptr) return std::nullopt;
  const auto& v = a.*(q->field);
  return v && std::isfinite(*v) ? v : std::nullopt;
}

struct Stated {
  std::optional<double> value;
  std::string from;
};

std::string ms(double dt) { return fmt::format("{:.3g} ms", 1e3 * dt); }

// The record's stated uncertainty of one quantity.
Stated stated(const RowDef& d, const RecordResult& r, const RecordUncertainty& u) {
  const auto& a = r.analysis;
  switch (d.rule) {
    case Rule::None:
      return {std::nullopt, "not stated"};
    case Rule::Force:
      return {u.force_resolution,
              fmt::format("F's resolution {:.3g} mN", 1e3 * u.force_resolution)};
    case Rule::Ring:
      if (!u.ring_width) return {std::nullopt, "the ring's width not stated"};
      return {*u.ring_width, fmt::format("the ring's width {:.3g} mm", 1e3 * *u.ring_width)};
    case Rule::Length:
      if (!u.length_resolution) return {std::nullopt, "the lasers' resolution not stated"};
      return {*u.length_resolution,
              fmt::format("the lasers' resolution {:.3g} mm", 1e3 * *u.length_resolution)};
    case Rule::TwoLengths:
      if (!u.length_resolution) return {std::nullopt, "the lasers' resolution not stated"};
      return {2.0 * *u.length_resolution,
              fmt::format("two laser readings, {:.3g} mm each", 1e3 * *u.length_resolution)};
    case Rule::TwoForceTimes:
      return {2.0 * r.dt_force, fmt::format("two samples of F, {} each", ms(r.dt_force))};
    case Rule::OnsetToLaunch:
      return {r.dt_onset + r.dt_force,
              fmt::format("a sample of the onset's column ({}) and one of F ({})", ms(r.dt_onset),
                          ms(r.dt_force))};
    case Rule::Flight: {
      if (a.source("H_flight").find('z') != std::string::npos) {
        if (!u.length_resolution) return {std::nullopt, "the lasers' resolution not stated"};
        return {2.0 * *u.length_resolution,
                fmt::format("two laser readings, {:.3g} mm each", 1e3 * *u.length_resolution)};
      }
      if (!a.H_flight || !a.flight_time || !(*a.flight_time > 0.0)) return {std::nullopt, ""};
      return {*a.H_flight * 2.0 * (2.0 * r.dt_force) / *a.flight_time,
              fmt::format("T to two samples of F ({} each): 2 dT / T of it", ms(r.dt_force))};
    }
    case Rule::Scaled: {
      const auto base = std::find_if(row_defs().begin(), row_defs().end(), [&](const RowDef& b) {
        return d.base == std::string_view(b.key);
      });
      const auto b = stated(*base, r, u);
      const auto bv = value(a, d.base);
      const auto v = value(a, d.key);
      if (!b.value || !bv || !v || *bv == 0.0) return {std::nullopt, b.from};
      return {std::abs(*v * *b.value / *bv), fmt::format("{}'s: {}", d.base, b.from)};
    }
  }
  return {};
}

ComparisonRow make_row(const RowDef& d, std::span<const RecordResult> records, const Analysis& run,
                       const Prediction& p, const RecordUncertainty& u) {
  const auto* q = find_quantity(d.key);
  ComparisonRow row;
  row.key = d.key;
  row.unit = std::string(q->unit);
  row.label = std::string(q->label);
  for (const auto& r : records) {
    const auto v = value(r.analysis, d.key);
    if (!v) continue;
    row.values.push_back(*v);
    if (row.source.empty()) row.source = r.analysis.source(d.key);
    const auto s = stated(d, r, u);
    if (row.uncertainty_from.empty() ||
        (s.value && (!row.uncertainty || *s.value > *row.uncertainty))) {
      row.uncertainty_from = s.from;
    }
    if (s.value) row.uncertainty = std::max(row.uncertainty.value_or(0.0), *s.value);
  }
  if (!row.values.empty()) {
    double sum = 0.0;
    for (const double v : row.values) sum += v;
    const double mean = sum / static_cast<double>(row.values.size());
    row.record = mean;
    if (row.values.size() >= 2) {
      double ss = 0.0;
      for (const double v : row.values) ss += (v - mean) * (v - mean);
      row.spread = std::sqrt(ss / static_cast<double>(row.values.size() - 1));
    }
  }
  row.run_key = d.key;
  if (d.run_key != nullptr && value(run, d.run_key)) row.run_key = d.run_key;
  row.run = value(run, row.run_key);
  if (row.record && row.run) {
    row.difference = *row.record - *row.run;
    if (row.uncertainty || row.spread) {
      const double tol = std::max(row.uncertainty.value_or(0.0), row.spread.value_or(0.0));
      row.within = std::abs(*row.difference) <= tol;
    }
  }
  if (const auto b = d.bounds(p); b && std::isfinite(b->lo) && std::isfinite(b->hi)) {
    row.lower = std::min(b->lo, b->hi);
    row.upper = std::max(b->lo, b->hi);
    row.bounds_of = d.bounds_of;
    if (row.record) {
      const double w = row.uncertainty.value_or(0.0);
      row.in_bounds = *row.record >= *row.lower - w && *row.record <= *row.upper + w;
    }
  }
  return row;
}

std::string cell(const std::optional<double>& v) { return v ? fmt::format("{}", *v) : ""; }
std::string cell(const std::optional<bool>& v) { return v ? (*v ? "yes" : "no") : ""; }

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

}  // namespace

Comparison compare(std::span<const RecordResult> records, const Analysis& run,
                   const theory::Prediction& p, const RecordUncertainty& u) {
  Comparison c;
  for (const auto& r : records) {
    c.records.push_back(r.name);
    c.record_outcomes.push_back(outcome_text(r.analysis.outcome));
  }
  c.run_outcome = outcome_text(run.outcome);
  c.predicted_outcome = p.outcome_text();
  for (const auto& d : row_defs()) {
    auto row = make_row(d, records, run, p, u);
    if (row.record || row.run) c.rows.push_back(std::move(row));
  }
  if (!value(run, "t_landing")) {
    c.notes.emplace_back(
        "the run ends at the apex of its flight: it has no landing, so no flight_time; its "
        "H_flight is the rise z shows");
  }
  if (value(run, "F_star_plate")) {
    c.notes.emplace_back(
        "F* and alpha_F of the run are taken through the paper's 170 Hz plate (F_star_plate), as a "
        "measured record has been through its plate");
  }
  for (const auto& r : records) {
    if (r.analysis.basis == Basis::ForceOnly) {
      c.notes.push_back(fmt::format(
          "{}: read from the force alone: t*_rise (the force's rise to the launch) stands for t*, "
          "H_flight for the rise after the launch (the theory's H_s bounds it)",
          r.name));
    }
    if (!r.analysis.undetermined.empty()) {
      c.notes.push_back(
          fmt::format("{}: outcome undetermined: {}", r.name, r.analysis.undetermined));
    }
  }
  return c;
}

nlohmann::json to_json(const Comparison& c) {
  using nlohmann::json;
  const auto num = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  const auto flag = [](const std::optional<bool>& v) { return v ? json(*v) : json(nullptr); };
  json q = json::object();
  for (const auto& r : c.rows) {
    q[r.key] = {{"unit", r.unit},
                {"label", r.label},
                {"record", num(r.record)},
                {"values", r.values},
                {"n", r.values.size()},
                {"spread", num(r.spread)},
                {"uncertainty", num(r.uncertainty)},
                {"uncertainty_from", r.uncertainty_from},
                {"run", num(r.run)},
                {"run_key", r.run_key},
                {"difference", num(r.difference)},
                {"within", flag(r.within)},
                {"lower", num(r.lower)},
                {"upper", num(r.upper)},
                {"bounds_of", r.bounds_of.empty() ? json(nullptr) : json(r.bounds_of)},
                {"in_bounds", flag(r.in_bounds)},
                {"source", r.source}};
  }
  return {
      {"units", "SI"},
      {"records", c.records},
      {"outcomes",
       {{"records", c.record_outcomes}, {"run", c.run_outcome}, {"theory", c.predicted_outcome}}},
      {"quantities", q},
      {"notes", c.notes}};
}

void write_csv(std::ostream& out, const Comparison& c) {
  fmt::print(out,
             "quantity,unit,record,spread,n,uncertainty,run,run_key,difference,within,lower,upper,"
             "in_bounds,source\n");
  for (const auto& r : c.rows) {
    fmt::print(out, "{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.key, r.unit, cell(r.record),
               cell(r.spread), r.values.size(), cell(r.uncertainty), cell(r.run), r.run_key,
               cell(r.difference), cell(r.within), cell(r.lower), cell(r.upper), cell(r.in_bounds),
               csv_text(r.source));
  }
  const bool same = std::all_of(c.record_outcomes.begin(), c.record_outcomes.end(),
                                [&](const std::string& o) { return o == c.run_outcome; });
  fmt::print(out, "outcome,,{},,{},,{},,,{},,,,{}\n",
             csv_text(fmt::format("{}", fmt::join(c.record_outcomes, " / "))),
             c.record_outcomes.size(), csv_text(c.run_outcome), same ? "yes" : "no",
             csv_text("theory: " + c.predicted_outcome));
}

void write_table(std::ostream& out, const Comparison& c) {
  const auto show = [](const std::optional<double>& v, double scale) {
    return v ? fmt::format("{:.4g}", *v / scale) : std::string("-");
  };
  fmt::print(out, "snapjump compare: {} record{} against the run\n", c.records.size(),
             c.records.size() == 1 ? "" : "s");
  fmt::print(out, "  outcome     record {}; run {}; theory {}\n",
             fmt::join(c.record_outcomes, ", "), c.run_outcome, c.predicted_outcome);
  fmt::print(out, "  {:<16} {:>6} {:>10} {:>9} {:>10} {:>10} {:>7}  {:<19} {}\n", "quantity",
             "unit", c.records.size() > 1 ? "mean" : "record", c.records.size() > 1 ? "spread" : "",
             "+- stated", "run", "within", "theory", "record's source");
  for (const auto& r : c.rows) {
    const auto* q = find_quantity(r.key);
    const double s = q->display_scale;
    fmt::print(out, "  {:<16} {:>6} {:>10} {:>9} {:>10} {:>10} {:>7}  {:<19} {}\n", r.key,
               q->display_unit, show(r.record, s), r.spread ? show(r.spread, s) : "",
               show(r.uncertainty, s), show(r.run, s), r.within ? (*r.within ? "yes" : "no") : "-",
               r.lower ? fmt::format("{:.4g} .. {:.4g}{}", *r.lower / s, *r.upper / s,
                                     r.in_bounds ? (*r.in_bounds ? "" : " out") : "")
                       : std::string("-"),
               r.source);
  }
  fmt::print(out,
             "  within: |record - run| <= the record's stated uncertainty (or the records' spread, "
             "if larger); out: the record outside the theory's bounds\n");
  for (const auto& r : c.rows) {
    if (r.uncertainty) continue;
    if (!r.uncertainty_from.empty() && r.record) {
      fmt::print(out, "  {}: {}\n", r.key, r.uncertainty_from);
    }
  }
  for (const auto& n : c.notes) fmt::print(out, "  note: {}\n", n);
}

}  // namespace snapjump::measure
