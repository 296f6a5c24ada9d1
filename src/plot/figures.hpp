// The paper's figures drawn from snapjump's own outputs (docs/figures.md):
//   plot_series    Fig. 2(a): z, r and w, F, delta_p of one run against time
//   plot_sections  Fig. 1(c): cross-sections of the shell at chosen times
//   plot_sweep     Fig. 2(b)-(e), 3(a)-(c), 4 from a sweep's combined table
//   plot_contact   Fig. S2(a): the disk and ring branches of the shell-plane contact problem
// Each writes FIGURE.gp and the image beside it and returns their paths. Bad input throws
// PlotInputError, a gnuplot failure PlotError (plot/gnuplot.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "measure/time_series.hpp"
#include "plot/gnuplot.hpp"

namespace snapjump::plot {

// What plot_series draws besides the run.
struct SeriesFigureOptions {
  // A measured record (the reader's formats, docs/analysis.md) drawn solid, the run dashed;
  // panels the record has no column of are left out. Empty: the run alone.
  std::filesystem::path experiment;
  // The time window drawn [s, the run's clock]; the whole run (and record) when absent.
  std::optional<std::pair<double, double>> window;
  // The record is shifted so that its onset falls on the run's; with this, not shifted (both
  // clocks start at the release, as the valve opens).
  bool align_at_release = false;
  // How to read the record (column mapping, units by option).
  measure::ReadOptions read;
};

// RUN_DIR/series.csv (and RUN_DIR/summary.json when present); default image
// RUN_DIR/figures/series.png (series-experiment.png with a record).
FigureResult plot_series(const std::filesystem::path& run_dir, const FigureOptions& options,
                         const SeriesFigureOptions& series_options = {});

// The snapshot of RUN_DIR/run.pvd nearest each time [s]; default image
// RUN_DIR/figures/sections.png.
FigureResult plot_sections(const std::filesystem::path& run_dir, std::span<const double> times,
                           const FigureOptions& options);

enum class SweepFigure { Scaling, Lift, Flight, Phase, Friction };
std::string_view to_string(SweepFigure f);  // "scaling", ...
std::optional<SweepFigure> parse_sweep_figure(std::string_view text);

// A sweep's combined table; default image <table's folder>/figures/<figure>.png.
FigureResult plot_sweep(const std::filesystem::path& table, SweepFigure figure,
                        const FigureOptions& options);

// The branch curves of `snapjump contact --curves FILE.csv`; default image beside it,
// <stem>.png.
FigureResult plot_contact(const std::filesystem::path& curves, const FigureOptions& options);

}  // namespace snapjump::plot
