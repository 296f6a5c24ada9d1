#include "app/cli.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <new>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "app/case_options.hpp"
#include "app/compare_command.hpp"
#include "app/design_command.hpp"
#include "app/option_values.hpp"
#include "app/plot_command.hpp"
#include "app/run.hpp"
#include "app/sweep_command.hpp"
#include "config/case.hpp"
#include "config/text.hpp"
#include "contact/contact.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/prediction_report.hpp"
#include "measure/analysis.hpp"
#include "measure/time_series.hpp"
#include "mesh/cap_mesher.hpp"
#include "mesh/msh_reader.hpp"
#include "popper/reverse_snap.hpp"
#include "theory/scaling.hpp"

namespace snapjump::app {
namespace {

// The reverse snap from the axisymmetric branch, or why it is not known; never fails predict.
std::optional<popper::ReverseSnap> reverse_snap_of(const config::Case& c, std::string& why) {
  try {
    return popper::reverse_snap(c);
  } catch (const std::exception& e) {
    why = e.what();
    return std::nullopt;
  }
}

void write_reverse_snap(std::ostream& out, const std::optional<popper::ReverseSnap>& r,
                        const std::string& why, double pc, double delta_p_j) {
  if (!r) {
    fmt::print(out, "\nreverse snap: not computed ({})\n", why);
    return;
  }
  fmt::print(out, "\nreverse snap ({}; {:.1f} s)\n", r->model, r->wall_time);
  const auto row = [&](const char* label, double p) {
    if (std::isfinite(p)) {
      fmt::print(out, "  {:<42} {:>11.4g}              kPa  ({:.3f} Zoelly's p_c)\n", label,
                 p / 1e3, p / pc);
    } else {
      fmt::print(out, "  {:<42} {:>11}  not reached\n", label, "-");
    }
  };
  row("p_c    buckling suction (branch maximum)", r->p_c);
  row("p_-    lowest suction of a buckled state", r->p_minus);
  row("p_hold lowest suction holding it inverted", r->p_hold);
  if (!r->note.empty()) fmt::print(out, "  the branch stopped {}\n", r->note);
  if (std::isfinite(r->p_minus)) {
    fmt::print(out, "  {}\n",
               r->p_minus > 0.0
                   ? "monostable: without suction the inverted shell snaps back (p_- > 0)"
                   : "bistable: the inverted shell stays inverted without suction (p_- < 0)");
  }
  if (std::isfinite(r->p_hold)) {
    fmt::print(out, "  delta_p_j = {:.4g} kPa {} the fully inverted shell (p_hold = {:.4g} kPa)\n",
               delta_p_j / 1e3, delta_p_j >= r->p_hold ? "holds" : "does not hold",
               r->p_hold / 1e3);
  }
}

nlohmann::json reverse_snap_json(const std::optional<popper::ReverseSnap>& r,
                                 const std::string& why) {
  using nlohmann::json;
  if (!r) return {{"computed", false}, {"why", why}};
  const auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"computed", true},
          {"model", r->model},
          {"p_c", num(r->p_c)},
          {"p_minus", num(r->p_minus)},
          {"p_hold", num(r->p_hold)},
          {"note", r->note},
          {"monostable", std::isfinite(r->p_minus) ? json(r->p_minus > 0.0) : json(nullptr)}};
}

// A valid case can still lie where the closed forms overflow or vanish (h/R of 1e-309, with
// --allow-implausible): say which quantity, rather than print inf or nan. An end the theory gives
// no value beyond its range (NaN, Prediction::beyond_range) is not such a one.
void check_evaluated(const config::Case& c, const theory::Prediction& p) {
  const auto failed = [&](double v) {
    return std::isinf(v) || (std::isnan(v) && p.beyond_range.empty());
  };
  for (const auto& row : io::prediction_rows(p)) {
    if (failed(row.lo) || failed(row.hi)) {
      throw config::CaseError(fmt::format(
          "the case gives a non-finite {} ({} .. {}): h/R = {:.3g} and E h^2 / mg = {:.3g} lie "
          "outside what the closed forms can evaluate",
          row.key, row.lo, row.hi, c.shell.h / c.shell.R,
          c.material.E * c.shell.h * c.shell.h / c.popper.net_weight));
    }
  }
}

int predict(const CaseOptions& opts, const std::string& format, bool branch, std::ostream& out,
            std::ostream& err) {
  const auto c = opts.load(err);
  const auto p = theory::predict(c, theory::contact_constants());
  check_evaluated(c, p);
  if (!p.beyond_range.empty()) {
    fmt::print(err, "warning: the predicted outcome is unknown: {}\n", p.beyond_range);
  }
  std::string why = "--no-branch";
  const auto r = branch ? reverse_snap_of(c, why) : std::nullopt;
  if (format == "json") {
    auto doc = io::to_json(c, p);
    doc["reverse_snap"] = reverse_snap_json(r, why);
    out << doc.dump(2) << '\n';
  } else if (format == "csv") {
    io::write_csv(out, p);
    if (r) {
      for (const auto& [key, v] : {std::pair{"reverse_p_c", r->p_c},
                                   {"reverse_p_minus", r->p_minus},
                                   {"reverse_p_hold", r->p_hold}}) {
        if (std::isfinite(v)) fmt::print(out, "{},{:.10g},{:.10g},Pa\n", key, v, v);
      }
    }
  } else {
    io::write_table(out, c, p);
    write_reverse_snap(out, r, why,
                       theory::zoelly_pressure(c.material.E, c.shell.h, c.shell.R, c.material.nu),
                       theory::jump_pressure(c));
  }
  return kExitOk;
}

