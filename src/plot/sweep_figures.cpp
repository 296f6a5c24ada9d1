// Figures of a sweep's combined table: the scaling laws (Fig. 2(b)-(e)), the lift (Fig. 3(a)),
// the flight (Fig. 3(b)), the Jump / Snap / No snap diagram (Fig. 3(c)) and the friction
// dependence of the prefactors (Fig. 4).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "config/case.hpp"
#include "config/text.hpp"
#include "plot/figures.hpp"
#include "plot/style.hpp"
#include "plot/table.hpp"
#include "theory/scaling.hpp"
#include "theory/snap_boundary.hpp"

namespace snapjump::plot {
namespace {

namespace fs = std::filesystem;
using Rows = std::vector<std::vector<double>>;

Table read_table(const fs::path& path) {
  auto t = Table::read_csv_file(path);
  if (t.empty())
    throw PlotInputError(fmt::format("{}: empty table (a header and no rows)", path.string()));
  return t;
}

using text::lower;

// (x, y) of the rows where both are present, each times its scale.
// With `outcome`, only the rows whose outcome column reads so (any case).
Rows pairs(const Table& t, std::string_view x, std::string_view y, double sx = 1.0, double sy = 1.0,
           std::optional<std::string_view> outcome = std::nullopt) {
  Rows v;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    if (outcome && lower(t.text(r, "outcome")) != *outcome) continue;
    const auto a = t.number(r, x);
    const auto b = t.number(r, y);
    if (a && b) v.push_back({*a * sx, *b * sy});
  }
  return v;
}

// (x, lo, hi) of the rows where all three are present, sorted by x.
Rows band_rows(const Table& t, std::string_view x, std::string_view lo, std::string_view hi,
               double sx = 1.0, double sy = 1.0) {
  Rows v;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const auto a = t.number(r, x);
    const auto b = t.number(r, lo);
    const auto c = t.number(r, hi);
    if (a && b && c) v.push_back({*a * sx, std::min(*b, *c) * sy, std::max(*b, *c) * sy});
  }
  std::stable_sort(v.begin(), v.end(), [](const auto& p, const auto& q) { return p[0] < q[0]; });
  return v;
}

// How a band of per-row bounds continues to the edges of the plot.
enum class Extend { Constant, Proportional };

// The band carried from its first and last rows out to [x0, x1]: with the same bounds
// (quantities that do not depend on x) or in proportion to x (bounds of the form k x).
void extend(Rows& band, double x0, double x1, Extend how) {
  if (band.empty()) return;
  const auto first = band.front();
  const auto last = band.back();
  const auto at = [&](const std::vector<double>& row, double x) {
    const double f = how == Extend::Proportional && row[0] != 0.0 ? x / row[0] : 1.0;
    return std::vector<double>{x, row[1] * f, row[2] * f};
  };
  if (x0 < first[0]) band.insert(band.begin(), at(first, x0));
  if (x1 > last[0]) band.push_back(at(last, x1));
}

struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  [[nodiscard]] bool empty() const { return !(hi >= lo); }
};

Extent column_extent(const Rows& rows, std::size_t k) {
  Extent e;
  for (const auto& r : rows) e.add(r[k]);
  return e;
}

// The first row's (lo, hi) where both are present.
std::optional<std::pair<double, double>> first_bounds(const Table& t, std::string_view lo,
                                                      std::string_view hi) {
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const auto a = t.number(r, lo);
    const auto b = t.number(r, hi);
    if (a && b) return std::make_pair(std::min(*a, *b), std::max(*a, *b));
  }
  return std::nullopt;
}

std::string header(std::string_view what, const fs::path& table, const FigureResult& result) {
  return fmt::format(
      "# {}, from the sweep table {}.\n"
      "# Written by `snapjump plot sweep`; edit and redraw with `gnuplot {}` in this folder.\n",
      what, printable(table.string()), printable(result.script.filename().string()));
}

std::string no_rows_error(const Table& t, std::string_view x, std::string_view y) {
  return fmt::format("{}: no row has values in both '{}' and '{}'", t.source(), x, y);
}

// --- scaling, Fig. 2(b)-(e) ---

