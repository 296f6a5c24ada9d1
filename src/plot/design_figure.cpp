#include "plot/design_figure.hpp"

#include <fmt/format.h>

#include <cmath>

namespace snapjump::plot {

FigureResult plot_design(const theory::DesignResult& result, const theory::Range& alpha_F,
                         const FigureOptions& options) {
  if (options.output.empty()) throw PlotInputError("design figure: name the image file");
  if (result.points.empty()) throw PlotInputError("design figure: no design was searched");
  auto paths = figure_paths(options, options.output);
  std::vector<std::vector<double>> searched, feasible, chosen;
  double x_lo = INFINITY, x_hi = 0.0;
  for (const auto& p : result.points) {
    (p.feasible ? feasible : searched).push_back({p.h_over_R, p.load, 1e3 * p.H_lower});
    x_lo = std::min(x_lo, p.h_over_R);
    x_hi = std::max(x_hi, p.h_over_R);
  }
  for (const auto& d : result.designs) {
    chosen.push_back(
        {d.h / d.R, d.prediction.F_c > 0.0 ? d.prediction.F_c * d.R / d.h / d.net_weight : NAN});
  }
  // The Jump / Snap boundary F* = mg: E h^2 / mg = 1 / (alpha_F h / R), at each end of alpha_F.
  std::vector<std::vector<double>> jump_lo, jump_hi;
  for (int i = 0; i <= 40; ++i) {
    const double x = x_lo * std::pow(x_hi / x_lo, i / 40.0);
    jump_lo.push_back({x, 1.0 / (alpha_F.lo * x)});
    jump_hi.push_back({x, 1.0 / (alpha_F.hi * x)});
  }
  std::string s = terminal(options.format, 1000, 720, paths.figure.filename());
  s += datablock("searched", "h/R, E h^2/mg, H lower bound [mm]", searched);
  s += datablock("feasible", "h/R, E h^2/mg, H lower bound [mm]", feasible);
  s += datablock("chosen", "h/R, E h^2/mg", chosen);
  s += datablock("jump_lo", "h/R, E h^2/mg on F* = mg at alpha_F's lower bound", jump_lo);
  s += datablock("jump_hi", "h/R, E h^2/mg on F* = mg at alpha_F's upper bound", jump_hi);
  s += "set logscale xy\nset xlabel 'h / R'\nset ylabel 'E h^2 / mg'\n";
  s += "set key outside top center horizontal\nset cblabel 'H, lower bound [mm]'\n";
  s += "set title 'snapjump design: the searched designs in the paper''s Fig. 3(c) plane'\n";
  s += "set palette rgb 33,13,10\n";
  s += "plot $searched using 1:2 with points pt 7 ps 0.3 lc rgb '#cccccc' title 'searched', \\\n"
       "     $feasible using 1:2:3 with points pt 7 ps 0.5 lc palette title 'meets the targets', "
       "\\\n"
       "     $jump_lo using 1:2 with lines dt 2 lc rgb 'black' title 'F* = mg (alpha_F low)', \\\n"
       "     $jump_hi using 1:2 with lines dt 3 lc rgb 'black' title 'F* = mg (alpha_F high)', \\\n"
       "     $chosen using 1:2 with points pt 6 ps 2 lw 2 lc rgb 'black' title 'listed designs', "
       "\\\n"
       "     $chosen using 1:2:(sprintf('%d', $0 + 1)) with labels offset 1.5,1 notitle\n";
  render(paths, s, options.gnuplot);
  paths.notes.push_back(fmt::format("{} searched designs, {} meet the targets",
                                    result.points.size(), feasible.size()));
  return paths;
}

}  // namespace snapjump::plot