struct ContactOptions {
  double nu = 0.5;
  std::string format = "table";
  std::string curves;
};

int contact_cmd(const ContactOptions& o, std::ostream& out, std::ostream& err) {
  if (!(o.nu > -1.0 && o.nu <= 0.5)) {
    fmt::print(err, "error: --nu {} must lie in (-1, 0.5]\n", o.nu);
    return kExitBadInput;
  }
  const auto c = contact::compute_constants();
  const auto tc = theory::from_solver(c);
  const auto b = theory::prefactor_bounds(tc, o.nu);
  const double kappa = theory::kappa(o.nu);
  if (!o.curves.empty()) {
    std::ofstream csv(o.curves);
    if (!csv) {
      fmt::print(err, "error: --curves: cannot write {}\n", o.curves);
      return kExitFailure;
    }
    contact::write_curves_csv(csv, contact::disk_branch(), contact::ring_branch());
    if (!csv) {
      fmt::print(err, "error: --curves: writing {} failed\n", o.curves);
      return kExitFailure;
    }
  }
  if (o.format == "json") {
    using nlohmann::json;
    const auto range = [](theory::Range r) { return json{{"lower", r.lo}, {"upper", r.hi}}; };
    const json doc = {
        {"units", "rescaled: x = r / l, e_hat = sqrt(kappa) e / h, N = kappa F R / (E h^3)"},
        {"reissner_slope", c.reissner_slope},
        {"N_plus", {{"N", c.N_plus}, {"a", c.a_plus}, {"e_hat", c.e_hat_plus}, {"paper", 76.94}}},
        {"n2", {{"ridge", c.n2}, {"large_rings", c.n2_ring_extrapolated}, {"paper", 20.83}}},
        {"N_minus",
         {{"N", c.N_minus}, {"a", c.a_minus}, {"e_hat", c.e_hat_minus}, {"paper", 46.8}}},
        {"e_hat_ring_law_at_N_plus", c.e_hat_ring_law_at_plus},
        {"mirror_energy_prefactor",
         {{"cap_height", c.mirror_energy_prefactor_cap_height},
          {"apex_displacement", c.mirror_energy_prefactor}}},
        {"ring_branch_min_N", c.ring_N_min},
        {"nu", o.nu},
        {"kappa", kappa},
        {"bounds",
         {{"alpha_r", range(b.alpha_r)},
          {"alpha_e", range(b.alpha_e)},
          {"alpha_F", range(b.alpha_F)},
          {"alpha_t", range(b.alpha_t)}}},
        {"checks",
         {{"max_residual", c.max_residual},
          {"max_offgrid_residual", c.max_offgrid_residual},
          {"min_disk_gap", c.min_disk_gap},
          {"min_ring_gap", c.min_ring_gap}}},
    };
    out << doc.dump(2) << '\n';
    return kExitOk;
  }
  fmt::print(out,
             "snapjump contact: a spherical shell pushed by a rigid plane (axisymmetric "
             "shallow shell)\n");
  fmt::print(out,
             "rescaled units: x = r / l, e_hat = sqrt(kappa) e / h, N = kappa F R / (E h^3), "
             "kappa = 12 (1 - nu^2)\n\n");
  fmt::print(out, "  {:<52} {:>10.5f}   closed form 8 (Reissner)\n",
             "slope dN/de_hat at small load", c.reissner_slope);
  fmt::print(out, "  {:<52} {:>10.4f}   paper 76.94; a = {:.4f}, e_hat = {:.4f}\n",
             "N+  end of the disk branch (contact disk buckles)", c.N_plus, c.a_plus, c.e_hat_plus);
  fmt::print(out, "  {:<52} {:>10.4f}   paper 20.83; large rings give {:.4f}\n",
             "n(2) ridge boundary layer, N_ring = n(2) sqrt(e_hat)", c.n2, c.n2_ring_extrapolated);
  fmt::print(out, "  {:<52} {:>10.4f}   paper 46.8; a = {:.4f}, e_hat = {:.4f}\n",
             "N-  disk branch meets the ring law", c.N_minus, c.a_minus, c.e_hat_minus);
  fmt::print(out, "  {:<52} {:>10.4f}\n", "e_hat on the ring law at N+, (N+ / n(2))^2",
             c.e_hat_ring_law_at_plus);
  fmt::print(out, "  {:<52} {:>10.4f}   ring states need N >= this\n",
             "lowest force on the computed ring branch", c.ring_N_min);
  fmt::print(out, "  {:<52} {:>10.4f}   U = C E h^5/2 H^3/2 / ((1-nu^2)^3/4 R)\n",
             "mirror-buckling energy prefactor C (cap height H)",
             c.mirror_energy_prefactor_cap_height);
  fmt::print(out, "\nprefactor bounds at nu = {} (kappa = {:.4g}):\n", o.nu, kappa);
  fmt::print(out, "  alpha_r  {:.4f} .. {:.4f}   disk contact radius at N- .. at N+\n",
             b.alpha_r.lo, b.alpha_r.hi);
  fmt::print(out, "  alpha_e  {:.4f} .. {:.4f}   e_hat at N- .. ring law at N+\n", b.alpha_e.lo,
             b.alpha_e.hi);
  fmt::print(out, "  alpha_F  {:.4f} .. {:.4f}   N- .. N+\n", b.alpha_F.lo, b.alpha_F.hi);
  fmt::print(out, "  alpha_t  {:.4f} .. {:.4f}   sqrt(3 alpha_e / alpha_F) at the two points\n",
             b.alpha_t.lo, b.alpha_t.hi);
  fmt::print(out,
             "\nchecks: max residual {:.1e}, max residual between nodes {:.1e}, "
             "min gap to the plane {:.1e} (disk) {:.1e} (ring)\n",
             c.max_residual, c.max_offgrid_residual, c.min_disk_gap, c.min_ring_gap);
  if (!o.curves.empty()) fmt::print(out, "branches written to {}\n", o.curves);
  return kExitOk;
}

