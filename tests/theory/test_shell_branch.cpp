// The axisymmetric shell branch against physics it does not contain as such: the membrane state
// of a pressurised sphere, the conservation of energy along the branch, its own convergence, the
// mirror symmetry of inversion, and Budiansky's snap-through pressures of clamped shallow caps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "theory/shell_branch.hpp"

namespace snapjump::theory {
namespace {

constexpr double kPi = std::numbers::pi;

double deg(double d) { return d * kPi / 180.0; }

double zoelly(const ShellBranchSpec& s) {
  return 2.0 * s.E * s.h * s.h / (s.R * s.R * std::sqrt(3.0 * (1.0 - s.nu * s.nu)));
}

// The thinnest of the paper's shells.
ShellBranchSpec thin_popper() { return ShellBranchSpec{0.030, 0.001, deg(80.0), 1.2e6, 0.45, 0}; }

// A clamped cap of R / h = R_over_h whose rise H gives the shallow-shell parameter
// lambda = 2 [3 (1 - nu^2)]^(1/4) sqrt(H / h), i.e. H = h lambda^2 / (4 sqrt(3 (1 - nu^2))).
ShellBranchSpec shallow_cap(double lambda, double R_over_h, double nu) {
  const double h = 0.001;
  const double R = R_over_h * h;
  const double H = h * lambda * lambda / (4.0 * std::sqrt(3.0 * (1.0 - nu * nu)));
  return ShellBranchSpec{R, h, std::acos(1.0 - H / R), 1.0e6, nu, 0};
}

// Far from the rim a clamped deep cap under a small pressure is in the membrane state of a
// sphere: a uniform inward normal displacement w = dp R^2 (1 - nu) / (2 E h), here carried along
// with a rigid axial translation c (the clamp's boundary layer moves the interior as a whole).
// Both are fitted to the nodes within 40 deg of the apex.
TEST(ShellBranch, MembraneStateFarFromTheRim) {
  const ShellBranchSpec s = thin_popper();
  const double dp = 1e-3 * zoelly(s);
  const ShellState st = solve_shell_at_pressure(s, dp);
  std::vector<const MeridianNode*> inner;
  for (const MeridianNode& n : st.nodes) {
    if (n.s0 / s.R <= deg(40.0)) inner.push_back(&n);
  }
  ASSERT_GE(inner.size(), 10u);
  const auto rows = static_cast<Eigen::Index>(2 * inner.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, 2);
  Eigen::VectorXd b(rows);
  for (std::size_t i = 0; i < inner.size(); ++i) {
    const double th = inner[i]->s0 / s.R;
    const auto k = static_cast<Eigen::Index>(2 * i);
    A(k, 0) = -std::sin(th);  // radial displacement -w sin(theta)
    b(k) = inner[i]->r - inner[i]->r0;
    A(k + 1, 0) = -std::cos(th);  // axial displacement -w cos(theta) + c
    A(k + 1, 1) = 1.0;
    b(k + 1) = inner[i]->z - inner[i]->z0;
  }
  const Eigen::Vector2d x = A.colPivHouseholderQr().solve(b);
  const double w_membrane = dp * s.R * s.R * (1.0 - s.nu) / (2.0 * s.E * s.h);
  const double rms = (A * x - b).norm() / std::sqrt(static_cast<double>(rows));
  std::printf("membrane state: w / w_membrane = %.5f, c / w = %.4f, rms misfit / w = %.2e\n",
              x(0) / w_membrane, x(1) / x(0), rms / x(0));
  EXPECT_NEAR(x(0) / w_membrane, 1.0, 0.01);
  EXPECT_LT(rms / x(0), 0.01);
}

// With the rim fixed the follower pressure is conservative: the work -Int dp dV done on the shell
// from the natural state equals its strain energy at every point of the branch, through the
// buckling, the volume's turning back and the inversion. Trapezoid rule on the branch points.
TEST(ShellBranch, PressureWorkEqualsStrainEnergy) {
  const ShellBranchSpec s = thin_popper();
  const ShellBranch b = trace_shell_branch(s);
  ASSERT_TRUE(b.reached_inverted) << b.note;
  ASSERT_GE(b.points.size(), 3u);
  EXPECT_DOUBLE_EQ(b.points.front().volume, b.V0);
  EXPECT_EQ(b.points.front().dp, 0.0);
  EXPECT_LE(b.points.back().volume, -b.V0);
  double work = 0.0, worst = 0.0, u_max = 0.0;
  for (std::size_t i = 1; i < b.points.size(); ++i) {
    const BranchPoint& p = b.points[i - 1];
    const BranchPoint& q = b.points[i];
    work -= 0.5 * (p.dp + q.dp) * (q.volume - p.volume);
    worst = std::max(worst, std::abs(work - q.strain_energy));
    u_max = std::max(u_max, q.strain_energy);
  }
  std::printf("energy: %zu points, max U = %.5g J, max |W - U| / max U = %.2e\n", b.points.size(),
              u_max, worst / u_max);
  EXPECT_LT(worst / u_max, 1e-3);
}

// p_c and p_- of the thinnest popper at half, one and two times the default mesh.
TEST(ShellBranch, ConvergesWithRefinement) {
  ShellBranchSpec s = thin_popper();
  const ShellBranch def = trace_shell_branch(s);
  s.segments = 2 * def.segments;
  const ShellBranch fine = trace_shell_branch(s);
  s.segments = def.segments / 2;
  const ShellBranch coarse = trace_shell_branch(s);
  for (const ShellBranch* b : {&coarse, &def, &fine}) {
    std::printf("%4d segments: p_c = %.3f Pa (%.5f p_cl), p_- = %.3f Pa (%.5f p_cl)\n", b->segments,
                b->p_c, b->p_c / b->p_cl, b->p_minus, b->p_minus / b->p_cl);
  }
  EXPECT_NEAR(def.p_c / fine.p_c, 1.0, 0.005);
  EXPECT_NEAR(def.p_minus / fine.p_minus, 1.0, 0.005);
  EXPECT_LE(std::abs(def.p_c - fine.p_c), std::abs(coarse.p_c - fine.p_c) + 1e-9 * fine.p_c);
}

// Inversion by mirror symmetry: the mirror image of a cap (z -> -z) has the same meridian length
// and radii, so for a thin shallow cap the inverted state of volume -V0 is its mirror image up to
// the rim's boundary layer, and the apex has moved by twice the rise H. The clamped cap stays
// monostable (p_- > 0): the ridge of a mirror-buckled region needs a pressure to hold it.
TEST(ShellBranch, InvertedShallowCapIsTheMirrorImage) {
  const ShellBranchSpec s = shallow_cap(20.0, 1000.0, 0.3);
  const ShellBranch b = trace_shell_branch(s);
  ASSERT_TRUE(b.reached_inverted) << b.note;
  const BranchPoint& p = b.points[b.points.size() - 2];
  const BranchPoint& q = b.points.back();
  ASSERT_GT(p.volume, -b.V0);
  const double t = (-b.V0 - p.volume) / (q.volume - p.volume);
  const double apex = p.apex_z + t * (q.apex_z - p.apex_z);
  const double H = s.R * (1.0 - std::cos(s.phi));
  std::printf(
      "mirror: apex displacement at V = -V0 over 2 H = %.4f; p_c = %.4f p_cl, p_- = %.4f "
      "p_cl\n",
      -apex / (2.0 * H), b.p_c / b.p_cl, b.p_minus / b.p_cl);
  EXPECT_NEAR(-apex / (2.0 * H), 1.0, 0.02);
  EXPECT_GT(b.p_minus, 0.0);
}

// Axisymmetric snap-through pressures of clamped shallow spherical caps, p_c / p_cl against
// lambda: Budiansky, B. (1959), "Buckling of clamped shallow spherical shells", Proc. IUTAM
// Symposium on the Theory of Thin Elastic Shells, Delft, as tabulated in Teng, J.G. & Rotter, J.M.
// (1989), "Elastic-plastic large deflection analysis of axisymmetric shells", Computers &
// Structures 31(2), 211-233, Table 1 (numbers read from the AQUINAS-FE examples,
// src/Examples/input_Example_GNA05.csv, whose caps are R / h = 100, nu = 0.3). Teng & Rotter's
// own large-deflection shell values for the same caps are printed alongside.
TEST(ShellBranch, BudianskySnapThroughPressures) {
  struct Row {
    double lambda, budiansky, teng_rotter;
  };
  for (const Row& row : {Row{4.0, 0.578, 0.563}, Row{6.0, 0.995, 0.972}, Row{7.0, 1.068, 1.046},
                         Row{8.0, 1.130, 1.109}}) {
    const ShellBranchSpec s = shallow_cap(row.lambda, 100.0, 0.3);
    const ShellBranch b = trace_shell_branch(s);
    const double ratio = b.p_c / b.p_cl;
    std::printf(
        "lambda = %.1f (phi = %.2f deg): p_c / p_cl = %.4f, Budiansky %.3f, "
        "Teng & Rotter %.3f\n",
        row.lambda, s.phi * 180.0 / kPi, ratio, row.budiansky, row.teng_rotter);
    EXPECT_NEAR(ratio / row.budiansky, 1.0, 0.025) << "lambda = " << row.lambda;
  }
}

TEST(ShellBranch, RejectsBadInput) {
  const ShellBranchSpec good = thin_popper();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto with = [&](auto change) {
    ShellBranchSpec s = good;
    change(s);
    return s;
  };
  const std::vector<ShellBranchSpec> bad{
      with([](ShellBranchSpec& s) { s.R = 0.0; }),
      with([](ShellBranchSpec& s) { s.R = -0.03; }),
      with([&](ShellBranchSpec& s) { s.R = nan; }),
      with([](ShellBranchSpec& s) { s.h = 0.0; }),
      with([](ShellBranchSpec& s) { s.h = 0.05; }),
      with([](ShellBranchSpec& s) { s.E = -1.0; }),
      with([](ShellBranchSpec& s) { s.phi = 0.0; }),
      with([](ShellBranchSpec& s) { s.phi = kPi; }),
      with([](ShellBranchSpec& s) { s.nu = -1.0; }),
      with([](ShellBranchSpec& s) { s.nu = 0.51; }),
      with([](ShellBranchSpec& s) { s.segments = -1; }),
      with([](ShellBranchSpec& s) { s.segments = 2; }),
  };
  for (const ShellBranchSpec& s : bad) {
    EXPECT_THROW(trace_shell_branch(s), std::invalid_argument);
    EXPECT_THROW(solve_shell_at_pressure(s, 1.0), std::invalid_argument);
  }
  EXPECT_THROW(solve_shell_at_pressure(good, nan), std::invalid_argument);
  // Far beyond the buckling pressure there is no equilibrium on the natural branch.
  EXPECT_THROW(solve_shell_at_pressure(good, 5.0 * zoelly(good)), std::runtime_error);
  std::printf("bad input: %zu specifications rejected\n", bad.size());
}

}  // namespace
}  // namespace snapjump::theory