struct ScalingPanel {
  const char* tag;
  const char* x;
  const char* y;
  const char* alpha;
  double scale;
  const char* xlabel;
  const char* ylabel;
  const char* alpha_text;
};

constexpr std::array kScalingPanels{
    ScalingPanel{"(b) contact radius at the onset", "r_c", "r_star", "alpha_r", 1e3,
                 "r_c = √(hR) [mm]", "r* [mm]", "α_r"},
    ScalingPanel{"(c) apex displacement at the onset", "e_c", "e_star", "alpha_e", 1e3,
                 "e_c = h [mm]", "e* [mm]", "α_e"},
    ScalingPanel{"(d) peak plate force", "F_c", "F_star", "alpha_F", 1.0, "F_c = E h^3 / R [N]",
                 "F* [N]", "α_F"},
    ScalingPanel{"(e) disk contact time, onset to launch", "t_c", "t_star", "alpha_t", 1e3,
                 "t_c = √(m R / (E h^2)) [ms]", "t* [ms]", "α_t"},
};

std::string scaling(const Table& t, const fs::path& table, FigureResult& result,
                    const FigureOptions& options) {
  for (const auto& p : kScalingPanels) {
    const std::string lo = std::string(p.alpha) + "_lo", hi = std::string(p.alpha) + "_hi";
    t.require({p.x, p.y, lo, hi});
  }
  std::string gp =
      header("Fig. 2(b)-(e) of the paper: r*, e*, F*, t* against their scales", table, result);
  gp +=
      "# The bands are y = alpha_lo x .. alpha_hi x, the alpha bounds of the table's first row\n"
      "# (they depend only on nu).\n";
  gp += terminal(options.format, 1200, 1000, result.figure, 14);
  // With an outcome column, the runs that jump and those that only snap are told apart (a
  // snapping popper's F* includes its weight, and its t* is not a flight's launch); other
  // outcomes have no onset and are left out.
  struct Group {
    std::optional<std::string_view> outcome;
    const char* title;
    std::string points;  // gnuplot point style
  };
  std::vector<Group> groups;
  if (t.has("outcome")) {
    groups = {{"jump", "simulation: Jump", style::points(style::kBlue)},
              {"snap", "simulation: Snap", style::points(style::kOrange, 8)}};
  } else {
    groups = {{std::nullopt, "simulation", style::points(style::kBlue)}};
  }
  std::size_t total = 0;
  std::vector<std::vector<Rows>> panel_rows(kScalingPanels.size());
  for (std::size_t k = 0; k < kScalingPanels.size(); ++k) {
    const auto& p = kScalingPanels[k];
    for (std::size_t g = 0; g < groups.size(); ++g) {
      panel_rows[k].push_back(pairs(t, p.x, p.y, p.scale, p.scale, groups[g].outcome));
      total += panel_rows[k].back().size();
      gp += datablock(fmt::format("panel{}_{}", k, g), fmt::format("{}  {}", p.x, p.y),
                      panel_rows[k].back());
    }
  }
  if (total == 0) {
    throw PlotInputError(fmt::format(
        "{}: no row has a measured quantity with its scale (r_c and r_star, e_c and e_star, F_c "
        "and F_star, t_c and t_star)",
        t.source()));
  }
  gp +=
      "set multiplot layout 2,2 title 'characteristic quantities against the scaling "
      "predictions' font ',16'\n";
  gp += "set key top left Left reverse opaque box lc rgb '#c0c0c0' font ',13'\n";
  gp += "set grid lc rgb '#e0e0e0'\nset samples 2\n";
  for (std::size_t k = 0; k < kScalingPanels.size(); ++k) {
    const auto& p = kScalingPanels[k];
    Rows rows;
    for (const auto& g : panel_rows[k]) rows.insert(rows.end(), g.begin(), g.end());
    const auto bounds = first_bounds(t, std::string(p.alpha) + "_lo", std::string(p.alpha) + "_hi");
    const auto xs = column_extent(rows, 0);
    const auto ys = column_extent(rows, 1);
    // Every panel starts at the origin, where the scaling laws pass.
    double xmax = xs.empty() ? 1.0 : 1.15 * xs.hi;
    if (!(xmax > 0.0)) xmax = 1.0;
    double ymax = ys.empty() ? 0.0 : ys.hi;
    if (bounds) ymax = std::max(ymax, bounds->second * xmax);
    if (!(ymax > 0.0)) ymax = 1.0;
    gp += fmt::format("set title '{}'\n", p.tag);
    // Headroom above the points for the key.
    gp += fmt::format("set xrange [0:{}]\nset yrange [0:{}]\n", number(xmax), number(1.35 * ymax));
    gp += fmt::format("set xlabel '{}'\nset ylabel '{}'\n", p.xlabel, p.ylabel);
    std::string plot = "plot ";
    if (bounds) {
      gp += fmt::format("set label 2 '{} = {:.3g} … {:.3g}' at graph 0.96, 0.08 right front\n",
                        p.alpha_text, bounds->first, bounds->second);
      plot += fmt::format("'+' using 1:({}*$1):({}*$1) with filledcurves {} title '{}', ",
                          number(bounds->first), number(bounds->second), style::kBand,
                          style::kBandTitle);
    } else {
      result.notes.push_back(fmt::format("no {}_lo / {}_hi in the table: panel {} has no band",
                                         p.alpha, p.alpha, p.tag));
    }
    if (rows.empty()) {
      result.notes.push_back(
          fmt::format("no row has both {} and {}: panel {} is empty", p.x, p.y, p.tag));
      gp += "set label 1 'no data in the table' at graph 0.5, 0.5 center\n";
      plot += "NaN notitle\n";
    } else {
      std::vector<std::string> parts;
      for (std::size_t g = 0; g < groups.size(); ++g) {
        if (panel_rows[k][g].empty()) continue;
        parts.push_back(fmt::format("$panel{}_{} using 1:2 {} title '{}'", k, g, groups[g].points,
                                    groups[g].title));
      }
      plot += fmt::format("{}\n", fmt::join(parts, ", "));
    }
    gp += plot;
    gp += "unset label 1\nunset label 2\n";
  }
  gp += "unset multiplot\n";
  return gp;
}

