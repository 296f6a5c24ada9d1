#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh/tet10.hpp"

namespace snapjump::mesh {
namespace {

// Reference coordinates of the tet10 nodes in gmsh's order (corners, then edge midpoints of
// (0,1), (1,2), (0,2), (0,3), (2,3), (1,3)), as gmsh's getElementProperties(11) lists them.
constexpr double kTetNodesRst[10][3] = {{0, 0, 0},   {1, 0, 0},   {0, 1, 0},  {0, 0, 1},
                                        {.5, 0, 0},  {.5, .5, 0}, {0, .5, 0}, {0, 0, .5},
                                        {0, .5, .5}, {.5, 0, .5}};
constexpr double kTriNodesRs[6][2] = {{0, 0}, {1, 0}, {0, 1}, {.5, 0}, {.5, .5}, {0, .5}};

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

TEST(Tet10, KroneckerProperty) {
  for (int b = 0; b < 10; ++b) {
    const auto N = tet10_shape(kTetNodesRst[b][0], kTetNodesRst[b][1], kTetNodesRst[b][2]);
    for (int a = 0; a < 10; ++a) EXPECT_NEAR(N[a], a == b ? 1.0 : 0.0, 1e-15) << a << " at " << b;
  }
}

TEST(Tet10, PartitionOfUnityAndLinearCompleteness) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    double r = u(rng), s = u(rng), t = u(rng);
    if (r + s + t > 1.0) {
      r /= 3;
      s /= 3;
      t /= 3;
    }
    const auto N = tet10_shape(r, s, t);
    const auto G = tet10_shape_gradients(r, s, t);
    double sum = 0, xr = 0, gsum[3] = {};
    for (int a = 0; a < 10; ++a) {
      sum += N[a];
      xr += N[a] * kTetNodesRst[a][0];  // reproduces the coordinate r
      for (int d = 0; d < 3; ++d) gsum[d] += G[a][d];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(xr, r, 1e-14);
    for (double g : gsum) EXPECT_NEAR(g, 0.0, 1e-13);
  }
}

TEST(Tet10, GradientsMatchFiniteDifferences) {
  const double r = 0.21, s = 0.17, t = 0.33, eps = 1e-6;
  const auto G = tet10_shape_gradients(r, s, t);
  for (int d = 0; d < 3; ++d) {
    double p[3] = {r, s, t}, m[3] = {r, s, t};
    p[d] += eps;
    m[d] -= eps;
    const auto Np = tet10_shape(p[0], p[1], p[2]);
    const auto Nm = tet10_shape(m[0], m[1], m[2]);
    for (int a = 0; a < 10; ++a) EXPECT_NEAR(G[a][d], (Np[a] - Nm[a]) / (2 * eps), 1e-8);
  }
}

TEST(Tri6, KroneckerUnityAndGradients) {
  for (int b = 0; b < 6; ++b) {
    const auto N = tri6_shape(kTriNodesRs[b][0], kTriNodesRs[b][1]);
    for (int a = 0; a < 6; ++a) EXPECT_NEAR(N[a], a == b ? 1.0 : 0.0, 1e-15);
  }
  const double r = 0.3, s = 0.45, eps = 1e-6;
  const auto N = tri6_shape(r, s);
  double sum = 0;
  for (double v : N) sum += v;
  EXPECT_NEAR(sum, 1.0, 1e-14);
  const auto G = tri6_shape_gradients(r, s);
  const auto Nr = tri6_shape(r + eps, s), Nl = tri6_shape(r - eps, s);
  const auto Nu = tri6_shape(r, s + eps), Nd = tri6_shape(r, s - eps);
  for (int a = 0; a < 6; ++a) {
    EXPECT_NEAR(G[a][0], (Nr[a] - Nl[a]) / (2 * eps), 1e-8);
    EXPECT_NEAR(G[a][1], (Nu[a] - Nd[a]) / (2 * eps), 1e-8);
  }
}

// integral of r^a s^b t^c over the reference tetrahedron = a! b! c! / (a + b + c + 3)!
double tet_monomial(int a, int b, int c) {
  return factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
}

void expect_exact_tet(std::span<const QuadraturePoint3> rule, int degree) {
  for (int a = 0; a <= degree; ++a) {
    for (int b = 0; a + b <= degree; ++b) {
      for (int c = 0; a + b + c <= degree; ++c) {
        double sum = 0.0;
        for (const auto& q : rule)
          sum += q.weight * std::pow(q.r, a) * std::pow(q.s, b) * std::pow(q.t, c);
        EXPECT_NEAR(sum, tet_monomial(a, b, c), 1e-14) << a << b << c;
      }
    }
  }
}

TEST(Quadrature, TetRulesAreExactToTheirDegree) {
  expect_exact_tet(tet_rule_degree2(), 2);
  expect_exact_tet(tet_rule_degree5(), 5);
  for (const auto& q : tet_rule_degree5()) EXPECT_GT(q.weight, 0.0);
  // and the degree-2 rule is not exact for degree 3 (so the check above can fail)
  double sum = 0.0;
  for (const auto& q : tet_rule_degree2()) sum += q.weight * q.r * q.r * q.r;
  EXPECT_GT(std::abs(sum - tet_monomial(3, 0, 0)), 1e-6);
}

TEST(Quadrature, TriangleRuleIsExactToDegreeFour) {
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; a + b <= 4; ++b) {
      double sum = 0.0;
      for (const auto& q : tri_rule_degree4())
        sum += q.weight * std::pow(q.r, a) * std::pow(q.s, b);
      // integral of r^a s^b over the reference triangle = a! b! / (a + b + 2)!
      EXPECT_NEAR(sum, factorial(a) * factorial(b) / factorial(a + b + 2), 1e-13) << a << b;
    }
  }
}

}  // namespace
}  // namespace snapjump::mesh
