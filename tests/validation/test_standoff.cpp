// Where the plate meets the shell: a shell pressed onto the rigid plate rests a fraction of a grid
// cell away from z = 0, since the plate acts on the grid nodes of the layers z = 0, -dx, -2dx and
// a particle feels them through its quadratic B-spline stencil (1.5 cells each way). A particle
// is held by plate nodes alone only once it is half a cell below z = 0, and it feels none at all
// from 1.5 cells above, so its resting height lies in [-0.5 dx, 1.5 dx]: it can only go to the
// plate's true position as dx goes to zero. This is why the grid spacing is tied to the thickness
// h (popper::resolve_numerics) and why it must be small against the onset's distances.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "validation/shell_over_plate.hpp"

namespace snapjump {
namespace {

struct Standoff {
  double apex = 0.0;   // mean height of the outer apex above z = 0 while held [m]
  double force = 0.0;  // mean plate force while held [N]
};

// The default shell (coarse mesh, sqrt(hR)/1.5 elements) lowered at 5 cm/s until the plate
// carries 1 N, then held for 20 ms; the apex height averaged over the last 10.
Standoff press(double dx) {
  using P = testing::ShellOverPlate;
  P s(0.3, dx, std::sqrt(P::h * P::R) / 1.5);
  s.rim.vz = -0.05;
  for (double next = 0.5e-3; s.mean_force_until(next, [] {}) < 1.0; next += 0.5e-3) {
    if (next > 0.2) ADD_FAILURE() << "the plate never carried 1 N";
  }
  s.rim.vz = 0.0;
  const double t_avg = s.stepper->time() + 0.01;
  double apex = 0.0;
  int n = 0;
  Standoff out;
  out.force = s.mean_force_until(s.stepper->time() + 0.02, [&] {
    if (s.stepper->time() > t_avg) {
      apex += s.apex_height();
      ++n;
    }
  });
  out.apex = apex / n;
  return out;
}

TEST(Standoff, ShellRestsWithinTheStencilsReachAndConvergesWithTheCell) {
  using P = testing::ShellOverPlate;
  const double cells[] = {P::h / 2, P::h / 4, P::h / 8};
  double previous = INFINITY;
  for (const double dx : cells) {
    const auto s = press(dx);
    std::printf(
        "standoff: dx = h/%.0f = %.3f mm: apex %.4f mm above the plate (%.3f dx) at %.3f N\n",
        P::h / dx, 1e3 * dx, 1e3 * s.apex, s.apex / dx, s.force);
    EXPECT_GE(s.apex, -0.5 * dx) << "dx = " << dx;
    EXPECT_LE(s.apex, 1.5 * dx) << "dx = " << dx;
    // Halving the cell brings the shell closer to the plate.
    EXPECT_LT(std::abs(s.apex), previous) << "dx = " << dx;
    previous = std::abs(s.apex);
  }
}

}  // namespace
}  // namespace snapjump