// The key, the grid and the plot command of a figure with one theory band ($band, columns
// x, lower, upper) under the simulated points ($sim); without a band, a note says so.
std::string band_under_points(const Rows& band, const char* no_band_note, FigureResult& result) {
  std::string plot =
      "set key top left Left reverse opaque box lc rgb '#c0c0c0'\nset grid lc rgb '#e0e0e0'\nplot ";
  if (!band.empty()) {
    plot += fmt::format("$band using 1:2:3 with filledcurves {} title '{}', ", style::kBand,
                        style::kBandTitle);
  } else {
    result.notes.push_back(no_band_note);
  }
  plot += fmt::format("$sim using 1:2 {} title 'simulation'\n", style::points(style::kBlue));
  return plot;
}

// --- lift, Fig. 3(a) ---

std::string lift(const Table& t, const fs::path& table, FigureResult& result,
                 const FigureOptions& options) {
  t.require({"delta_p_j_over_p_c", "H_l", "H_l_lo", "H_l_hi"});
  const auto points = pairs(t, "delta_p_j_over_p_c", "H_l", 1.0, 1e3);
  auto band = band_rows(t, "delta_p_j_over_p_c", "H_l_lo", "H_l_hi", 1.0, 1e3);
  if (points.empty()) throw PlotInputError(no_rows_error(t, "delta_p_j_over_p_c", "H_l"));
  Extent xs = column_extent(points, 0);
  for (const auto& b : band) xs.add(b[0]);
  const auto xr = style::padded(xs.lo, xs.hi, false);
  extend(band, xr.lo, xr.hi, Extend::Constant);
  std::string gp =
      header("Fig. 3(a) of the paper: the lift H_l against delta_p_j / p_c", table, result);
  gp +=
      "# The band is the theory's H_l = R (1 - cos phi) - alpha_e h (fully inverted limit) of\n"
      "# each run, sorted by delta_p_j / p_c and carried flat to the edges.\n";
  gp += terminal(options.format, 1000, 750, result.figure, 15);
  gp += datablock("sim", "delta_p_j/p_c  H_l [mm]", points);
  gp += datablock("band", "delta_p_j/p_c  H_l_lo [mm]  H_l_hi [mm]", band);
  gp += fmt::format("set xrange [{}:{}]\n", number(xr.lo), number(xr.hi));
  gp += "set offsets 0, 0, graph 0.08, graph 0.08\n";
  gp += "set xlabel 'pressure difference at release δp_j / p_c [-]'\n";
  gp += "set ylabel 'lift H_l [mm]'\n";
  gp += "set title 'lift of the container up to the contact transition'\n";
  return gp + band_under_points(band, "no row has H_l_lo and H_l_hi: no theory band", result);
}

