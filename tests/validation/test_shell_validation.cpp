// The shell body against physics nobody here wrote (docs/validation.md, "Shell body"):
//   Lame's thick-sphere solution and the membrane state of a pressurised spherical shell. (Zoelly's
//   buckling pressure and the inverted states of the five fabricated shells are measured through
//   the popper's own buckling phase: test_popper_validation.cpp.)
// Sizes are chosen so that the whole file runs in a few minutes on two cores.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "fem/explicit.hpp"
#include "mesh/cap_mesher.hpp"
#include "theory/scaling.hpp"

namespace snapjump::fem {
namespace {

constexpr double kE = 1.2e6, kRho = 1160.0;
const double kPhi = 80.0 * std::numbers::pi / 180.0;

double radial_displacement(const mesh::Points& X, const mesh::Points& x, int a) {
  const double r = std::hypot(X.x[a], X.y[a], X.z[a]);
  return (X.x[a] * (x.x[a] - X.x[a]) + X.y[a] * (x.y[a] - X.y[a]) + X.z[a] * (x.z[a] - X.z[a])) / r;
}

// Lame: a thick spherical shell (radii a < b) with pressure p_i inside and none outside has the
// radial displacement u(r) = p_i a^3 / (b^3 - a^3) ((1 - 2 nu) r / E + (1 + nu) b^3 / (2 E r^2)).
// Imposing that displacement on the rim face of the cap makes it the exact solution of the cap
// too; the body must reproduce it inside.
TEST(ShellValidation, LameThickSphereExactSolution) {
  const double R = 0.030, h = 0.001, nu = 0.3, dp = 20.0;  // dp = -p_i: suction inside
  const Body body(
      mesh::make_cap_mesh({.R = R, .h = h, .phi = kPhi, .element_size = 0.003, .layers = 1}),
      Material::from_young(kE, nu, kRho));
  const double a = R - h / 2, b = R + h / 2;
  const auto lame = [&](double r) {
    return -dp * a * a * a / (b * b * b - a * a * a) *
           ((1 - 2 * nu) * r / kE + (1 + nu) * b * b * b / (2 * kE * r * r));
  };
  const auto& X = body.mesh().nodes;
  ExplicitOptions o;
  o.time_step_factor = 0.5;
  o.damping = 1000.0;
  o.pressure = [&](double) { return dp; };
  o.clamp_displacement = [&](int n) {
    const double r = std::hypot(X.x[n], X.y[n], X.z[n]);
    const double s = lame(r) / r;
    return std::array<double, 3>{s * X.x[n], s * X.y[n], s * X.z[n]};
  };
  ExplicitDriver d(body, o);
  d.run_until(0.05);
  const int apex = body.mesh().apex;
  const double u = radial_displacement(X, d.positions(), apex);
  const double exact = lame(b);
  std::printf("Lame: apex radial displacement %.6e m, exact %.6e m, error %.3f %%\n", u, exact,
              100 * (u / exact - 1));
  EXPECT_NEAR(u / exact, 1.0, 0.005);
}

// A small pressure on the clamped (30, 1.0) mm cap. Far from the rim the shell is in the
// membrane state, a uniform radial displacement w = p R^2 (1 - nu) / (2 E h), carried along by a
// rigid translation t e_z (the clamp holds the rim, where the membrane state would move it by w
// along the normal, i.e. by w cos(phi) along z). Fit u = -w n + t e_z on the outer nodes within
// 40 deg of the apex. With either bulk rule (fem::BulkRule).
struct MembraneCase {
  double nu;
  BulkRule bulk;
};

void PrintTo(const MembraneCase& c, std::ostream* os) {
  *os << "nu = " << c.nu
      << (c.bulk == BulkRule::full ? ", bulk at four points" : ", bulk at the centroid");
}

class MembraneState : public ::testing::TestWithParam<MembraneCase> {};

TEST_P(MembraneState, UnderSmallPressure) {
  const double R = 0.030, h = 0.001, nu = GetParam().nu, dp = 20.0;
  const Body body(
      mesh::make_cap_mesh({.R = R, .h = h, .phi = kPhi, .element_size = 0.003, .layers = 1}),
      Material::from_young(kE, nu, kRho), GetParam().bulk);
  ExplicitOptions o;
  o.time_step_factor = 0.5;
  o.damping = 1000.0;
  o.pressure = [&](double t) { return dp * std::min(1.0, t / 0.002); };
  ExplicitDriver d(body, o);
  d.run_until(0.03);
  const auto& X = body.mesh().nodes;
  const auto& x = d.positions();
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  for (int n : body.mesh().outer) {
    const double r = std::hypot(X.x[n], X.y[n], X.z[n]);
    if (std::acos(-X.z[n] / r) > 40.0 * std::numbers::pi / 180.0) continue;
    // u = -w n + t e_z, n = X / r: three equations per node in the unknowns (w, t)
    const double nx = X.x[n] / r, ny = X.y[n] / r, nz = X.z[n] / r;
    const double u[3] = {x.x[n] - X.x[n], x.y[n] - X.y[n], x.z[n] - X.z[n]};
    const double cw[3] = {-nx, -ny, -nz}, ct[3] = {0, 0, 1};
    for (int i = 0; i < 3; ++i) {
      A(0, 0) += cw[i] * cw[i];
      A(0, 1) += cw[i] * ct[i];
      A(1, 1) += ct[i] * ct[i];
      rhs(0) += cw[i] * u[i];
      rhs(1) += ct[i] * u[i];
    }
  }
  A(1, 0) = A(0, 1);
  const Eigen::Vector2d wt = A.ldlt().solve(rhs);
  const double membrane = dp * R * R * (1 - nu) / (2 * kE * h);
  const int apex = body.mesh().apex;
  std::printf(
      "membrane (nu = %.2f, %s): raw apex displacement %.5e m = %.4f p R^2 (1 - nu) / (2 E h)\n",
      nu, GetParam().bulk == BulkRule::full ? "full" : "centroid", x.z[apex] - X.z[apex],
      (x.z[apex] - X.z[apex]) / membrane);
  std::printf(
      "membrane: fitted w %.5e m, p R^2 (1 - nu) / (2 E h) = %.5e m (ratio %.4f); "
      "translation %.3e m = %.3f w (cos phi = %.3f)\n",
      wt(0), membrane, wt(0) / membrane, wt(1), wt(1) / wt(0), std::cos(kPhi));
  EXPECT_NEAR(wt(0) / membrane, 1.0, 0.05);
}

INSTANTIATE_TEST_SUITE_P(ShellValidation, MembraneState,
                         ::testing::Values(MembraneCase{0.45, BulkRule::full},
                                           MembraneCase{0.45, BulkRule::centroid}));

}  // namespace
}  // namespace snapjump::fem
