#include "popper/reverse_snap.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "axi/body.hpp"
#include "axi/static_branch.hpp"
#include "popper/material.hpp"
#include "theory/scaling.hpp"

namespace snapjump::popper {

ReverseSnap reverse_snap(const config::Case& c) {
  const int through = config::preset(config::Resolution::Coarse).axi_through;
  const int along = axi::elements_along(c.shell.R, c.shell.h, c.shell.phi, through);
  const axi::Body body(
      {.R = c.shell.R, .h = c.shell.h, .phi = c.shell.phi, .through = through, .along = along},
      body_material(c.material));
  axi::BranchOptions o;
  o.p_ref = theory::zoelly_pressure(c.material.E, c.shell.h, c.shell.R, c.material.nu);
  // Steps of 0.1 find the same extrema as 0.02 to 0.01 % on the default shell (docs).
  o.step = 0.1;
  o.end_volume = -0.9;
  const auto t0 = std::chrono::steady_clock::now();
  const auto b = axi::trace_static_branch(body, o);
  ReverseSnap r;
  r.model = fmt::format(
      "axisymmetric finite elements, quasi-static branch, {} x {} elements (the coarse mesh)",
      along, through);
  r.p_c = b.p_c;
  r.p_minus = b.p_minus;
  r.p_hold = b.p_hold;
  r.note = b.reached_end ? "" : b.stop_reason;
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace snapjump::popper
