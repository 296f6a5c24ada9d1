// The clamped cap's buckling and reverse-snap suctions for a case, from the axisymmetric model's
// quasi-static pressure-volume branch (axi/static_branch.hpp), for `snapjump predict`: what the
// closed forms cannot say (whether the inverted shell holds, and down to which suction).
#pragma once

#include <string>

#include "config/case.hpp"

namespace snapjump::popper {

struct ReverseSnap {
  std::string model;  // what computed it, in words (the mesh)
  // The branch's buckling maximum; its lowest suction after it (below which no buckled state is
  // left: positive means monostable); the lowest suction that holds the fully inverted shell
  // [Pa]. NaN where the branch did not get there (note says why).
  double p_c = 0.0, p_minus = 0.0, p_hold = 0.0;
  std::string note;
  double wall_time = 0.0;  // [s]
};

// On the case's coarse axisymmetric mesh (its elements through h and along the meridian as the
// coarse preset makes them), the branch followed to V = -0.9 V0: past the inverted segment's
// minimum of the default shells. Throws config::CaseError where the case cannot be meshed.
ReverseSnap reverse_snap(const config::Case& c);

}  // namespace snapjump::popper
