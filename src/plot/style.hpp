// The common look of snapjump's figures: colours, the theory band, panel margins.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

namespace snapjump::plot::style {

// Colours, distinct in print and for most colour-blind readers (Tableau 10).
inline constexpr std::string_view kBlue = "#1f77b4";
inline constexpr std::string_view kOrange = "#ff7f0e";
inline constexpr std::string_view kGreen = "#2ca02c";
inline constexpr std::string_view kRed = "#d62728";
inline constexpr std::string_view kPurple = "#9467bd";
inline constexpr std::string_view kBrown = "#8c564b";
inline constexpr std::string_view kPink = "#e377c2";
inline constexpr std::string_view kGrey = "#7f7f7f";
inline constexpr std::string_view kOlive = "#bcbd22";
inline constexpr std::string_view kCyan = "#17becf";
inline constexpr std::string_view kPalette[] = {kBlue,  kOrange, kGreen, kRed,   kPurple,
                                                kBrown, kPink,   kGrey,  kOlive, kCyan};

// The theory's band of bounds: light grey, see-through, no border.
inline constexpr std::string_view kBand = "fc rgb '#8c8c8c' fs transparent solid 0.3 noborder";
inline constexpr std::string_view kBandTitle = "theory bounds (contact solver)";
// Simulated points: open circles, as the paper draws simulations.
inline std::string points(std::string_view colour, int point_type = 6, double size = 1.6) {
  return fmt::format("with points pt {} ps {} lw 1.5 lc rgb '{}'", point_type, size, colour);
}

// Margins (screen fractions) that put panel `row` of `rows` stacked panels (row 0 on top) between
// `top` and `bottom`, with a small gap between panels.
inline std::string stacked_margins(int row, int rows, double top, double bottom, double left,
                                   double right, double gap = 0.012) {
  const double h = (top - bottom) / rows;
  const double t = top - row * h - (row > 0 ? gap / 2 : 0.0);
  const double b = top - (row + 1) * h + (row + 1 < rows ? gap / 2 : 0.0);
  return fmt::format(
      "set lmargin at screen {:.4f}; set rmargin at screen {:.4f}; set tmargin at screen {:.4f}; "
      "set bmargin at screen {:.4f}\n",
      left, right, t, b);
}

// A data range [lo, hi] widened for a plot: by `fraction` of its span on a linear axis, by the
// factor (1 + fraction)^... on a log axis; a single value gets +-20 % (linear) or a factor 1.5.
struct Span {
  double lo = 0.0;
  double hi = 1.0;
};
inline Span padded(double lo, double hi, bool log_axis, double fraction = 0.08) {
  if (log_axis) {
    if (!(hi > lo)) return {lo / 1.5, hi * 1.5};
    const double f = std::pow(hi / lo, fraction);
    return {lo / f, hi * f};
  }
  if (!(hi > lo)) {
    const double d = lo != 0.0 ? 0.2 * std::abs(lo) : 1.0;
    return {lo - d, hi + d};
  }
  const double d = fraction * (hi - lo);
  return {lo - d, hi + d};
}

}  // namespace snapjump::plot::style
