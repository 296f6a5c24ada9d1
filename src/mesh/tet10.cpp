#include "mesh/tet10.hpp"

#include <cmath>
#include <vector>

namespace snapjump::mesh {

std::array<double, kTetNodes> tet10_shape(double r, double s, double t) {
  const std::array<double, 4> L{1.0 - r - s - t, r, s, t};
  std::array<double, kTetNodes> N{};
  for (int a = 0; a < 4; ++a) N[a] = L[a] * (2.0 * L[a] - 1.0);
  for (int e = 0; e < 6; ++e) N[4 + e] = 4.0 * L[kTetEdges[e][0]] * L[kTetEdges[e][1]];
  return N;
}

std::array<std::array<double, 3>, kTetNodes> tet10_shape_gradients(double r, double s, double t) {
  const std::array<double, 4> L{1.0 - r - s - t, r, s, t};
  // dL_a / d(r, s, t)
  constexpr std::array<std::array<double, 3>, 4> dL{
      {{-1.0, -1.0, -1.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  std::array<std::array<double, 3>, kTetNodes> G{};
  for (int a = 0; a < 4; ++a) {
    for (int d = 0; d < 3; ++d) G[a][d] = (4.0 * L[a] - 1.0) * dL[a][d];
  }
  for (int e = 0; e < 6; ++e) {
    const int i = kTetEdges[e][0], j = kTetEdges[e][1];
    for (int d = 0; d < 3; ++d) G[4 + e][d] = 4.0 * (dL[i][d] * L[j] + L[i] * dL[j][d]);
  }
  return G;
}

std::array<double, kTriNodes> tri6_shape(double r, double s) {
  const std::array<double, 3> L{1.0 - r - s, r, s};
  std::array<double, kTriNodes> N{};
  for (int a = 0; a < 3; ++a) N[a] = L[a] * (2.0 * L[a] - 1.0);
  for (int e = 0; e < 3; ++e) N[3 + e] = 4.0 * L[kTriEdges[e][0]] * L[kTriEdges[e][1]];
  return N;
}

std::array<std::array<double, 2>, kTriNodes> tri6_shape_gradients(double r, double s) {
  const std::array<double, 3> L{1.0 - r - s, r, s};
  constexpr std::array<std::array<double, 2>, 3> dL{{{-1.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}}};
  std::array<std::array<double, 2>, kTriNodes> G{};
  for (int a = 0; a < 3; ++a) {
    for (int d = 0; d < 2; ++d) G[a][d] = (4.0 * L[a] - 1.0) * dL[a][d];
  }
  for (int e = 0; e < 3; ++e) {
    const int i = kTriEdges[e][0], j = kTriEdges[e][1];
    for (int d = 0; d < 2; ++d) G[3 + e][d] = 4.0 * (dL[i][d] * L[j] + L[i] * dL[j][d]);
  }
  return G;
}

namespace {

// The 4-point degree-2 rule: points at (a, b, b), (b, a, b), ... with
// a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20, equal weights.
std::array<QuadraturePoint3, 4> make_degree2() {
  const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0;
  const double b = (5.0 - std::sqrt(5.0)) / 20.0;
  const double w = 1.0 / 24.0;
  return {{{b, b, b, w}, {a, b, b, w}, {b, a, b, w}, {b, b, a, w}}};
}

// Gauss-Legendre nodes and weights on [0, 1], n = 4.
constexpr std::array<double, 4> kGL4x{0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                                      0.9305681557970263};
constexpr std::array<double, 4> kGL4w{0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                                      0.1739274225687269};

// Collapsed cube -> tetrahedron: r = u, s = v (1 - u), t = w (1 - u)(1 - v), Jacobian
// (1 - u)^2 (1 - v). Gauss-Legendre integrates degree 7 in each of u, v, w; a monomial of total
// degree p in (r, s, t) times the Jacobian has degree p + 2 in u, so the rule is exact for p <= 5.
std::vector<QuadraturePoint3> make_conical() {
  std::vector<QuadraturePoint3> q;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 4; ++k) {
        const double u = kGL4x[i], v = kGL4x[j], w = kGL4x[k];
        const double jac = (1.0 - u) * (1.0 - u) * (1.0 - v);
        q.push_back(
            {u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v), kGL4w[i] * kGL4w[j] * kGL4w[k] * jac});
      }
    }
  }
  return q;
}

// Strang-Fix / Dunavant 6-point rule of degree 4 on the reference triangle (area 1/2).
constexpr std::array<QuadraturePoint2, 6> kTri4{{
    {0.445948490915965, 0.445948490915965, 0.5 * 0.223381589678011},
    {0.108103018168070, 0.445948490915965, 0.5 * 0.223381589678011},
    {0.445948490915965, 0.108103018168070, 0.5 * 0.223381589678011},
    {0.091576213509771, 0.091576213509771, 0.5 * 0.109951743655322},
    {0.816847572980459, 0.091576213509771, 0.5 * 0.109951743655322},
    {0.091576213509771, 0.816847572980459, 0.5 * 0.109951743655322},
}};

}  // namespace

std::span<const QuadraturePoint3> tet_rule_degree2() {
  static const auto rule = make_degree2();
  return rule;
}

std::span<const QuadraturePoint3> tet_rule_degree5() {
  static const auto rule = make_conical();
  return rule;
}

std::span<const QuadraturePoint2> tri_rule_degree4() { return kTri4; }

}  // namespace snapjump::mesh
