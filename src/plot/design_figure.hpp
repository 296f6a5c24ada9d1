// The design figure of `snapjump design --figure`: every searched cap in the paper's Fig. 3(c)
// plane (h / R against E h^2 / mg), those that meet the targets coloured by H's lower bound, the
// Jump / Snap boundary F* = mg at both ends of alpha_F, and the listed designs numbered.
#pragma once

#include "plot/gnuplot.hpp"
#include "theory/design.hpp"

namespace snapjump::plot {

// options.output names the image (.png or .svg). Throws PlotInputError without one or without
// searched designs, PlotError when gnuplot fails.
FigureResult plot_design(const theory::DesignResult& result, const theory::Range& alpha_F,
                         const FigureOptions& options);

}  // namespace snapjump::plot