struct AnalyzeOptions {
  std::vector<std::string> records;
  std::string case_file;
  std::string R;
  std::string force_threshold;
  std::string force_offset;
  std::string settle_time;
  bool complete = false;
  std::vector<std::string> columns;  // NAME=HEADER
  std::vector<std::string> units;    // NAME=UNIT
  std::string format = "table";
};

// One record's analysis, or the error that stopped it.
struct RecordResult {
  std::string file;
  std::optional<measure::Analysis> analysis;
  std::size_t samples = 0;
  std::string error;
};

void print_analysis_table(std::ostream& out, const RecordResult& r, bool with_case) {
  const auto& a = *r.analysis;
  const auto row = [&](const char* label, const std::optional<double>& v, double scale,
                       const char* unit) {
    if (v) {
      fmt::print(out, "  {:<40} {:>12.5g}  {}\n", label, *v / scale, unit);
    } else {
      fmt::print(out, "  {:<40} {:>12}  {}\n", label, "-", unit);
    }
  };
  fmt::print(out, "snapjump analyze: {} ({} samples)\n", r.file, r.samples);
  fmt::print(out, "  {:<40} {:>12}\n", "outcome", measure::outcome_text(a.outcome));
  if (!a.undetermined.empty())
    fmt::print(out, "  {:<40} {}\n", "  why undetermined", a.undetermined);
  row("transition onset t (w/R < 0.03)", a.t_onset, 1e-3, "ms");
  row("r*  contact radius at the onset", a.r_star, 1e-3, "mm");
  row("e*  indentation at the onset", a.e_star, 1e-3, "mm");
  row("    apex displacement at the onset", a.e_apex_star, 1e-3, "mm");
  row("foot of the force's rise to F*", a.t_force_rise, 1e-3, "ms");
  row("F*  peak plate force of the snap", a.F_star, 1.0, "N");
  row("launch t (F back to about 0)", a.t_launch, 1e-3, "ms");
  row("t*  onset to launch", a.t_star, 1e-3, "ms");
  row("    force rise to launch", a.t_star_rise, 1e-3, "ms");
  row("force threshold used for the launch", a.force_threshold, 1.0, "N");
  row("landing t (back on the plate)", a.t_landing, 1e-3, "ms");
  row("H   highest container position", a.H, 1e-3, "mm");
  row("H_l container position at the onset", a.H_l, 1e-3, "mm");
  row("H_s = H - H_l", a.H_s, 1e-3, "mm");
  row("delta_p at the onset", a.delta_p_onset, 1e3, "kPa");
  if (with_case) {
    row("alpha_r = r* / sqrt(h R)", a.alpha_r, 1.0, "");
    row("alpha_e = e* / h", a.alpha_e, 1.0, "");
    row("alpha_F = F* / (E h^3 / R)", a.alpha_F, 1.0, "");
    row("alpha_t = t* / sqrt(m R / (E h^2)), m = popper + counterweight", a.alpha_t, 1.0, "");
    row("  the same with the popper's own mass", a.alpha_t_own, 1.0, "");
    row("  the same with m = mg / g", a.alpha_t_net, 1.0, "");
    row("H_s / (E h^4 / (mg R))", a.H_s_scaled, 1.0, "");
  }
  for (const auto& w : a.warnings) fmt::print(out, "  warning: {}\n", w);
}

