// The theory's Snap / No snap boundary (the phase diagram, Fig. 3(c)): the net weight at which the
// fully inverted shell's energy just lifts the popper by H_l.
#pragma once

#include <optional>

#include "config/case.hpp"
#include "theory/prefactors.hpp"

namespace snapjump::theory {

// Which end of the snap margin U / (mg H_l) (Prediction::snap_margin) a boundary is drawn for.
enum class SnapMarginEnd { Lower, Upper };

// The net weight mg [N] at which the chosen end of the case's snap margin U / (mg H_l), as
// predict() gives it, is 1: lighter poppers have a margin above 1 (they snap), heavier ones below
// (No snap). Found by bisection in log mg, from the case's own net weight (1 N when it has none)
// bracketed by factors of 10, to a relative width of 1e-12; the rest of the case is kept. Nothing
// when there is no such weight, e.g. where the theory gives H_l no value (the indentation reaches
// the cap's depth).
std::optional<double> snap_boundary_weight(config::Case c, SnapMarginEnd end,
                                           const ContactConstants& constants);

}  // namespace snapjump::theory
