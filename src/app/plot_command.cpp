#include "app/plot_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "app/cli.hpp"
#include "config/units.hpp"
#include "plot/figures.hpp"

namespace snapjump::app {
namespace {

namespace fs = std::filesystem;

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return std::string(s.substr(first, last - first + 1));
}

// "0,0.2,450ms" -> seconds; a bare number is in seconds.
std::vector<double> parse_times(const std::string& text) {
  const units::UnitParser parser;
  std::vector<double> times;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto comma = text.find(',', start);
    const auto item = trim(std::string_view(text).substr(
        start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty()) {
      throw plot::PlotInputError(
          fmt::format("--times '{}': an empty item; write times such as 0,0.2,450ms", text));
    }
    try {
      times.push_back(parser.parse(item, units::Dimension::Time));
    } catch (const units::UnitError& e) {
      throw plot::PlotInputError(fmt::format("--times: '{}': {}", item, e.what()));
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return times;
}

// "450ms:560ms" -> seconds; bare numbers are seconds.
std::pair<double, double> parse_window(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) {
    throw plot::PlotInputError(
        fmt::format("--window '{}': write START:END, e.g. 450ms:560ms", text));
  }
  const units::UnitParser parser;
  const auto one = [&](std::string_view item) {
    try {
      return parser.parse(trim(item), units::Dimension::Time);
    } catch (const units::UnitError& e) {
      throw plot::PlotInputError(fmt::format("--window: '{}': {}", trim(item), e.what()));
    }
  };
  const double a = one(std::string_view(text).substr(0, colon));
  const double b = one(std::string_view(text).substr(colon + 1));
  if (!(b > a)) {
    throw plot::PlotInputError(
        fmt::format("--window '{}': the end must come after the start", text));
  }
  return {a, b};
}

plot::FigureOptions figure_options(const std::string& format, const std::string& output) {
  plot::FigureOptions o;
  o.output = output;
  std::optional<plot::Format> from_extension;
  if (!output.empty()) {
    auto ext = fs::path(output).extension().string();
    if (!ext.empty()) from_extension = plot::parse_format(ext.substr(1));
    if (!from_extension) {
      throw plot::PlotInputError(fmt::format(
          "--output {}: snapjump draws png or svg; name the file .png or .svg", output));
    }
  }
  if (!format.empty()) {
    const auto f = plot::parse_format(format);
    if (!f) throw plot::PlotInputError(fmt::format("--format {}: use png or svg", format));
    if (from_extension && *from_extension != *f) {
      throw plot::PlotInputError(fmt::format("--output {} does not end in .{} as --format {} asks",
                                             output, plot::extension(*f), format));
    }
    o.format = *f;
  } else if (from_extension) {
    o.format = *from_extension;
  }
  if (const char* g = std::getenv("SNAPJUMP_GNUPLOT"); g != nullptr && *g != '\0') o.gnuplot = g;
  return o;
}

void add_common(CLI::App& cmd, std::string& format, std::string& output) {
  cmd.add_option("--format", format,
                 "png (default) or svg; without it, taken from --output's extension")
      ->check(CLI::IsMember({"png", "svg"}, CLI::ignore_case));
  cmd.add_option("--output", output,
                 "the image file; the gnuplot script is written beside it as <stem>.gp");
}

}  // namespace

PlotCommand::PlotCommand(CLI::App& app) {
  plot_ = app.add_subcommand(
      "plot",
      "Draw the paper's figures with gnuplot: a run's time series or cross-sections, a sweep's "
      "figures, the contact problem's branches. Each writes FIGURE.png (or .svg) and the script "
      "FIGURE.gp beside it.");
  plot_->require_subcommand(1);
  plot_->footer(
      "Examples:\n"
      "  snapjump plot series runs/default-20250101-120000\n"
      "  snapjump plot sections runs/default-20250101-120000 --times 0,200ms,450ms\n"
      "  snapjump plot sweep sweeps/mg/table.csv --figure phase --format svg\n"
      "  snapjump plot contact branches.csv\n"
      "SNAPJUMP_GNUPLOT names the gnuplot program (default gnuplot). See docs/figures.md.");

  series_ = plot_->add_subcommand(
      "series",
      "Fig. 2(a): container height z, contact radius r and apex gap w, plate force F and "
      "pressure difference delta_p against time, from RUN_DIR/series.csv (onset and launch "
      "marked from summary.json). Default output RUN_DIR/figures/series.png.");
  series_->add_option("run_dir", input_, "a folder written by `snapjump run`")->required();
  series_
      ->add_option("--experiment", experiment_,
                   "a measured record (CSV, as `snapjump analyze` reads it) drawn solid beside "
                   "the run (dashed); default output RUN_DIR/figures/series-experiment.png")
      ->check(CLI::ExistingFile);
  series_->add_option("--window", window_,
                      "the time window drawn, START:END after the release (the run's clock), "
                      "e.g. 450ms:560ms");
  series_
      ->add_option("--align", align_,
                   "with --experiment: shift the record so that its onset falls on the run's "
                   "(onset, the default) or draw both from the release (release)")
      ->check(CLI::IsMember({"onset", "release"}));
  series_->add_option("--column", columns_,
                      "with --experiment: which header names a column of the record, "
                      "NAME=HEADER (as for analyze)");
  series_->add_option("--unit", units_,
                      "with --experiment: unit of a record's column whose header has none, "
                      "NAME=UNIT");
  add_common(*series_, format_, output_);

  sections_ = plot_->add_subcommand(
      "sections",
      "Fig. 1(c): cross-sections of the shell (x-z plane) at chosen times, from the snapshots "
      "of RUN_DIR/run.pvd nearest them. Default output RUN_DIR/figures/sections.png.");
  sections_->add_option("run_dir", input_, "a folder written by `snapjump run`")->required();
  sections_
      ->add_option("--times", times_,
                   "comma-separated times after the release; seconds or with units, e.g. "
                   "0,0.2,0.45 or 0,200ms,450ms")
      ->required();
  add_common(*sections_, format_, output_);

  sweep_ = plot_->add_subcommand(
      "sweep",
      "Figures of a sweep's combined table: scaling (Fig. 2(b)-(e)), lift (Fig. 3(a)), flight "
      "(Fig. 3(b)), phase (Fig. 3(c)), friction (Fig. 4). Default output "
      "<table's folder>/figures/<figure>.png.");
  sweep_->add_option("table", input_, "the sweep's combined CSV table")->required();
  sweep_
      ->add_option("--figure", figure_,
                   "scaling, lift, flight, phase or friction (see docs/figures.md)")
      ->required()
      ->check(CLI::IsMember({"scaling", "lift", "flight", "phase", "friction"}, CLI::ignore_case));
  add_common(*sweep_, format_, output_);

  contact_ = plot_->add_subcommand(
      "contact",
      "Fig. S2(a): force N against plane displacement e_hat on the disk and ring branches, from "
      "`snapjump contact --curves FILE.csv`. Default output beside it: <stem>.png.");
  contact_->add_option("curves", input_, "the CSV of `snapjump contact --curves`")->required();
  add_common(*contact_, format_, output_);
}

bool PlotCommand::parsed() const { return plot_->parsed(); }

int PlotCommand::run(std::ostream& out, std::ostream& err) const {
  try {
    const auto options = figure_options(format_, output_);
    plot::FigureResult r;
    if (series_->parsed()) {
      plot::SeriesFigureOptions so;
      so.experiment = experiment_;
      if (!window_.empty()) so.window = parse_window(window_);
      so.align_at_release = align_ == "release";
      const auto pair = [](const std::string& text, const char* flag) {
        const auto eq = text.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
          throw plot::PlotInputError(fmt::format("{} {}: write NAME=VALUE", flag, text));
        }
        return std::pair{text.substr(0, eq), text.substr(eq + 1)};
      };
      for (const auto& c : columns_) so.read.columns.push_back(pair(c, "--column"));
      for (const auto& u : units_) so.read.units.push_back(pair(u, "--unit"));
      r = plot::plot_series(input_, options, so);
    } else if (sections_->parsed()) {
      r = plot::plot_sections(input_, parse_times(times_), options);
    } else if (sweep_->parsed()) {
      const auto figure = plot::parse_sweep_figure(figure_);
      if (!figure) {
        throw plot::PlotInputError(
            fmt::format("--figure {}: use scaling, lift, flight, phase or friction", figure_));
      }
      r = plot::plot_sweep(input_, *figure, options);
    } else if (contact_->parsed()) {
      r = plot::plot_contact(input_, options);
    } else {
      fmt::print(err, "error: plot: name a figure: series, sections, sweep or contact\n");
      return kExitBadInput;
    }
    for (const auto& note : r.notes) fmt::print(out, "note: {}\n", note);
    fmt::print(out, "figure  {}\nscript  {}\n", r.figure.string(), r.script.string());
    return kExitOk;
  } catch (const plot::PlotInputError& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const plot::PlotError& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitFailure;
  }
}

}  // namespace snapjump::app