// The quantities of the one-row-per-record table, in SI.
struct TableColumn {
  const char* name;
  std::optional<double> measure::Analysis::*field;
};
constexpr std::array kRecordColumns{
    TableColumn{"t_onset", &measure::Analysis::t_onset},
    TableColumn{"r_star", &measure::Analysis::r_star},
    TableColumn{"e_star", &measure::Analysis::e_star},
    TableColumn{"F_star", &measure::Analysis::F_star},
    TableColumn{"t_launch", &measure::Analysis::t_launch},
    TableColumn{"t_star", &measure::Analysis::t_star},
    TableColumn{"H", &measure::Analysis::H},
    TableColumn{"H_l", &measure::Analysis::H_l},
    TableColumn{"H_s", &measure::Analysis::H_s},
    TableColumn{"delta_p_onset", &measure::Analysis::delta_p_onset},
    TableColumn{"alpha_r", &measure::Analysis::alpha_r},
    TableColumn{"alpha_e", &measure::Analysis::alpha_e},
    TableColumn{"alpha_F", &measure::Analysis::alpha_F},
    TableColumn{"alpha_t", &measure::Analysis::alpha_t},
};

int analyze_cmd(const AnalyzeOptions& o, std::ostream& out, std::ostream& err) {
  const units::UnitParser parser;
  std::optional<config::Case> c;
  if (!o.case_file.empty()) c = config::load_case_file(o.case_file, {}, &parser);
  measure::AnalysisOptions opts;
  const auto quantity = [&](const std::string& text, units::Dimension d, const char* flag) {
    return quantity_option(parser, text, d, flag);
  };
  if (!o.R.empty()) opts.R = quantity(o.R, units::Dimension::Length, "--R");
  if (!o.force_threshold.empty()) {
    opts.force_threshold =
        quantity(o.force_threshold, units::Dimension::Force, "--force-threshold");
  }
  if (!o.force_offset.empty()) {
    opts.force_offset = quantity(o.force_offset, units::Dimension::Force, "--force-offset");
  }
  if (!o.settle_time.empty()) {
    opts.settle_time = quantity(o.settle_time, units::Dimension::Time, "--settle-time");
  }
  opts.complete = o.complete;
  measure::ReadOptions read;
  for (const auto& m : o.columns) read.columns.push_back(name_value(m, "--column"));
  for (const auto& u : o.units) read.units.push_back(name_value(u, "--unit"));

  std::vector<RecordResult> results;
  for (const auto& file : o.records) {
    RecordResult r;
    r.file = file;
    try {
      const auto series = measure::TimeSeries::read_csv_file(file, &parser, read);
      r.samples = series.size();
      r.analysis = measure::analyze(series, opts, c ? &*c : nullptr);
    } catch (const measure::SeriesError& e) {
      if (o.records.size() == 1) throw;  // one record: its error is the command's
      r.error = e.what();
      fmt::print(err, "error: {}\n", e.what());
    }
    results.push_back(std::move(r));
  }
  const bool failed = std::any_of(results.begin(), results.end(),
                                  [](const RecordResult& r) { return !r.error.empty(); });

  if (o.format == "json") {
    auto one = [](const RecordResult& r) {
      nlohmann::json j = r.analysis ? measure::to_json(*r.analysis) : nlohmann::json::object();
      j["file"] = r.file;
      if (!r.error.empty()) j["error"] = r.error;
      return j;
    };
    if (results.size() == 1) {
      out << one(results.front()).dump(2) << '\n';
    } else {
      nlohmann::json all = nlohmann::json::array();
      for (const auto& r : results) all.push_back(one(r));
      out << all.dump(2) << '\n';
    }
  } else if (o.format == "csv" || results.size() > 1) {
    // One row per record (SI units); the table format prints it aligned.
    const bool csv = o.format == "csv";
    std::vector<std::string> header{"file", "outcome"};
    for (const auto& col : kRecordColumns) header.emplace_back(col.name);
    header.emplace_back("warnings");
    header.emplace_back("undetermined");
    header.emplace_back("error");
    std::vector<std::vector<std::string>> rows;
    for (const auto& r : results) {
      std::vector<std::string> row{r.file};
      if (r.analysis) {
        const auto& a = *r.analysis;
        row.push_back(measure::outcome_text(a.outcome));
        for (const auto& col : kRecordColumns) {
          const auto& v = a.*col.field;
          if (!v) {
            row.emplace_back();
          } else {
            row.push_back(csv ? fmt::format("{}", *v) : fmt::format("{:.4g}", *v));
          }
        }
        row.push_back(fmt::format("{}", a.warnings.size()));
        row.push_back(a.undetermined);
      } else {
        row.emplace_back();
        for (std::size_t k = 0; k < kRecordColumns.size(); ++k) row.emplace_back();
        row.emplace_back();
        row.emplace_back();
      }
      row.push_back(r.error);
      rows.push_back(std::move(row));
    }
    if (csv) {
      const auto line = [&](const std::vector<std::string>& cells) {
        for (std::size_t k = 0; k < cells.size(); ++k) {
          fmt::print(out, "{}{}", k > 0 ? "," : "", io::csv_field(cells[k]));
        }
        fmt::print(out, "\n");
      };
      line(header);
      for (const auto& row : rows) line(row);
    } else {
      // Aligned: the quantities (SI), the outcome; reasons and errors below the table.
      const std::size_t shown = 2 + kRecordColumns.size() + 1;
      std::vector<std::size_t> width(shown, 0);
      for (std::size_t k = 0; k < shown; ++k) {
        width[k] = header[k].size();
        for (const auto& row : rows) width[k] = std::max(width[k], row[k].size());
      }
      fmt::print(out, "snapjump analyze: {} records (SI units: s, m, N, Pa)\n", rows.size());
      for (std::size_t k = 0; k < shown; ++k) fmt::print(out, "{:<{}}  ", header[k], width[k]);
      fmt::print(out, "\n");
      for (const auto& row : rows) {
        for (std::size_t k = 0; k < shown; ++k) {
          fmt::print(out, "{:<{}}  ", row[k].empty() ? "-" : row[k], width[k]);
        }
        fmt::print(out, "\n");
      }
      for (const auto& r : results) {
        if (!r.error.empty()) fmt::print(out, "  {}: error: {}\n", r.file, r.error);
        if (r.analysis && !r.analysis->undetermined.empty()) {
          fmt::print(out, "  {}: undetermined: {}\n", r.file, r.analysis->undetermined);
        }
      }
    }
  } else {
    print_analysis_table(out, results.front(), c.has_value());
  }
  return failed ? kExitBadInput : kExitOk;
}