// --- flight, Fig. 3(b) ---

std::string flight(const Table& t, const fs::path& table, FigureResult& result,
                   const FigureOptions& options) {
  t.require({"Eh4_over_mgR2", "H_s", "R", "H_s_lo", "H_s_hi"});
  Rows points;
  Rows band;
  std::size_t dropped = 0;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const auto x = t.number(r, "Eh4_over_mgR2");
    const auto R = t.number(r, "R");
    if (!x || !R || !(*x > 0.0) || !(*R > 0.0)) continue;
    if (const auto Hs = t.number(r, "H_s")) {
      if (*Hs > 0.0) {
        points.push_back({*x, *Hs / *R});
      } else {
        ++dropped;
      }
    }
    const auto lo = t.number(r, "H_s_lo");
    const auto hi = t.number(r, "H_s_hi");
    if (lo && hi && std::min(*lo, *hi) > 0.0) {
      band.push_back({*x, std::min(*lo, *hi) / *R, std::max(*lo, *hi) / *R});
    }
  }
  if (dropped > 0) {
    result.notes.push_back(
        fmt::format("{} row(s) with H_s <= 0 left out (the axes are logarithmic)", dropped));
  }
  if (points.empty()) {
    throw PlotInputError(fmt::format(
        "{}: no row has a positive H_s with R and Eh4_over_mgR2 (nothing to draw on log axes)",
        t.source()));
  }
  std::stable_sort(band.begin(), band.end(),
                   [](const auto& p, const auto& q) { return p[0] < q[0]; });
  Extent xs = column_extent(points, 0);
  for (const auto& b : band) xs.add(b[0]);
  const auto xr = style::padded(xs.lo, xs.hi, true, 0.1);
  extend(band, xr.lo, xr.hi, Extend::Proportional);
  std::string gp =
      header("Fig. 3(b) of the paper: the flight H_s / R against E h^4 / (m g R^2)", table, result);
  gp +=
      "# The band is the theory's H_s = alpha_F alpha_e E h^4 / (m g R) of each run, divided by\n"
      "# R, sorted by E h^4 / (m g R^2) and carried in proportion to it to the edges.\n";
  gp += terminal(options.format, 1000, 750, result.figure, 15);
  gp += datablock("sim", "E h^4/(m g R^2)  H_s/R", points);
  gp += datablock("band", "E h^4/(m g R^2)  H_s_lo/R  H_s_hi/R", band);
  gp += "set logscale xy\n";
  gp += fmt::format("set xrange [{}:{}]\n", number(xr.lo), number(xr.hi));
  gp += "set xlabel 'E h^4 / (m g R^2) [-]'\nset ylabel 'flight height H_s / R [-]'\n";
  gp += "set title 'height gained by the snap'\n";
  return gp +
         band_under_points(band, "no row has positive H_s_lo and H_s_hi: no theory band", result);
}

// --- phase diagram, Fig. 3(c) ---

// The base case of the Snap / No snap boundary: the first run of the table with a case file that
// loads, the one its run wrote (runs/<run>/case.toml) or else the one the sweep planned
// (cases/<run>.toml).
std::optional<std::pair<config::Case, fs::path>> first_case(const Table& t, const fs::path& dir,
                                                            std::vector<std::string>& notes) {
  std::size_t tried = 0;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const auto& run = t.text(r, "run");
    if (run.empty()) continue;
    for (const auto& path : {dir / "runs" / run / "case.toml", dir / "cases" / (run + ".toml")}) {
      std::error_code ec;
      if (!fs::is_regular_file(path, ec)) continue;
      ++tried;
      try {
        return std::make_pair(config::load_case_file(path), path);
      } catch (const config::CaseError& e) {
        notes.push_back(fmt::format("{} left aside: {}", path.string(), e.what()));
      }
    }
  }
  notes.push_back(fmt::format(
      "no usable case file {}/runs/<run>/case.toml{}: only the Jump / Snap boundary is drawn",
      dir.string(), tried > 0 ? "" : " (none found)"));
  return std::nullopt;
}

