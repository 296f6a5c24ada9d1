#include "app/analyze_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/option_values.hpp"
#include "config/case.hpp"
#include "config/units.hpp"
#include "io/csv.hpp"
#include "measure/analysis.hpp"
#include "measure/time_series.hpp"

namespace snapjump::app {
namespace {

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

using Cells = std::vector<std::string>;

// The analysis options from the command line's quantities (each with its unit).
measure::AnalysisOptions analysis_options(const units::UnitParser& parser, const std::string& R,
                                          const std::string& force_threshold,
                                          const std::string& force_offset,
                                          const std::string& settle_time, bool complete) {
  measure::AnalysisOptions opts;
  const auto quantity = [&](const std::string& text, units::Dimension d, const char* flag) {
    return quantity_option(parser, text, d, flag);
  };
  if (!R.empty()) opts.R = quantity(R, units::Dimension::Length, "--R");
  if (!force_threshold.empty()) {
    opts.force_threshold = quantity(force_threshold, units::Dimension::Force, "--force-threshold");
  }
  if (!force_offset.empty()) {
    opts.force_offset = quantity(force_offset, units::Dimension::Force, "--force-offset");
  }
  if (!settle_time.empty()) {
    opts.settle_time = quantity(settle_time, units::Dimension::Time, "--settle-time");
  }
  opts.complete = complete;
  return opts;
}

// Each record read and analysed; with several, a record that cannot be read gets its error (said
// on err) and the others go on; a single record's error is the command's.
std::vector<RecordResult> analyze_records(const std::vector<std::string>& records,
                                          const units::UnitParser& parser,
                                          const measure::ReadOptions& read,
                                          const measure::AnalysisOptions& opts,
                                          const config::Case* c, std::ostream& err) {
  std::vector<RecordResult> results;
  for (const auto& file : records) {
    RecordResult r;
    r.file = file;
    try {
      const auto series = measure::TimeSeries::read_csv_file(file, &parser, read);
      r.samples = series.size();
      r.analysis = measure::analyze(series, opts, c);
    } catch (const measure::SeriesError& e) {
      if (records.size() == 1) throw;  // one record: its error is the command's
      r.error = e.what();
      fmt::print(err, "error: {}\n", e.what());
    }
    results.push_back(std::move(r));
  }
  return results;
}

void write_json(std::ostream& out, const std::vector<RecordResult>& results) {
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
}

// The header of the one-row-per-record table.
Cells record_header() {
  Cells header{"file", "outcome"};
  for (const auto& col : kRecordColumns) header.emplace_back(col.name);
  header.emplace_back("warnings");
  header.emplace_back("undetermined");
  header.emplace_back("error");
  return header;
}

// A record's row (SI units): full precision for CSV, four digits for the aligned table.
Cells record_row(const RecordResult& r, bool csv) {
  Cells row{r.file};
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
  return row;
}

void write_csv(std::ostream& out, const Cells& header, const std::vector<Cells>& rows) {
  const auto line = [&](const Cells& cells) {
    for (std::size_t k = 0; k < cells.size(); ++k) {
      fmt::print(out, "{}{}", k > 0 ? "," : "", io::csv_field(cells[k]));
    }
    fmt::print(out, "\n");
  };
  line(header);
  for (const auto& row : rows) line(row);
}

// Aligned: the quantities (SI), the outcome; reasons and errors below the table.
void write_aligned(std::ostream& out, const Cells& header, const std::vector<Cells>& rows,
                   const std::vector<RecordResult>& results) {
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

}  // namespace

AnalyzeCommand::AnalyzeCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "analyze",
      "Characteristic quantities of a time series, simulated or measured on a force plate: "
      "onset (w/R < 0.03), r*, e*, F*, launch, t*, H, H_l, H_s, the outcome (docs/analysis.md).");
  cmd_->add_option("records", records_,
                   "CSV records (one or several) with columns t and F, and any of z, r, w, e, "
                   "delta_p, contact; units in the header, e.g. 't [ms]' or 'Time (s)'")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_->add_option("--case", case_file_,
                   "case file of the popper: gives R and the scales for the prefactors")
      ->check(CLI::ExistingFile);
  cmd_->add_option("--R", R_,
                   "shell radius for the onset criterion w/R < 0.03, with its unit (30mm)");
  cmd_->add_option("--force-threshold", force_threshold_,
                   "plate force below which the popper has left (default: 2% of F* or 4 "
                   "times the noise)");
  cmd_->add_option("--force-offset", force_offset_,
                   "added to F before the analysis, e.g. 0.48N for a plate tared with the "
                   "popper on it");
  cmd_->add_option("--settle-time", settle_time_,
                   "how long a record must go on after the force peak (or after delta_p "
                   "reached zero) to call it Snap (No snap); default 50ms");
  cmd_->add_flag("--complete", complete_,
                 "the records cover the whole experiment: no onset is No snap, no launch Snap");
  cmd_->add_option("--column", columns_,
                   "which header names a column, NAME=HEADER, e.g. --column t=\"Time (s)\" "
                   "(repeatable)");
  cmd_->add_option("--unit", units_,
                   "unit of a column whose header has none, NAME=UNIT, e.g. --unit F=mN "
                   "(repeatable)");
  cmd_->add_option("--format", format_, "output: table, json or csv (one row per record)")
      ->check(CLI::IsMember({"table", "json", "csv"}));
}

bool AnalyzeCommand::parsed() const { return cmd_->parsed(); }

int AnalyzeCommand::run(std::ostream& out, std::ostream& err) const {
  const units::UnitParser parser;
  std::optional<config::Case> c;
  if (!case_file_.empty()) c = config::load_case_file(case_file_, {}, &parser);
  const auto opts =
      analysis_options(parser, R_, force_threshold_, force_offset_, settle_time_, complete_);
  measure::ReadOptions read;
  for (const auto& m : columns_) read.columns.push_back(name_value(m, "--column"));
  for (const auto& u : units_) read.units.push_back(name_value(u, "--unit"));
  const auto results = analyze_records(records_, parser, read, opts, c ? &*c : nullptr, err);
  const bool failed = std::any_of(results.begin(), results.end(),
                                  [](const RecordResult& r) { return !r.error.empty(); });
  if (format_ == "json") {
    write_json(out, results);
  } else if (format_ == "csv" || results.size() > 1) {
    // One row per record (SI units); the table format prints it aligned.
    const bool csv = format_ == "csv";
    std::vector<Cells> rows;
    for (const auto& r : results) rows.push_back(record_row(r, csv));
    if (csv) {
      write_csv(out, record_header(), rows);
    } else {
      write_aligned(out, record_header(), rows, results);
    }
  } else {
    print_analysis_table(out, results.front(), c.has_value());
  }
  return failed ? kExitBadInput : kExitOk;
}

}  // namespace snapjump::app
