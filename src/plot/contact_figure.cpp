// Fig. S2(a): the disk and ring branches of the shell-plane contact problem, in rescaled units.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "plot/figures.hpp"
#include "plot/style.hpp"
#include "plot/table.hpp"
#include "theory/prefactors.hpp"

namespace snapjump::plot {

FigureResult plot_contact(const std::filesystem::path& curves, const FigureOptions& options) {
  const auto t = Table::read_csv_file(curves);
  t.require({"branch", "N", "e_hat"});
  if (t.empty()) {
    throw PlotInputError(fmt::format("{}: empty table (a header and no rows)", curves.string()));
  }
  std::vector<std::vector<double>> disk, ring;
  double e_max = 0.0, N_max = 0.0;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const auto& branch = t.text(r, "branch");
    const auto N = t.number(r, "N");
    const auto e = t.number(r, "e_hat");
    if (!N || !e) continue;
    if (branch == "disk") {
      disk.push_back({*e, *N});
    } else if (branch == "ring") {
      ring.push_back({*e, *N});
    } else {
      throw PlotInputError(fmt::format("{}: column 'branch': '{}' is neither disk nor ring",
                                       curves.string(), branch));
    }
    e_max = std::max(e_max, *e);
    N_max = std::max(N_max, *N);
  }
  if (disk.empty() && ring.empty()) {
    throw PlotInputError(
        fmt::format("{}: no row has values in both 'N' and 'e_hat'", curves.string()));
  }
  auto result = figure_paths(options, curves.parent_path() / curves.stem());
  // The constants the theory uses: the ring law N = n(2) sqrt(e_hat), N+ and N-.
  const auto& k = theory::contact_constants();
  const double n2 = k.n2, N_plus = k.upper.N, N_minus = k.lower.N;
  const double x_hi = 1.05 * e_max;
  const double y_hi = 1.12 * std::max(N_max, N_plus);

  std::string gp = fmt::format(
      "# Fig. S2(a) of the paper: a spherical shell pushed by a rigid plane, from {}.\n"
      "# Written by `snapjump plot contact`; edit and redraw with `gnuplot {}` in this folder.\n"
      "# Rescaled units (docs/contact-solver.md): e_hat = sqrt(kappa) e / h, "
      "N = kappa F R / (E h^3),\n# kappa = 12 (1 - nu^2); the curves do not depend on nu.\n"
      "# {}\n",
      printable(curves.string()), printable(result.script.filename().string()),
      printable(k.source));
  gp += terminal(options.format, 1000, 750, result.figure, 15);
  gp += datablock("disk", "e_hat  N  (disk branch)", disk);
  gp += datablock("ring", "e_hat  N  (ring branch, mirror-buckled)", ring);
  gp += fmt::format("set xrange [0:{}]\nset yrange [0:{}]\n", number(x_hi), number(y_hi));
  gp += "set samples 400\n";
  gp += "set xlabel 'plane displacement ê = √κ e / h [-]'\n";
  gp += "set ylabel 'force N = κ F R / (E h^3) [-]'\n";
  gp += "set title 'shell pushed by a rigid plane (κ = 12 (1 - ν^2))'\n";
  gp +=
      "set key bottom right Left reverse opaque box lc rgb '#c0c0c0' font ',13'\nset grid lc rgb "
      "'#e0e0e0'\n";
  std::vector<std::string> parts;
  if (!disk.empty()) {
    parts.push_back(
        fmt::format("$disk using 1:2 with lines lw 2.5 lc rgb '{}' title 'disk "
                    "branch (contact disk)'",
                    style::kBlue));
  }
  if (!ring.empty()) {
    parts.push_back(
        fmt::format("$ring using 1:2 with lines lw 2.5 lc rgb '{}' title 'ring "
                    "branch (mirror-buckled)'",
                    style::kRed));
  }
  parts.push_back(fmt::format(
      "'+' using 1:({}*sqrt($1)) with lines dt 2 lw 1.5 lc rgb '{}' title 'ring law N = n(2) √ê, "
      "n(2) = {:.2f}'",
      number(n2), style::kGreen, n2));
  parts.push_back(
      "'+' using 1:($1 <= 3 ? 8*$1 : NaN) with lines dt 3 lw 1.5 lc rgb '#606060' title 'Reissner, "
      "N = 8 ê'");
  parts.push_back(
      fmt::format("'+' using 1:({}) with lines dt 4 lw 1.5 lc rgb 'black' title 'N_{{+}} = {:.2f} "
                  "(disk buckles)'",
                  number(N_plus), N_plus));
  parts.push_back(
      fmt::format("'+' using 1:({}) with lines dt 5 lw 1.5 lc rgb '{}' title 'N_{{−}} = {:.2f} "
                  "(disk meets ring "
                  "law)'",
                  number(N_minus), style::kPurple, N_minus));
  std::string plot = "plot ";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    plot += (i > 0 ? ", \\\n     " : "") + parts[i];
  }
  gp += plot + "\n";
  render(result, gp, options.gnuplot);
  return result;
}

}  // namespace snapjump::plot