// The points of the phase diagram, one group per outcome.
struct PhaseGroup {
  const char* key;  // outcome text, lower case; "" for the rest
  const char* title;
  int point_type;
  std::string_view colour;
  Rows rows;
};
using PhaseGroups = std::array<PhaseGroup, 5>;

// The rows with positive h/R and E h^2 / (m g), by outcome, and their extents.
PhaseGroups phase_groups(const Table& t, Extent& xs, Extent& ys) {
  PhaseGroups groups{
      PhaseGroup{"jump", "simulation: Jump", 6, style::kBlue, {}},
      PhaseGroup{"snap", "simulation: Snap", 8, style::kOrange, {}},
      PhaseGroup{"no snap", "simulation: No snap", 4, style::kRed, {}},
      PhaseGroup{"thrown", "simulation: Thrown", 12, "#7a3db8", {}},
      PhaseGroup{"", "failed / no outcome", 2, "#a0a0a0", {}},
  };
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const auto x = t.number(r, "h_over_R");
    const auto y = t.number(r, "Eh2_over_mg");
    if (!x || !y || !(*x > 0.0) || !(*y > 0.0)) continue;
    const auto outcome = lower(t.text(r, "outcome"));
    auto* g = &groups.back();
    for (auto& candidate : groups) {
      if (candidate.key[0] != '\0' && outcome == candidate.key) g = &candidate;
    }
    g->rows.push_back({*x, *y});
    xs.add(*x);
    ys.add(*y);
  }
  if (xs.empty()) {
    throw PlotInputError(fmt::format(
        "{}: no row has positive values in both 'h_over_R' and 'Eh2_over_mg'", t.source()));
  }
  return groups;
}

// The Snap / No snap boundary U / (mg H_l) = 1 over the x range, from the theory at the first
// run's case (theory::snap_boundary_weight): rows h/R, E h^2 / (m g) at the upper and at the lower
// end of the margin. `snap_case` names the case file used, empty when there is none.
Rows snap_boundary_rows(const Table& t, const fs::path& table, style::Span xr,
                        std::vector<std::string>& notes, std::string& snap_case) {
  Rows snap;
  const auto dir = table.parent_path().empty() ? fs::path(".") : table.parent_path();
  auto base = first_case(t, dir, notes);
  if (!base) return snap;
  const auto& k = theory::contact_constants();
  auto c = base->first;
  snap_case = base->second.string();
  const int n = 60;
  for (int i = 0; i < n; ++i) {
    const double x = xr.lo + (xr.hi - xr.lo) * i / (n - 1);
    c.shell.h = x * c.shell.R;
    const auto lo = theory::snap_boundary_weight(c, theory::SnapMarginEnd::Lower, k);
    const auto hi = theory::snap_boundary_weight(c, theory::SnapMarginEnd::Upper, k);
    const double scale = c.material.E * c.shell.h * c.shell.h;
    if (lo && hi) snap.push_back({x, scale / std::max(*lo, *hi), scale / std::min(*lo, *hi)});
  }
  if (snap.empty()) {
    notes.push_back(fmt::format(
        "the theory has no Snap / No snap boundary over h/R = {:.3g} .. {:.3g} at the case of {}",
        xr.lo, xr.hi, snap_case));
  }
  return snap;
}

// The y range: the data, and the boundaries within a factor 30 of it.
style::Span phase_y_range(const Extent& ys, const std::optional<std::pair<double, double>>& aF,
                          style::Span xr, const Rows& snap) {
  Extent yr = ys;
  const auto clip = [&](double v) {
    if (v > 0.0 && std::isfinite(v)) yr.add(std::clamp(v, ys.lo / 30.0, ys.hi * 30.0));
  };
  if (aF) {
    for (const double x : {xr.lo, xr.hi}) {
      clip(1.0 / (aF->first * x));
      clip(1.0 / (aF->second * x));
    }
  }
  for (const auto& s : snap) {
    clip(s[1]);
    clip(s[2]);
  }
  return style::padded(yr.lo, yr.hi, true, 0.1);
}

