// The fold check (fem/fold_check.hpp): a determinant negative only between the quadrature points
// is found, one negative only between the first sample points is found by splitting, a positive
// one whose first Bernstein coefficients are not all positive is proven positive, and the bodies
// name the folded element.
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <numbers>

#include "axi/body.hpp"
#include "fem/body.hpp"
#include "fem/fold_check.hpp"
#include "mesh/cap_mesher.hpp"
#include "mesh/tet10.hpp"

namespace snapjump::fem {
namespace {

// The nine-node square [-1, 1]^2 with nodes at the lattice (a - 1, b - 1), written out here
// (independently of axi::Body): the determinant of d(x, y) / d(s, t) at (s, t).
using Square = std::array<std::array<std::array<double, 2>, 3>, 3>;
double square_det(const Square& n, double s, double t) {
  const auto L = [](double u) {
    return std::array<double, 3>{0.5 * u * (u - 1.0), 1.0 - u * u, 0.5 * u * (u + 1.0)};
  };
  const auto dL = [](double u) { return std::array<double, 3>{u - 0.5, -2.0 * u, u + 0.5}; };
  double xs = 0, xt = 0, ys = 0, yt = 0;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      xs += n[a][b][0] * dL(s)[a] * L(t)[b];
      ys += n[a][b][1] * dL(s)[a] * L(t)[b];
      xt += n[a][b][0] * L(s)[a] * dL(t)[b];
      yt += n[a][b][1] * L(s)[a] * dL(t)[b];
    }
  }
  return xs * yt - xt * ys;
}

Square unit_square() {
  Square n{};
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) n[a][b] = {a - 1.0, b - 1.0};
  }
  return n;
}

// A corner node pulled halfway to the centre along the diagonal: the corner is crushed
// (det = -0.5 there) while every Gauss point of the 3 x 3 and the 2 x 2 rules stays positive,
// so a check at the quadrature points passes the element.
TEST(FoldCheck, ACornerCrushedBetweenTheQuadraturePointsIsFound) {
  auto n = unit_square();
  n[2][2] = {0.5, 0.5};
  for (const int points : {2, 3}) {
    const double g = points == 2 ? 1.0 / std::sqrt(3.0) : std::sqrt(0.6);
    for (double s : {-g, 0.0, g}) {
      for (double t : {-g, 0.0, g}) {
        if (points == 2 && (s == 0.0 || t == 0.0)) continue;
        EXPECT_GT(square_det(n, s, t), 0.0) << "Gauss point (" << s << ", " << t << ")";
      }
    }
  }
  EXPECT_NEAR(square_det(n, 1.0, 1.0), -0.5, 1e-12);
  const auto c = check_bicubic_on_square([&](double s, double t) { return square_det(n, s, t); });
  EXPECT_FALSE(c.positive);
  EXPECT_LE(c.min_found, 0.0);
  EXPECT_LE(square_det(n, c.at[0], c.at[1]), 0.0);
  // Undeformed, stretched and turned: proven positive at once.
  auto m = unit_square();
  for (auto& row : m) {
    for (auto& p : row) p = {2.0 * p[0] * 0.6 - 0.8 * p[1], 2.0 * p[0] * 0.8 + 0.6 * p[1]};
  }
  const auto ok = check_bicubic_on_square([&](double s, double t) { return square_det(m, s, t); });
  EXPECT_TRUE(ok.positive);
  EXPECT_EQ(ok.cells, 1);
  EXPECT_NEAR(ok.min_found, 2.0, 1e-12);
}

// (s - 1/2)^2 - 1/100 is negative only for 0.4 < s < 0.6, between the first lattice's s = 1/3
// and s = 1: splitting must find it. (s - 1/2)^2 + 1/100 has a negative Bernstein coefficient on
// [-1, 1] but is positive: splitting must prove it.
TEST(FoldCheck, SplittingFindsAFoldBetweenTheSamplesAndProvesAPositiveCubic) {
  const auto neg =
      check_bicubic_on_square([](double s, double) { return std::pow(s - 0.5, 2) - 0.01; });
  EXPECT_FALSE(neg.positive);
  EXPECT_GT(neg.cells, 1);
  EXPECT_GT(neg.at[0], 0.4);
  EXPECT_LT(neg.at[0], 0.6);
  const auto pos =
      check_bicubic_on_square([](double s, double) { return std::pow(s - 0.5, 2) + 0.01; });
  EXPECT_TRUE(pos.positive);
  EXPECT_GT(pos.cells, 1);
  EXPECT_GT(pos.lower_bound, 0.0);
  EXPECT_LE(pos.lower_bound, 0.01 + 1e-12);
  // The same on the tetrahedron along r (negative for 0.418 < r < 0.482; the first lattice
  // has r = 1/3 and 2/3, the first split's 1/2).
  const auto tneg = check_cubic_on_tetrahedron(
      [](const std::array<double, 3>& xi) { return std::pow(xi[0] - 0.45, 2) - 0.001; });
  EXPECT_FALSE(tneg.positive);
  EXPECT_GT(tneg.cells, 1);
  EXPECT_LE(std::pow(tneg.at[0] - 0.45, 2) - 0.001, 0.0);
  const auto tpos = check_cubic_on_tetrahedron(
      [](const std::array<double, 3>& xi) { return std::pow(xi[0] - 0.45, 2) + 0.001; });
  EXPECT_TRUE(tpos.positive);
  EXPECT_GT(tpos.cells, 1);
}

