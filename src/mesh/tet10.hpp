// The 10-node (quadratic) tetrahedron and 6-node triangle: shape functions in gmsh's node
// order, and the quadrature rules the body uses.
//
// Tetrahedron reference coordinates (r, s, t), barycentrics L0 = 1 - r - s - t, L1 = r, L2 = s,
// L3 = t. Nodes 0-3 are the corners; 4..9 the edge midpoints of edges
// (0,1), (1,2), (0,2), (0,3), (2,3), (1,3) (gmsh's MSH ordering for element type 11).
// Triangle (r, s): corners 0-2, then edges (0,1), (1,2), (0,2) (gmsh type 9).
#pragma once

#include <array>
#include <span>

namespace snapjump::mesh {

inline constexpr int kTetNodes = 10;
inline constexpr int kTriNodes = 6;
inline constexpr std::array<std::array<int, 2>, 6> kTetEdges{
    {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}}};
inline constexpr std::array<std::array<int, 2>, 3> kTriEdges{{{0, 1}, {1, 2}, {0, 2}}};

// N_a at (r, s, t).
std::array<double, kTetNodes> tet10_shape(double r, double s, double t);
// dN_a/d(r, s, t) at (r, s, t).
std::array<std::array<double, 3>, kTetNodes> tet10_shape_gradients(double r, double s, double t);

std::array<double, kTriNodes> tri6_shape(double r, double s);
std::array<std::array<double, 2>, kTriNodes> tri6_shape_gradients(double r, double s);

struct QuadraturePoint3 {
  double r, s, t, weight;  // weights sum to the reference volume 1/6
};
struct QuadraturePoint2 {
  double r, s, weight;  // weights sum to the reference area 1/2
};

// 4-point rule, exact for polynomials of degree 2: integrates the small-strain stiffness of the
// tet10 (gradients are linear, so B^T D B is quadratic) exactly on straight-sided elements.
std::span<const QuadraturePoint3> tet_rule_degree2();
// Conical (collapsed Gauss-Legendre) product rule with 4^3 points and positive weights, exact
// for polynomials of degree 5: used once for the lumped masses (integrals of N_a^2, degree 4).
std::span<const QuadraturePoint3> tet_rule_degree5();
// 6-point rule, exact for degree 4: the pressure load and the enclosed volume of curved 6-node
// faces (integrands x . (dx/dr x dx/ds) and N_a (dx/dr x dx/ds) are of degree 4).
std::span<const QuadraturePoint2> tri_rule_degree4();

}  // namespace snapjump::mesh