// The regions' names, where they fit: at 80 % of the x range, above both boundaries (Jump),
// between them (Snap), below the Snap / No snap boundary (No snap).
std::string region_labels(const std::optional<std::pair<double, double>>& aF, const Rows& snap,
                          style::Span xr, style::Span yrange) {
  std::string gp;
  const double x = xr.lo + 0.8 * (xr.hi - xr.lo);
  std::optional<double> jump_hi, jump_lo, snap_hi, snap_lo;
  if (aF) {
    jump_hi = 1.0 / (aF->first * x);
    jump_lo = 1.0 / (aF->second * x);
  }
  if (!snap.empty()) {
    const auto near = std::min_element(snap.begin(), snap.end(), [&](const auto& a, const auto& b) {
      return std::abs(a[0] - x) < std::abs(b[0] - x);
    });
    snap_lo = (*near)[1];
    snap_hi = (*near)[2];
  }
  const auto label = [&](const char* text, double y) {
    if (y > yrange.lo && y < yrange.hi) {
      gp += fmt::format("set label '{}' at {}, {} center font ',15' tc rgb '#505050' front\n", text,
                        number(x), number(y));
    }
  };
  const double top = std::max(jump_hi.value_or(0.0), snap_hi.value_or(0.0));
  if (top > 0.0) label("Jump", top * std::pow(yrange.hi / top, 0.5));
  if (jump_lo && snap_hi && *snap_hi < *jump_lo) label("Snap", std::sqrt(*snap_hi * *jump_lo));
  if (snap_lo) label("No snap", *snap_lo * std::pow(yrange.lo / *snap_lo, 0.5));
  return gp;
}

// The plot command: the Jump / Snap band, the Snap / No snap band, the points.
std::string phase_plot(const std::optional<std::pair<double, double>>& aF, const Rows& snap,
                       const PhaseGroups& groups, FigureResult& result) {
  std::vector<std::string> parts;
  if (aF) {
    parts.push_back(fmt::format(
        "'+' using 1:(1/({}*$1)):(1/({}*$1)) with filledcurves {} title 'theory: Jump / Snap, "
        "F*/mg = 1'",
        number(aF->second), number(aF->first), style::kBand));
    for (const double a : {aF->first, aF->second}) {
      parts.push_back(fmt::format(
          "'+' using 1:(1/({}*$1)) with lines dt 2 lw 1.5 lc rgb 'black' notitle", number(a)));
    }
  } else {
    result.notes.push_back("no row has alpha_F_lo and alpha_F_hi: no Jump / Snap boundary");
  }
  if (!snap.empty()) {
    parts.push_back(
        "$snap using 1:2:3 with filledcurves fc rgb '#5a5a5a' fs transparent solid 0.3 noborder "
        "title 'theory: Snap / No snap, U/(mg H_l) = 1'");
    parts.push_back("$snap using 1:2 with lines dt 4 lw 1.5 lc rgb '#303030' notitle");
    parts.push_back("$snap using 1:3 with lines dt 4 lw 1.5 lc rgb '#303030' notitle");
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].rows.empty()) continue;
    parts.push_back(fmt::format("$group{} using 1:2 {} title '{}'", g,
                                style::points(groups[g].colour, groups[g].point_type, 1.8),
                                groups[g].title));
  }
  std::string plot = "plot ";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    plot += (i > 0 ? ", \\\n     " : "") + parts[i];
  }
  return plot + "\n";
}

