#include "app/preparation_hints.hpp"

#include <fmt/format.h>

#include <cmath>
#include <exception>

#include "theory/scaling.hpp"

namespace snapjump::app {

std::string buckling_hint(const std::optional<popper::ReverseSnap>& b, const std::string& why,
                          double pc, double buckle_factor, bool run_followed_a_branch) {
  if (!b) return fmt::format("the axisymmetric branch's p_c could not be computed: {}", why);
  if (!std::isfinite(b->p_c)) {
    return fmt::format(
        "the cap's axisymmetric quasi-static branch has no buckling maximum{}: it does not snap "
        "under suction at all; a deeper or thinner cap does",
        b->note.empty() ? std::string() : " (" + b->note + ")");
  }
  const auto at = fmt::format(
      "the cap's axisymmetric quasi-static branch buckles at p_c = "
      "{:.0f} Pa ({:.3g} Zoelly's p_c)",
      b->p_c, b->p_c / pc);
  if (run_followed_a_branch) {
    // Its preparation takes the branch through the maximum wherever it lies.
    return at +
           ": the run's own branch, on the run's mesh, stopped before the inverted state, "
           "for the reason its preparation line gives";
  }
  if (b->p_c > buckle_factor * pc) {
    return at + ", beyond the preparation's suction: a thinner or deeper cap buckles within it";
  }
  return at +
         ", within the preparation's suction: the discretisation kept the shell from "
         "inverting";
}

std::string holding_hint(const std::optional<popper::ReverseSnap>& b, const std::string& why,
                         double pc, double delta_p_j, bool on_plate, double net_weight) {
  if (!b) return fmt::format("the axisymmetric branch's p_hold could not be computed: {}", why);
  if (!std::isfinite(b->p_hold)) {
    return fmt::format(
        "the cap's axisymmetric quasi-static branch does not reach the fully inverted shell{}{}",
        b->note.empty() ? "" : ": ", b->note);
  }
  const auto hold = fmt::format(
      "the cap's axisymmetric quasi-static branch holds the fully inverted shell from p_hold = "
      "{:.0f} Pa ({:.3g} p_c)",
      b->p_hold, b->p_hold / pc);
  if (delta_p_j < b->p_hold) {
    return fmt::format(
        "{}; delta_p_j = {:.0f} Pa is below it: raise --delta-p-j (or "
        "--delta-p-j-over-pc)",
        hold, delta_p_j);
  }
  if (on_plate) {
    return fmt::format(
        "{}; delta_p_j = {:.0f} Pa is above it, and the shell held there in the air: on the "
        "plate, carrying the net weight of {:.3g} N, it was pushed back (a lighter popper, or a "
        "higher --delta-p-j)",
        hold, delta_p_j, net_weight);
  }
  return fmt::format(
      "{}; delta_p_j = {:.0f} Pa is above it: the discretisation let the shell "
      "snap back",
      hold, delta_p_j);
}

std::vector<std::string> preparation_hints(const config::Case& c, const popper::Preparation& prep,
                                           double buckle_factor, double delta_p_j) {
  const double pc = theory::zoelly_pressure(c.material.E, c.shell.h, c.shell.R, c.material.nu);
  std::optional<popper::ReverseSnap> branch;
  std::string why;
  try {
    branch = popper::reverse_snap(c);
  } catch (const std::exception& e) {
    why = e.what();
  }
  std::vector<std::string> hints;
  if (prep.inverted) {
    hints.push_back(
        holding_hint(branch, why, pc, delta_p_j, prep.snapped_back_on_plate, c.popper.net_weight));
  } else {
    // The axisymmetric preparation follows its branch as far as it goes, with no suction bound.
    const bool axi = c.numerics.model == config::Model::Axisymmetric;
    hints.push_back(
        axi ? fmt::format("Zoelly's p_c of the case is {:.0f} Pa (snapjump predict)", pc)
            : fmt::format("Zoelly's p_c of the case is {:.0f} Pa (snapjump predict); the "
                          "preparation raised the suction to {:.3g} p_c = {:.0f} Pa",
                          pc, buckle_factor, buckle_factor * pc));
    hints.push_back(buckling_hint(branch, why, pc, buckle_factor, axi));
  }
  const auto r = c.numerics.resolution;
  hints.push_back(r == config::Resolution::Fine
                      ? std::string("the finest preset is in use: numerics.element_size, "
                                    "numerics.grid_spacing and numerics.elements_through_thickness "
                                    "refine further")
                      : fmt::format("a finer preset: --resolution {}",
                                    r == config::Resolution::Coarse ? "default" : "fine"));
  hints.push_back(fmt::format("the other model: --model {}",
                              c.numerics.model == config::Model::ThreeD ? "axisymmetric" : "3d"));
  return hints;
}

}  // namespace snapjump::app
