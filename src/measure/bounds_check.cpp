#include "measure/bounds_check.hpp"

#include <fmt/format.h>

#include <optional>

namespace snapjump::measure {
namespace {

std::string kpa(double p) { return fmt::format("{:.3g} kPa", p / 1e3); }

// F* far above its bounds: a sub-millisecond spike that a plate would not record, the gas that
// presses the shell onto the plate after the valve's inflow has overshot, or a measured plate's
// noise and ringing (docs/axisymmetric.md, docs/popper.md).
std::string force_above(const Analysis& a, const theory::Range& b) {
  if (a.alpha_F_plate && *a.alpha_F_plate <= kFarFromBounds * b.hi) {
    return fmt::format(
        "F* is a spike the paper's 170 Hz force plate would not record: through it alpha_F is "
        "{:.3g} (alpha_F_plate, the one to compare)",
        *a.alpha_F_plate);
  }
  if (a.delta_p_onset && *a.delta_p_onset < 0.0) {
    return fmt::format(
        "the valve's inflow has overshot (delta_p = {} at the onset): the gas presses the shell "
        "onto the plate, and F* carries that load besides the snap's",
        kpa(*a.delta_p_onset));
  }
  return "F* includes a load besides the snap's: the valve's pressure overshoot after the onset "
         "(delta_p below zero), or in a measured record the plate's noise or ringing";
}

std::string force_below(const Analysis& a) {
  if (a.delta_p_onset && *a.delta_p_onset > 0.0) {
    return fmt::format(
        "the suction left at the onset ({}) holds the dimple in and takes a share of the snap's "
        "load off the plate (thick shells keep more of it)",
        kpa(*a.delta_p_onset));
  }
  return "F*'s window may miss the snap's peak, or suction left at the onset takes a share of the "
         "load off the plate (no delta_p to tell)";
}

std::string time_cause(const Analysis& a, bool above) {
  if (above) {
    return "the launch comes late: the plate force stays above the launch threshold (the plate's "
           "noise, a hop as the shell unrolls) after the snap";
  }
  return fmt::format(
      "t* is set by the shell's own dynamics more than by the apparatus's inertia in t_c "
      "(docs/popper.md: 0.38 to 0.50 in the simulated shells){}",
      a.alpha_t_net ? fmt::format("; with m = mg / g alpha_t is {:.3g}", *a.alpha_t_net) : "");
}

std::string cause(const std::string& quantity, bool above, const Analysis& a,
                  const theory::Range& b) {
  if (quantity == "alpha_F") return above ? force_above(a, b) : force_below(a);
  if (quantity == "alpha_t") return time_cause(a, above);
  if (quantity == "alpha_r") {
    return "r* is resolved to the mesh: the patch the plate pushes is about one particle spacing "
           "or element wider or narrower than the contact (docs/popper.md), and a shell far from "
           "the theory's shallow cap meets the plate otherwise";
  }
  return "the onset comes early or late against the theory's: the 3D grid's standoff (the cell "
         "against alpha_e h, docs/popper.md), or a shell far from the theory's shallow cap";
}

}  // namespace

std::string FarFromBounds::text() const {
  return fmt::format("{} = {:.3g} lies a factor {:.3g} {} bound {:.3g}: {}", quantity, value,
                     factor, above ? "above its upper" : "below its lower",
                     above ? bounds.hi : bounds.lo, cause);
}

std::vector<FarFromBounds> far_from_bounds(const Analysis& a, const theory::Prefactors& bounds) {
  struct Row {
    const char* name;
    const std::optional<double>& value;
    const theory::Range& bounds;
  };
  const Row rows[] = {{"alpha_r", a.alpha_r, bounds.alpha_r},
                      {"alpha_e", a.alpha_e, bounds.alpha_e},
                      {"alpha_F", a.alpha_F, bounds.alpha_F},
                      {"alpha_t", a.alpha_t, bounds.alpha_t}};
  std::vector<FarFromBounds> out;
  for (const auto& r : rows) {
    if (!r.value || !(*r.value > 0.0)) continue;
    const double v = *r.value;
    const bool above = v > kFarFromBounds * r.bounds.hi;
    if (!above && !(v * kFarFromBounds < r.bounds.lo)) continue;
    out.push_back({r.name, v, r.bounds, above, above ? v / r.bounds.hi : r.bounds.lo / v,
                   cause(r.name, above, a, r.bounds)});
  }
  return out;
}

}  // namespace snapjump::measure
