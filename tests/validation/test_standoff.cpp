// Where the plate meets the shell: a shell pressed onto the rigid plate rests a fraction of a grid
// cell away from z = 0, since the plate acts on the grid nodes of the layers z = 0, -dx, -2dx and
// a particle feels them through its quadratic B-spline stencil (1.5 cells each way). A particle
// is held by plate nodes alone only once it is half a cell below z = 0, and it feels none at all
// from 1.5 cells above, so its resting height lies in [-0.5 dx, 1.5 dx]: it can only go to the
// plate's true position as dx goes to zero. This is why the grid spacing is tied to the thickness
// h (popper::resolve_numerics) and why it must be small against the onset's distances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "contact/contact.hpp"
#include "validation/shell_over_plate.hpp"

namespace snapjump {
namespace {

struct Standoff {
  double apex = 0.0;    // mean height of the outer apex above z = 0 while held [m]
  double force = 0.0;   // mean plate force while held [N]
  double radius = 0.0;  // mean contact radius while held, as snapjump run measures it [m]
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
  double apex = 0.0, radius = 0.0;
  int n = 0;
  Standoff out;
  const auto& x = s.stepper->particles().x;
  out.force = s.mean_force_until(s.stepper->time() + 0.02, [&] {
    if (s.stepper->time() > t_avg) {
      apex += s.apex_height();
      // The popper's r: the outermost outer particle that the plate carries.
      double r = 0.0;
      for (int a : s.shell->mesh().outer) {
        if (mpm::plate_carries(*s.plate, dx, x.x[a], x.y[a], x.z[a])) {
          r = std::max(r, std::hypot(x.x[a], x.y[a]));
        }
      }
      radius += r;
      ++n;
    }
  });
  out.apex = apex / n;
  out.radius = radius / n;
  return out;
}

// The contact solver's flat contact disk radius at force F (its disk branch, shallow-shell
// theory): N = kappa F R / (E h^3), r = a sqrt(h R) / kappa^(1/4).
double disk_radius(double F) {
  using P = testing::ShellOverPlate;
  const double kappa = 12.0 * (1.0 - P::nu * P::nu);
  const double N = kappa * F * P::R / (P::E * P::h * P::h * P::h);
  const auto branch = contact::disk_branch();
  for (std::size_t i = 1; i < branch.size(); ++i) {
    if (branch[i].N >= N) {
      const double f = (N - branch[i - 1].N) / (branch[i].N - branch[i - 1].N);
      const double a = branch[i - 1].a + f * (branch[i].a - branch[i - 1].a);
      return a * std::sqrt(P::h * P::R) / std::pow(kappa, 0.25);
    }
  }
  return NAN;
}

// Pressed with about 1 N, the shell also shows where the plate carries it: the contact radius
// that `snapjump run` reports (outer particles with at least half their stencil weight on the
// loaded plate nodes) against the contact solver's disk radius at the same force. Its resolution
// is one particle spacing along the surface (half an element, 2.6 mm here: the next particle out
// may be the one that carries load) plus the stencil's reach of 1.5 cells sideways.
TEST(Standoff, ShellRestsWithinTheStencilsReachAndConvergesWithTheCell) {
  using P = testing::ShellOverPlate;
  const double cells[] = {P::h / 2, P::h / 4, P::h / 8};
  const double spacing = std::sqrt(P::h * P::R) / 1.5 / 2.0;  // particles along the surface
  double previous = INFINITY;
  for (const double dx : cells) {
    const auto s = press(dx);
    const double r_theory = disk_radius(s.force);
    std::printf(
        "standoff: dx = h/%.0f = %.3f mm: apex %.4f mm above the plate (%.3f dx) at %.3f N; "
        "contact radius %.2f mm, the contact solver's disk %.2f mm\n",
        P::h / dx, 1e3 * dx, 1e3 * s.apex, s.apex / dx, s.force, 1e3 * s.radius, 1e3 * r_theory);
    EXPECT_GE(s.apex, -0.5 * dx) << "dx = " << dx;
    EXPECT_LE(s.apex, 1.5 * dx) << "dx = " << dx;
    // Halving the cell brings the shell closer to the plate.
    EXPECT_LT(std::abs(s.apex), previous) << "dx = " << dx;
    previous = std::abs(s.apex);
    EXPECT_NEAR(s.radius, r_theory, spacing + 1.5 * dx) << "dx = " << dx;
  }
}

}  // namespace
}  // namespace snapjump
