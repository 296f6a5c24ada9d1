// Checks of an axisymmetric mesh against closed forms, shared by the tests of the crease fan and
// the fan layer.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "axi/body.hpp"

namespace snapjump::axi::mesh_checks {

// The patch test: a uniform dilatation by 1 %, whose stress is uniform and isotropic and so in
// equilibrium without body forces. Returns the largest force on a node inside the body (off the
// axis, the rim face and both surfaces) over the largest on any node: zero where the rule
// integrates the elements exactly (the full 3 x 3 rule, on any 9-node quadrilateral).
inline double patch_test_residual(const Body& b) {
  std::vector<char> boundary(b.num_nodes(), 0);
  for (const auto* set : {&b.axis(), &b.rim(), &b.outer(), &b.inner()}) {
    for (int a : *set) boundary[a] = 1;
  }
  auto x = b.nodes();
  for (std::size_t a = 0; a < x.size(); ++a) {
    x.r[a] *= 1.01;
    x.z[a] *= 1.01;
  }
  Points f;
  b.internal_forces(x, f);
  double largest = 0.0, inside = 0.0;
  for (std::size_t a = 0; a < f.size(); ++a) {
    const double m = std::hypot(f.r[a], f.z[a]);
    largest = std::max(largest, m);
    if (!boundary[a]) inside = std::max(inside, m);
  }
  return inside / largest;
}

// The closing crease as a closed form: about the root P, in its tangent (along the meridian)
// and normal (into the shell) frame, the polar angle theta in [0, pi] of the material goes to
// pi/2 + k(rho) (theta - pi/2), k = `closing` within `r1` of P, 1 beyond `r2`, linear between.
// Its meridian det F is k(rho) > 0 everywhere, so a fold found is the mesh's; k = 2 closes the
// crease (the surface turned through 180 degrees at P).
inline Points close_crease(const Body& b, int root, double closing, double r1, double r2) {
  constexpr double kPi = std::numbers::pi;
  const auto& X = b.nodes();
  const double px = X.r[root], pz = X.z[root];
  const double angle = std::atan2(px, -pz);  // the root's polar angle about the centre
  const double tr = std::cos(angle), tz = std::sin(angle);   // along the meridian, to the rim
  const double nr = std::sin(angle), nz = -std::cos(angle);  // outwards, into the shell
  auto x = X;
  for (std::size_t a = 0; a < x.size(); ++a) {
    const double dr = X.r[a] - px, dz = X.z[a] - pz;
    const double u = dr * tr + dz * tz, v = dr * nr + dz * nz;
    const double rho = std::hypot(u, v);
    if (rho >= r2 || rho == 0.0) continue;
    const double k = rho <= r1 ? closing : closing + (1.0 - closing) * (rho - r1) / (r2 - r1);
    // The inner surface curves away from its tangent at P: its points lie just outside
    // [0, pi], and the angle is taken on the far side of the cavity's normal -n.
    double theta = std::atan2(v, u);
    if (theta < -0.5 * kPi) theta += 2.0 * kPi;
    const double th = 0.5 * kPi + k * (theta - 0.5 * kPi);
    const double u2 = rho * std::cos(th), v2 = rho * std::sin(th);
    x.r[a] = px + u2 * tr + v2 * nr;
    x.z[a] = pz + u2 * tz + v2 * nz;
  }
  return x;
}

}  // namespace snapjump::axi::mesh_checks
