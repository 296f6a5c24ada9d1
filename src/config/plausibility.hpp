// What a popper can plausibly be: the one table of ranges that a case's given values are held
// against before `snapjump predict`, `run` and `mesh` work on it (the command line refuses a value
// outside unless --allow-implausible) and that `analyze` warns by for its R.
//
// The ranges are wide on purpose: they catch a misreading, above all a number written without its
// unit and read in SI (`--R 30` is 30 m, `--E 1.2` is 1.2 Pa), not a bold design. Each row says
// why its ends lie where they do.
#pragma once

#include <span>
#include <string_view>

namespace snapjump::config {

struct PlausibleRange {
  std::string_view key;   // the case key, "shell.R"
  double lo = 0.0;        // [SI]
  double hi = 0.0;        // [SI]
  std::string_view text;  // the range as written for people, "1 mm .. 1 m"
  std::string_view what;  // the quantity in words, "a popper's shell radius"
  std::string_view why;
  [[nodiscard]] bool holds(double v) const { return v >= lo && v <= hi; }
};

// Every row, in the order of the case keys.
std::span<const PlausibleRange> plausible_ranges();
// The row of a dotted case key; nullptr for a key the table does not bound.
const PlausibleRange* plausible_range(std::string_view key);

}  // namespace snapjump::config