std::string phase(const Table& t, const fs::path& table, FigureResult& result,
                  const FigureOptions& options) {
  t.require({"run", "outcome", "h_over_R", "Eh2_over_mg", "alpha_F_lo", "alpha_F_hi"});
  Extent xs, ys;
  const auto groups = phase_groups(t, xs, ys);
  auto xr = style::padded(xs.lo, xs.hi, false, 0.1);
  if (!(xr.lo > 0.0)) xr.lo = 0.5 * xs.lo;
  xr.hi = std::min(xr.hi, 0.999);
  // The Jump / Snap boundary F*/mg = 1, i.e. E h^2 / (m g) = 1 / (alpha_F h / R).
  const auto aF = first_bounds(t, "alpha_F_lo", "alpha_F_hi");
  std::string snap_case;
  const Rows snap = snap_boundary_rows(t, table, xr, result.notes, snap_case);
  const auto yrange = phase_y_range(ys, aF, xr, snap);

  std::string gp =
      header("Fig. 3(c) of the paper: the Jump / Snap / No snap diagram", table, result);
  gp +=
      "# Theory: Jump / Snap where F*/mg = 1, E h^2/(m g) = 1/(alpha_F h/R), alpha_F bounds of\n"
      "# the table's first row; Snap / No snap where U/(mg H_l) = 1, solved by bisection on the\n"
      "# net weight with snapjump's theory (theory::predict, snap_margin lower and upper end)\n";
  if (aF) gp += fmt::format("# alpha_F = {} .. {}\n", number(aF->first), number(aF->second));
  if (!snap_case.empty()) {
    gp += fmt::format(
        "# at the case {} with h = (h/R) R while bisecting (the snap margin does not depend on\n"
        "# the moving mass).\n",
        printable(snap_case));
  } else {
    gp += "# (not drawn: no case file of a run was found).\n";
  }
  gp += terminal(options.format, 1100, 850, result.figure, 15);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    gp += datablock(fmt::format("group{}", g), fmt::format("{}: h/R  E h^2/(m g)", groups[g].title),
                    groups[g].rows);
  }
  if (!snap.empty()) {
    gp += datablock("snap", "h/R  E h^2/(m g) at U/(mg H_l) = 1, lower and upper bound", snap);
  }
  gp += "set logscale y\n";
  gp += fmt::format("set xrange [{}:{}]\nset yrange [{}:{}]\n", number(xr.lo), number(xr.hi),
                    number(yrange.lo), number(yrange.hi));
  gp += "set samples 200\n";
  gp += "set xlabel 'aspect ratio h / R [-]'\nset ylabel 'E h^2 / (m g) [-]'\n";
  gp += "set title 'Jump / Snap / No snap'\n";
  gp +=
      "set bmargin 8\nset key below center horizontal maxcols 2 Left reverse box lc rgb "
      "'#c0c0c0' font ',13'\n";
  gp += "set grid lc rgb '#e0e0e0'\n";
  gp += region_labels(aF, snap, xr, yrange);
  return gp + phase_plot(aF, snap, groups, result);
}

// --- friction, Fig. 4 ---

struct FrictionPanel {
  const char* alpha;
  const char* ylabel;
};

constexpr std::array kFrictionPanels{
    FrictionPanel{"alpha_r", "α_r = r* / √(hR) [-]"},
    FrictionPanel{"alpha_e", "α_e = e* / h [-]"},
    FrictionPanel{"alpha_F", "α_F = F* / (E h^3 / R) [-]"},
    FrictionPanel{"alpha_t", "α_t = t* / t_c [-]"},
};

