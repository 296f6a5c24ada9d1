#include "app/compare_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <filesystem>

#include "app/cli.hpp"
#include "app/option_values.hpp"
#include "config/case.hpp"
#include "measure/analysis.hpp"
#include "measure/comparison.hpp"
#include "measure/time_series.hpp"
#include "plot/figures.hpp"
#include "theory/scaling.hpp"

namespace snapjump::app {
namespace {

namespace fs = std::filesystem;

// The run's folder: its series and its case.
void require_run(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw config::CaseError(fmt::format(
        "compare: the last argument, {}, is not a folder: give the records, then the run's folder "
        "(snapjump compare RECORD... RUN_DIR)",
        dir.string()));
  }
  for (const char* name : {"series.csv", "case.toml"}) {
    if (!fs::is_regular_file(dir / name, ec)) {
      throw config::CaseError(
          fmt::format("compare: {} is not a snapjump run folder (no {})", dir.string(), name));
    }
  }
}

}  // namespace

CompareCommand::CompareCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "compare",
      "Measured records beside a simulated run and the theory: one table of every quantity "
      "measured in the records, simulated in the run and bounded by the theory, with the "
      "differences and whether each lies within the record's stated uncertainty; several records "
      "give their mean and spread. The overlay figure (record solid, run dashed) is drawn beside "
      "it (docs/analysis.md, \"A record beside a run\").");
  cmd_->add_option("inputs", inputs_,
                   "the records (CSV, as analyze reads them), then the run's folder (written by "
                   "snapjump run: series.csv, case.toml)")
      ->required()
      ->expected(2, -1);
  cmd_->add_option("--column", columns_, "which header names a record's column, NAME=HEADER");
  cmd_->add_option("--unit", units_, "unit of a record's column whose header has none, NAME=UNIT");
  cmd_->add_option("--force-offset", force_offset_,
                   "added to the records' F, e.g. 0.48N for a plate tared with the popper on it");
  cmd_->add_option("--settle-time", settle_time_,
                   "how long a record must go on after its force peak to call it Snap (50ms)");
  cmd_->add_flag("--complete", complete_, "the records cover the whole experiment");
  cmd_->add_option("--force-resolution", force_resolution_,
                   "the plate's resolution, the records' uncertainty of F (default 12 mN, the "
                   "paper's plate)");
  cmd_->add_option("--ring-width", ring_width_,
                   "the width of the contact ring the camera sees, the uncertainty of r* (none "
                   "by default: r* is then not judged)");
  cmd_->add_option("--length-resolution", length_resolution_,
                   "the lasers' resolution, the uncertainty of z, w and e (none by default)");
  cmd_->add_option("--format", format_, "table, csv or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  cmd_->add_option("--figure", figure_,
                   "the overlay figure (.png or .svg; default RUN_DIR/figures/compare.png)");
  cmd_->add_flag("--no-figure", no_figure_, "draw no figure");
}

bool CompareCommand::parsed() const { return cmd_->parsed(); }

int CompareCommand::run(std::ostream& out, std::ostream& err) const {
  const fs::path run_dir = inputs_.back();
  require_run(run_dir);
  const units::UnitParser parser;
  const auto c = config::load_case_file(run_dir / "case.toml", {}, &parser);
  measure::AnalysisOptions opts;
  if (!force_offset_.empty()) {
    opts.force_offset =
        quantity_option(parser, force_offset_, units::Dimension::Force, "--force-offset");
  }
  if (!settle_time_.empty()) {
    opts.settle_time =
        positive_option(parser, settle_time_, units::Dimension::Time, "--settle-time");
  }
  opts.complete = complete_;
  measure::RecordUncertainty u;
  u.force_resolution =
      positive_option(parser, force_resolution_, units::Dimension::Force, "--force-resolution");
  if (!ring_width_.empty()) {
    u.ring_width = positive_option(parser, ring_width_, units::Dimension::Length, "--ring-width");
  }
  if (!length_resolution_.empty()) {
    u.length_resolution = positive_option(parser, length_resolution_, units::Dimension::Length,
                                          "--length-resolution");
  }
  measure::ReadOptions read;
  for (const auto& m : columns_) read.columns.push_back(name_value(m, "--column"));
  for (const auto& m : units_) read.units.push_back(name_value(m, "--unit"));

  std::vector<measure::RecordResult> records;
  for (std::size_t i = 0; i + 1 < inputs_.size(); ++i) {
    std::error_code ec;
    if (!fs::is_regular_file(inputs_[i], ec)) {
      throw config::CaseError(fmt::format("compare: no record file {}", inputs_[i]));
    }
    const auto s = measure::TimeSeries::read_csv_file(inputs_[i], &parser, read);
    measure::RecordResult r;
    r.name = inputs_[i];
    r.analysis = measure::analyze(s, opts, &c);
    r.dt_force = s.sample_interval(measure::kForce);
    if (r.analysis.onset_source == measure::OnsetSource::ApexGap) {
      r.dt_onset = s.sample_interval(measure::kApexGap);
    } else if (r.analysis.onset_source == measure::OnsetSource::ContactDisk) {
      r.dt_onset = s.sample_interval(measure::kContact);
    }
    records.push_back(std::move(r));
  }
  // The run as snapjump run analyses it: its F also through the paper's plate.
  const auto run_series = measure::TimeSeries::read_csv_file(run_dir / "series.csv", &parser);
  measure::AnalysisOptions run_opts;
  run_opts.plate_frequency = measure::kPaperPlateFrequency;
  const auto run = measure::analyze(run_series, run_opts, &c);
  const auto prediction = theory::predict(c, theory::contact_constants());
  auto comparison = measure::compare(records, run, prediction, u);

  if (!no_figure_) {
    try {
      const auto fo = plot::options_for_image(
          figure_.empty() ? run_dir / "figures" / "compare.png" : fs::path(figure_), "--figure");
      plot::SeriesFigureOptions so;
      so.experiment = inputs_.front();
      so.read = read;
      const auto fig = plot::plot_series(run_dir, fo, so);
      comparison.notes.push_back(fmt::format(
          "figure {} (the record{} solid, the run dashed; script {})", fig.figure.string(),
          records.size() > 1 ? fmt::format(" {}", inputs_.front()) : "", fig.script.string()));
    } catch (const plot::PlotInputError&) {
      throw;
    } catch (const plot::PlotError& e) {
      fmt::print(err, "warning: the figure could not be drawn: {}\n", e.what());
      comparison.notes.push_back(fmt::format("no figure: {}", e.what()));
    }
  }
  if (format_ == "json") {
    out << measure::to_json(comparison).dump(2) << '\n';
  } else if (format_ == "csv") {
    measure::write_csv(out, comparison);
  } else {
    fmt::print(out, "  run         {}\n", run_dir.string());
    measure::write_table(out, comparison);
  }
  return kExitOk;
}

}  // namespace snapjump::app