// The ten-node tetrahedron with a corner node pulled halfway to the centroid: negative at that
// corner, positive at the four points of the degree-2 rule the body integrates with.
TEST(FoldCheck, ACrushedTetrahedronCornerIsFoundWhereItsQuadraturePointsArePositive) {
  std::array<std::array<double, 3>, 10> X{};
  X[0] = {0, 0, 0};
  X[1] = {1, 0, 0};
  X[2] = {0, 1, 0};
  X[3] = {0, 0, 1};
  for (int e = 0; e < 6; ++e) {
    for (int d = 0; d < 3; ++d) {
      X[4 + e][d] = 0.5 * (X[mesh::kTetEdges[e][0]][d] + X[mesh::kTetEdges[e][1]][d]);
    }
  }
  auto x = X;
  x[0] = {0.125, 0.125, 0.125};  // halfway to the centroid
  const auto det_at = [&](double r, double s, double t) {
    const auto G = mesh::tet10_shape_gradients(r, s, t);
    double A[3][3] = {};
    for (int a = 0; a < 10; ++a) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) A[i][j] += x[a][i] * G[a][j];
      }
    }
    return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
           A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
           A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  };
  for (const auto& q : mesh::tet_rule_degree2()) EXPECT_GT(det_at(q.r, q.s, q.t), 0.0);
  EXPECT_LT(det_at(0, 0, 0), 0.0);
  const auto c = check_tet10(X, x);
  EXPECT_FALSE(c.positive);
  EXPECT_LE(det_at(c.at[0], c.at[1], c.at[2]), 0.0);
  EXPECT_TRUE(check_tet10(X, X).positive);
  EXPECT_NEAR(check_tet10(X, X).min_found, 1.0, 1e-12);
}

// The bodies: the undeformed caps pass; a node pushed through its element names that element.
TEST(FoldCheck, TheBodiesNameTheFoldedElement) {
  const double phi = 80.0 * std::numbers::pi / 180.0;
  const auto material = Material::from_young(1.2e6, 0.45, 1160.0);
  const axi::MeshSpec spec{0.03, 0.002, phi, 2, axi::elements_along(0.03, 0.002, phi, 2)};
  const axi::Body axi_body(spec, material);
  auto x = axi_body.nodes();
  EXPECT_NO_THROW(axi_body.check_folds(x));
  // The inner surface's node next to the rim, pushed 0.5 mm (half the thickness) outwards.
  const int nj = 2 * spec.through + 1, i = 2 * spec.along - 1, node = i * nj;
  const double theta = phi * i / (2 * spec.along);
  x.r[node] += 5e-4 * std::sin(theta);
  x.z[node] -= 5e-4 * std::cos(theta);
  const int element = (spec.along - 1) * spec.through;  // next to the rim, inner layer
  try {
    axi_body.check_folds(x);
    ADD_FAILURE() << "the fold was not found";
  } catch (const FoldedElement& e) {
    EXPECT_EQ(e.element, element) << e.what();
    EXPECT_LE(e.det_f, 0.0);
  }

  const Body body(
      mesh::make_cap_mesh({.R = 0.03, .h = 0.002, .phi = phi, .element_size = 0.008, .layers = 1}),
      material);
  auto y = body.mesh().nodes;
  EXPECT_NO_THROW(body.check_folds(y));
  // The first element's first corner pulled towards the element's centroid, past it.
  const auto& tet = body.mesh().tets[0];
  double c[3] = {};
  for (int a = 0; a < 4; ++a) {
    c[0] += 0.25 * y.x[tet[a]];
    c[1] += 0.25 * y.y[tet[a]];
    c[2] += 0.25 * y.z[tet[a]];
  }
  const int a0 = tet[0];
  y.x[a0] += 1.5 * (c[0] - y.x[a0]);
  y.y[a0] += 1.5 * (c[1] - y.y[a0]);
  y.z[a0] += 1.5 * (c[2] - y.z[a0]);
  // The lowest-numbered element holding that node, at any thread count.
  int lowest = -1;
  for (std::size_t k = 0; k < body.mesh().tets.size() && lowest < 0; ++k) {
    for (int n : body.mesh().tets[k]) {
      if (n == a0) lowest = static_cast<int>(k);
    }
  }
  for (const int threads : {1, 2, 4}) {
    omp_set_num_threads(threads);
    try {
      body.check_folds(y);
      ADD_FAILURE() << "the fold was not found at " << threads << " threads";
    } catch (const FoldedElement& e) {
      EXPECT_EQ(e.element, lowest) << threads << " threads: " << e.what();
    }
  }
  omp_set_num_threads(1);
}

}  // namespace
}  // namespace snapjump::fem