// Levenshtein distance, case-insensitive.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// ", did you mean X?" for the nearest of `known` within two edits of `word`, or "".
std::string suggestion(std::string_view word, const std::vector<std::string>& known,
                       std::string_view prefix) {
  std::string best;
  std::size_t best_d = 3;
  for (const auto& k : known) {
    const auto d = edit_distance(word, k);
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best.empty() ? std::string() : fmt::format("; did you mean {}{}?", prefix, best);
}

// An unknown subcommand or --option in the command line, named with a suggestion, before CLI11
// parses it (CLI11 would take `--r 30mm` as a case file "30mm" that does not exist, and
// `snapjump analyse` as no subcommand at all). Nothing when every word is known.
std::optional<std::string> unknown_word(CLI::App& app, int argc, const char* const* argv) {
  std::vector<CLI::App*> chain{&app};
  int k = 1;
  // The subcommands named first (snapjump plot series ...).
  while (k < argc) {
    const std::string_view word = argv[k];
    if (word.starts_with("-")) break;
    CLI::App* next = nullptr;
    std::vector<std::string> names;
    for (auto* sub : chain.back()->get_subcommands({})) {
      names.push_back(sub->get_name());
      if (sub->get_name() == word) next = sub;
    }
    if (next == nullptr) {
      if (names.empty()) break;  // a positional argument of the subcommand
      if (chain.size() == 1) {
        return fmt::format("unknown subcommand '{}' (the subcommands: {}){}", word,
                           fmt::join(names, ", "), suggestion(word, names, ""));
      }
      return fmt::format("unknown subcommand '{}' of '{}' (its subcommands: {}){}", word,
                         chain.back()->get_name(), fmt::join(names, ", "),
                         suggestion(word, names, ""));
    }
    chain.push_back(next);
    ++k;
  }
  std::string path;  // "snapjump plot series" less "snapjump"
  for (std::size_t j = 1; j < chain.size(); ++j) path += " " + chain[j]->get_name();
  std::vector<std::string> known;
  for (auto* level : chain) {
    for (const auto* opt : level->get_options()) {
      for (const auto& name : opt->get_lnames()) known.push_back(name);
    }
  }
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word == "--") break;  // what follows is positional, whatever it looks like
    if (!word.starts_with("--")) continue;
    const auto eq = word.find('=');
    const auto name = word.substr(2, eq == std::string_view::npos ? eq : eq - 2);
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    return fmt::format("unknown option --{} for 'snapjump{}'{}", name, path,
                       suggestion(name, known, "--"));
  }
  return std::nullopt;
}

// The flags besides the case keys' that take a quantity with a unit.
constexpr std::array<std::string_view, 4> kOtherQuantityFlags = {"pause-at", "force-threshold",
                                                                 "force-offset", "settle-time"};

bool takes_quantity(std::string_view flag) {
  for (const auto& k : config::quantity_keys()) {
    if (k.dimension != units::Dimension::Dimensionless && flag == k.flag) return true;
  }
  return std::find(kOtherQuantityFlags.begin(), kOtherQuantityFlags.end(), flag) !=
         kOtherQuantityFlags.end();
}

