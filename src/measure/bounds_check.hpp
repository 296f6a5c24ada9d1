// Measured prefactors far outside the theory's bounds, each with its likely cause: what a run's
// results say beside the numbers, so that an alpha_F of 17 against 5.1 .. 8.0 is not read as any
// other number (docs/analysis.md, "Prefactors far from their bounds").
#pragma once

#include <string>
#include <vector>

#include "measure/analysis.hpp"
#include "theory/prefactors.hpp"

namespace snapjump::measure {

// How far beyond a bound a prefactor must lie to be called far from it: above the upper bound
// times this, or below the lower bound over it.
inline constexpr double kFarFromBounds = 1.5;

struct FarFromBounds {
  std::string quantity;  // "alpha_F"
  double value = 0.0;
  theory::Range bounds;
  bool above = false;
  double factor = 0.0;  // value / upper bound above, lower bound / value below
  std::string cause;    // the likely cause, in words
  // "alpha_F = 17.6 lies a factor 2.19 above its upper bound 8.04: <cause>"
  [[nodiscard]] std::string text() const;
};

// The prefactors of `a` (alpha_r, alpha_e, alpha_F, alpha_t) that lie far from `bounds`.
std::vector<FarFromBounds> far_from_bounds(const Analysis& a, const theory::Prefactors& bounds);

}  // namespace snapjump::measure
