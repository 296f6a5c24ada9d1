// What to try after a preparation that ended the run: the shell did not invert, or it snapped
// back before the release (in the air at delta_p_j, or on the plate as it was grounded).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "popper/popper.hpp"
#include "popper/reverse_snap.hpp"

namespace snapjump::app {

// What the axisymmetric quasi-static branch of the case's cap (b; nothing, with why, where it
// could not be computed) says about the buckling suction against the preparation's,
// buckle_factor Zoelly's p_c (pc). Where the run itself followed such a branch on its own mesh
// (run_followed_a_branch: the axisymmetric model, which has no such bound), a branch that
// buckles points to the reason the run's branch stopped, not to the discretisation.
std::string buckling_hint(const std::optional<popper::ReverseSnap>& b, const std::string& why,
                          double pc, double buckle_factor, bool run_followed_a_branch);

// What the branch says about the suction that holds the inverted shell, against delta_p_j. A
// shell that snapped back on the plate (on_plate) at a delta_p_j the branch holds it at was
// pushed back by the plate carrying its net weight (net_weight [N]), not let go by the
// discretisation.
std::string holding_hint(const std::optional<popper::ReverseSnap>& b, const std::string& why,
                         double pc, double delta_p_j, bool on_plate, double net_weight);

// The hints for the case and its preparation: the suctions of the theory and of the
// axisymmetric branch (popper::reverse_snap), a finer preset, the other model.
std::vector<std::string> preparation_hints(const config::Case& c, const popper::Preparation& prep,
                                           double buckle_factor, double delta_p_j);

}  // namespace snapjump::app