// The command line with `--R 40 mm` read as `--R "40 mm"`: a bare number after a quantity's flag
// (or in --R=40) and the word after it, when that is a unit the database knows and no file, are
// one value. Otherwise CLI11 would take the unit for the positional argument, the case file.
std::vector<std::string> with_units_joined(int argc, const char* const* argv) {
  std::vector<std::string> args(argv, argv + argc);
  std::optional<units::UnitParser> parser;  // loaded only where a word may be a unit
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string_view word = args[i];
    if (word == "--") break;  // what follows is positional
    if (!word.starts_with("--")) continue;
    const auto eq = word.find('=');
    if (!takes_quantity(word.substr(2, eq == std::string_view::npos ? eq : eq - 2))) continue;
    const std::size_t value = eq == std::string_view::npos ? i + 1 : i;  // the number's word
    if (value + 1 >= args.size()) continue;
    const std::string number = eq == std::string_view::npos ? args[value] : args[i].substr(eq + 1);
    const std::string unit = args[value + 1];
    std::error_code ec;
    if (!units::is_bare_number(number) || unit.starts_with("-") ||
        std::filesystem::exists(unit, ec)) {
      continue;
    }
    if (!parser) parser.emplace();
    if (!parser->is_unit(unit)) continue;
    args[value] += " " + unit;
    args.erase(args.begin() + static_cast<std::ptrdiff_t>(value + 1));
  }
  return args;
}

