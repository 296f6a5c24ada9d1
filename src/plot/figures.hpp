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

#include "plot/gnuplot.hpp"

namespace snapjump::plot {

// RUN_DIR/series.csv (and RUN_DIR/summary.json when present); default image
// RUN_DIR/figures/series.png.
FigureResult plot_series(const std::filesystem::path& run_dir, const FigureOptions& options);

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