std::string friction(const Table& t, const fs::path& table, FigureResult& result,
                     const FigureOptions& options) {
  t.require({"mu"});
  for (const auto& p : kFrictionPanels) {
    t.require({p.alpha, std::string(p.alpha) + "_lo", std::string(p.alpha) + "_hi"});
  }
  Extent xs;
  std::size_t total = 0;
  std::array<Rows, 4> points, bands;
  for (std::size_t k = 0; k < kFrictionPanels.size(); ++k) {
    const std::string a = kFrictionPanels[k].alpha;
    points[k] = pairs(t, "mu", a);
    bands[k] = band_rows(t, "mu", a + "_lo", a + "_hi");
    total += points[k].size();
    for (const auto& p : points[k]) xs.add(p[0]);
  }
  if (total == 0) {
    throw PlotInputError(fmt::format(
        "{}: no row has mu with a measured prefactor (alpha_r, alpha_e, alpha_F or alpha_t)",
        t.source()));
  }
  auto xr = style::padded(xs.lo, xs.hi, false, 0.08);
  std::string gp =
      header("Fig. 4 of the paper: the prefactors against the friction coefficient", table, result);
  gp +=
      "# The bands are the theory's alpha bounds (from the contact solver, at each run's nu),\n"
      "# sorted by mu and carried flat to the edges: the theory has no friction.\n";
  gp += terminal(options.format, 1200, 900, result.figure, 14);
  for (std::size_t k = 0; k < kFrictionPanels.size(); ++k) {
    extend(bands[k], xr.lo, xr.hi, Extend::Constant);
    gp += datablock(fmt::format("sim{}", k), fmt::format("mu  {}", kFrictionPanels[k].alpha),
                    points[k]);
    gp += datablock(
        fmt::format("band{}", k),
        fmt::format("mu  {}_lo  {}_hi", kFrictionPanels[k].alpha, kFrictionPanels[k].alpha),
        bands[k]);
  }
  gp +=
      "set multiplot layout 2,2 title 'prefactors against the friction coefficient' font "
      "',16'\n";
  gp += fmt::format("set xrange [{}:{}]\n", number(xr.lo), number(xr.hi));
  gp += "set offsets 0, 0, graph 0.1, graph 0.1\n";
  gp += "set xlabel 'friction coefficient μ [-]'\n";
  gp +=
      "set key top right Left reverse opaque box lc rgb '#c0c0c0' font ',12'\nset grid lc rgb "
      "'#e0e0e0'\n";
  for (std::size_t k = 0; k < kFrictionPanels.size(); ++k) {
    gp += fmt::format("set ylabel '{}'\n", kFrictionPanels[k].ylabel);
    std::string plot = "plot ";
    if (!bands[k].empty()) {
      plot += fmt::format("$band{} using 1:2:3 with filledcurves {} title '{}', ", k, style::kBand,
                          style::kBandTitle);
    } else {
      result.notes.push_back(fmt::format("no row has {}_lo and {}_hi: no band",
                                         kFrictionPanels[k].alpha, kFrictionPanels[k].alpha));
    }
    if (points[k].empty()) {
      gp += "set label 1 'no data in the table' at graph 0.5, 0.5 center\n";
      plot += bands[k].empty() ? "0 notitle\n" : "NaN notitle\n";
    } else {
      plot +=
          fmt::format("$sim{} using 1:2 {} title 'simulation'\n", k, style::points(style::kBlue));
    }
    gp += plot + "unset label 1\n";
  }
  gp += "unset multiplot\n";
  return gp;
}

}  // namespace

std::string_view to_string(SweepFigure f) {
  switch (f) {
    case SweepFigure::Scaling:
      return "scaling";
    case SweepFigure::Lift:
      return "lift";
    case SweepFigure::Flight:
      return "flight";
    case SweepFigure::Phase:
      return "phase";
    case SweepFigure::Friction:
      return "friction";
  }
  return "scaling";
}

std::optional<SweepFigure> parse_sweep_figure(std::string_view text) {
  for (const auto f : {SweepFigure::Scaling, SweepFigure::Lift, SweepFigure::Flight,
                       SweepFigure::Phase, SweepFigure::Friction}) {
    if (lower(text) == to_string(f)) return f;
  }
  return std::nullopt;
}

FigureResult plot_sweep(const fs::path& table, SweepFigure figure, const FigureOptions& options) {
  const auto t = read_table(table);
  const auto dir = table.parent_path().empty() ? fs::path(".") : table.parent_path();
  auto result = figure_paths(options, dir / "figures" / std::string(to_string(figure)));
  std::string gp;
  switch (figure) {
    case SweepFigure::Scaling:
      gp = scaling(t, table, result, options);
      break;
    case SweepFigure::Lift:
      gp = lift(t, table, result, options);
      break;
    case SweepFigure::Flight:
      gp = flight(t, table, result, options);
      break;
    case SweepFigure::Phase:
      gp = phase(t, table, result, options);
      break;
    case SweepFigure::Friction:
      gp = friction(t, table, result, options);
      break;
  }
  render(result, gp, options.gnuplot);
  return result;
}

}  // namespace snapjump::plot