// --end-time's value given with --resume [s].
double parse_end_time(const std::string& text) {
  const units::UnitParser parser;
  double t = 0.0;
  try {
    t = parser.parse(text, units::Dimension::Time);
  } catch (const units::UnitError& e) {
    throw config::CaseError(fmt::format("--end-time: {}", e.what()));
  }
  if (!(t > 0.0 && std::isfinite(t))) {
    throw config::CaseError(fmt::format("--end-time {}: must be positive", text));
  }
  return t;
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            const CliHooks& hooks) {
  CLI::App app{
      "snapjump: predicts and simulates how elastic shells snap and jump.\n"
      "Start with `snapjump predict` (the theory for the paper's default popper), then "
      "`snapjump run` (its simulated jump, about 2 minutes on two cores)."};
  app.name("snapjump");
  app.require_subcommand(1);
  app.set_version_flag("--version", "snapjump 0.1.0");

  auto* predict_cmd = app.add_subcommand(
      "predict",
      "Closed-form theory for one popper: r*, e*, F*, t*, H_l, H_s, H with their bounds, and "
      "the predicted outcome (Jump / Snap / No snap); then the buckling and reverse-snap "
      "suctions from the axisymmetric model's quasi-static pressure-volume branch (a few "
      "seconds).");
  CaseOptions predict_opts;
  predict_opts.add_to(*predict_cmd);
  std::string format = "table";
  predict_cmd->add_option("--format", format, "output: table (for people), json or csv")
      ->check(CLI::IsMember({"table", "json", "csv"}));
  bool no_branch = false;
  predict_cmd->add_flag("--no-branch", no_branch,
                        "skip the pressure-volume branch (the closed forms only, at once)");
  predict_cmd->footer(
      "Values take units: --R 30mm --h 2mm --E 1.2MPa --net-weight 0.48N --phi 80deg (or\n"
      "--R 30 mm). A bare number is SI (metres, pascals, radians...), with a warning; a value no\n"
      "popper has (R of metres, E of pascals) is refused unless --allow-implausible.");

  auto* contact = app.add_subcommand(
      "contact",
      "Solve the shell-plane contact problem: N+, n(2), N-, the mirror-buckling energy and the "
      "prefactor bounds at a Poisson ratio.");
  ContactOptions contact_opts;
  contact->add_option("--nu", contact_opts.nu, "Poisson's ratio for the bounds (default 0.5)");
  contact->add_option("--format", contact_opts.format, "output: table or json")
      ->check(CLI::IsMember({"table", "json"}));
  contact->add_option("--curves", contact_opts.curves,
                      "write the disk and ring branches N(e_hat) to this CSV file");

  auto* analyze = app.add_subcommand(
      "analyze",
      "Characteristic quantities of a time series, simulated or measured on a force plate: "
      "onset (w/R < 0.03), r*, e*, F*, launch, t*, H, H_l, H_s, the outcome (docs/analysis.md).");
  AnalyzeOptions analyze_opts;
  analyze
      ->add_option("records", analyze_opts.records,
                   "CSV records (one or several) with columns t and F, and any of z, r, w, e, "
                   "delta_p, contact; units in the header, e.g. 't [ms]' or 'Time (s)'")
      ->required()
      ->check(CLI::ExistingFile);
  analyze
      ->add_option("--case", analyze_opts.case_file,
                   "case file of the popper: gives R and the scales for the prefactors")
      ->check(CLI::ExistingFile);
  analyze->add_option("--R", analyze_opts.R,
                      "shell radius for the onset criterion w/R < 0.03, with its unit (30mm)");
  analyze->add_option("--force-threshold", analyze_opts.force_threshold,
                      "plate force below which the popper has left (default: 2% of F* or 4 "
                      "times the noise)");
  analyze->add_option("--force-offset", analyze_opts.force_offset,
                      "added to F before the analysis, e.g. 0.48N for a plate tared with the "
                      "popper on it");
  analyze->add_option("--settle-time", analyze_opts.settle_time,
                      "how long a record must go on after the force peak (or after delta_p "
                      "reached zero) to call it Snap (No snap); default 50ms");
  analyze->add_flag("--complete", analyze_opts.complete,
                    "the records cover the whole experiment: no onset is No snap, no launch Snap");
  analyze->add_option("--column", analyze_opts.columns,
                      "which header names a column, NAME=HEADER, e.g. --column t=\"Time (s)\" "
                      "(repeatable)");
  analyze->add_option("--unit", analyze_opts.units,
                      "unit of a column whose header has none, NAME=UNIT, e.g. --unit F=mN "
                      "(repeatable)");
  analyze
      ->add_option("--format", analyze_opts.format,
                   "output: table, json or csv (one row per record)")
      ->check(CLI::IsMember({"table", "json", "csv"}));

  auto* mesh_cmd = app.add_subcommand(
      "mesh",
      "Write the shell the simulator would use as a gmsh .msh file (quadratic tetrahedra, the "
      "physical groups shell, inner, clamped, outer): a starting point to edit in gmsh and name "
      "in a case as [shell] mesh = \"cap.msh\" (docs/shells.md).");
  CaseOptions mesh_case;
  mesh_case.add_to(*mesh_cmd);
  std::string mesh_resolution, mesh_output;
  mesh_cmd->add_option("--resolution", mesh_resolution, "coarse, default or fine")
      ->check(CLI::IsMember({"coarse", "default", "fine"}));
  mesh_cmd->add_option("--output", mesh_output, "the .msh file to write")->required();

  auto* run_cmd = app.add_subcommand(
      "run",
      "Simulate the popper (3D MPM, or --model axisymmetric): buckle, set delta_p_j, ground, "
      "release; write the time series, a summary and ParaView snapshots into a new folder.");
  CaseOptions run_case;
  run_case.add_to(*run_cmd);
  RunOptions run_opts;
  std::string run_resolution, run_model, run_bulk;
  run_cmd
      ->add_option("--model", run_model,
                   "discretisation of the shell: 3d (the paper's MPM, the default) or "
                   "axisymmetric (finite elements on the meridian section: a reference for the 3D "
                   "model, fast enough for sweeps); overrides numerics.model")
      ->check(CLI::IsMember({"3d", "axisymmetric"}));
  run_cmd
      ->add_option("--bulk-integration", run_bulk,
                   "where the elements integrate the bulk energy: full (with the rest; the 3D "
                   "default, the paper's element) or reduced (3D: at each element's centroid; "
                   "axisymmetric: 2 x 2 points, its default); overrides numerics.bulk_integration")
      ->check(CLI::IsMember({"full", "reduced"}));
  run_cmd->add_option("--output", run_opts.output,
                      "folder for the results (must not exist or be empty; default "
                      "runs/<case>-<date-time>)");
  run_cmd->add_option("--resolution", run_resolution, "coarse, default or fine")
      ->check(CLI::IsMember({"coarse", "default", "fine"}));
  run_cmd->add_flag("--quiet", run_opts.quiet, "no progress lines");
  std::string pause_at;
  run_cmd->add_option("--pause-at", pause_at,
                      "stop at this time after the release (e.g. 0.2s), leaving a checkpoint");
  run_cmd
      ->add_option("--resume", run_opts.resume,
                   "continue a paused, interrupted or killed run in this folder from its last "
                   "checkpoint; with --end-time, a run that went to its cap goes on to the later "
                   "one (or to the apex)")
      ->check(CLI::ExistingDirectory);
  std::string reanalyze;
  run_cmd
      ->add_option("--reanalyze", reanalyze,
                   "analyse the time series of a finished run in this folder again and rewrite "
                   "its summary.json (after an update of the analysis); simulates nothing")
      ->check(CLI::ExistingDirectory);

  SweepCommand sweep_cmd(app);
  PlotCommand plot_cmd(app);
  CompareCommand compare_cmd(app);
  DesignCommand design_cmd(app);

  const auto args = with_units_joined(argc, argv);
  std::vector<const char*> words;
  for (const auto& a : args) words.push_back(a.c_str());
  const int count = static_cast<int>(words.size());
  if (const auto unknown = unknown_word(app, count, words.data())) {
    fmt::print(err, "error: {}\nRun with --help for more information.\n", *unknown);
    return kExitBadInput;
  }
  try {
    app.parse(count, words.data());
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e, out, err);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    if (predict_cmd->parsed()) return predict(predict_opts, format, !no_branch, out, err);
    if (contact->parsed()) return contact_cmd(contact_opts, out, err);
    if (analyze->parsed()) return analyze_cmd(analyze_opts, out, err);
    if (mesh_cmd->parsed()) {
      auto c = mesh_case.load(err);
      if (const auto r = config::parse_resolution(mesh_resolution)) c.numerics.resolution = *r;
      if (!c.shell.mesh.empty()) {
        throw config::CaseError(fmt::format(
            "mesh: the case already names its mesh ({}); `snapjump mesh` writes the spherical "
            "cap of R, h, phi",
            c.shell.mesh));
      }
      if (std::filesystem::path(mesh_output).extension() != ".msh") {
        throw config::CaseError(
            fmt::format("mesh --output {}: name the file .msh (gmsh's format)", mesh_output));
      }
      const auto spec = mesh::cap_spec(c);
      const auto m = mesh::make_cap_mesh(spec);
      mesh::write_msh(m, mesh_output);
      fmt::print(out,
                 "snapjump mesh: {}\n  cap         R = {:.4g} mm, h = {:.4g} mm, phi = {:.4g} deg, "
                 "element size {:.3g} mm, {} layers ({} resolution)\n  mesh        {} ten-node "
                 "tetrahedra, {} nodes; groups shell, inner, clamped, outer\n  written     {}\n",
                 text::printable_line(c.title.empty() ? c.source : c.title), 1e3 * spec.R,
                 1e3 * spec.h, spec.phi * 180.0 / std::numbers::pi, 1e3 * spec.element_size,
                 spec.layers, config::to_string(c.numerics.resolution), m.tets.size(),
                 m.nodes.size(), mesh_output);
      return kExitOk;
    }
    if (sweep_cmd.parsed()) return sweep_cmd.run(out, err);
    if (plot_cmd.parsed()) return plot_cmd.run(out, err);
    if (compare_cmd.parsed()) return compare_cmd.run(out, err);
    if (design_cmd.parsed()) return design_cmd.run(out, err);
    if (run_cmd->parsed()) {
      if (!pause_at.empty()) {
        const units::UnitParser parser;
        try {
          run_opts.pause_at = parser.parse(pause_at, units::Dimension::Time);
        } catch (const units::UnitError& e) {
          throw config::CaseError(fmt::format("--pause-at: {}", e.what()));
        }
      }
      // A new run's set-up, which --resume and --reanalyze take from the run's folder instead.
      const bool sets_up_a_run = !run_case.case_file.empty() || !run_case.values.empty() ||
                                 !run_resolution.empty() || !run_model.empty() ||
                                 !run_bulk.empty() || !run_opts.output.empty();
      if (!reanalyze.empty()) {
        if (sets_up_a_run || !run_opts.resume.empty() || run_opts.pause_at) {
          throw config::CaseError(
              "--reanalyze reads a finished run's folder as it is: give no case file, case "
              "values, --resolution, --model, --bulk-integration, --output, --resume or --pause-at "
              "with it");
        }
        return reanalyze_run(reanalyze, out);
      }
      // Ctrl-C stops the run with a checkpoint, unless the embedding program stops it itself.
      std::optional<SigintStop> sigint;
      if (hooks.stop_requested) {
        run_opts.stop_requested = hooks.stop_requested;
      } else {
        sigint.emplace();
        run_opts.stop_requested = [&sigint] { return sigint->requested(); };
      }
      if (!run_opts.resume.empty()) {
        // A new cap is the one case value a resume takes.
        auto values = run_case.values;
        const auto end = values.find("numerics.end_time");
        if (end != values.end()) {
          run_opts.end_time = parse_end_time(end->second);
          values.erase(end);
        }
        if (!run_case.case_file.empty() || !values.empty() || !run_resolution.empty() ||
            !run_model.empty() || !run_bulk.empty() || !run_opts.output.empty()) {
          throw config::CaseError(
              "--resume continues a run as it was set up (its case.toml, its folder): give no "
              "case file, case values (but --end-time, a later cap), --resolution, --model, "
              "--bulk-integration or --output with it");
        }
        return run_simulation(config::Case{}, run_opts, out, err);
      }
      auto c = run_case.load(err);
      if (const auto r = config::parse_resolution(run_resolution)) c.numerics.resolution = *r;
      if (const auto m = config::parse_model(run_model)) c.numerics.model = *m;
      if (const auto b = config::parse_bulk_integration(run_bulk)) {
        c.numerics.bulk_integration = *b;
      }
      return run_simulation(c, run_opts, out, err);
    }
  } catch (const io::WriteFailed& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitWriteFailed;
  } catch (const InputError& e) {  // a case, a unit, a series, a mesh, a sweep file, a figure
    fmt::print(err, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    const auto subcommands = app.get_subcommands();
    const auto doing =
        fmt::format("running snapjump {}",
                    subcommands.empty() ? std::string() : subcommands.front()->get_name());
    fmt::print(err, "error: {}\n", error_text(e, doing));
    return kExitFailure;
  }
  return kExitOk;
}

std::string error_text(const std::exception& e, std::string_view doing) {
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr) {
    return fmt::format(
        "out of memory while {} (an input asks for more memory than the machine has left)", doing);
  }
  return e.what();
}

}  // namespace snapjump::app
