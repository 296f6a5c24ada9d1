// Whether an element is folded through itself anywhere, not only at its quadrature points.
//
// The Jacobian determinant of a quadratic element is a polynomial over the reference element: of
// degree 3 on the ten-node tetrahedron (each column of dx/dxi is linear in xi), of degree 3 in
// each variable on the nine-node quadrilateral (dx/ds is linear in s and quadratic in t, dx/dt the
// reverse). A polynomial written in the Bernstein basis of its cell lies between its smallest and
// largest coefficient, and the coefficients at the cell's corners are its values there. So:
//   - all coefficients positive: the determinant is positive over the whole cell (proven);
//   - a value at one of the points sampled (the cell's degree-3 lattice, 20 points on a
//     tetrahedron, 16 on a square) not positive: the element is folded there (found);
//   - neither: split the cell (a tetrahedron into 8, a square into 4) and look again. Each split
//     brings the coefficients closer to the values (the gap shrinks with the square of the cell's
//     size), so a handful of levels decide every element that is not within rounding of a zero.
// This is the validity test of curved finite elements by Bernstein bounds (Johnen, Remacle and
// Geuzaine, J. Comput. Phys. 2013), applied to the deformed element. A fixed grid of sample points
// could step over a thin crushed corner; the bound cannot.
#pragma once

#include <array>
#include <cstddef>

namespace snapjump::fem {

// The verdict on a polynomial determinant over one reference cell.
struct JacobianCheck {
  bool positive = true;        // proven positive everywhere in the cell
  double min_found = 0.0;      // the smallest value at a point where it was evaluated
  std::array<double, 3> at{};  // that point, in the cell's reference coordinates
  double lower_bound = 0.0;    // a lower bound over the cell (the smallest leaf coefficient)
  int cells = 0;               // how many cells (the element and its pieces) were looked at
};

// Levels of splitting before an undecided cell counts as not positive (a determinant within
// rounding of zero: 8^4 pieces of a tetrahedron, 4^6 of a square).
inline constexpr int kTetFoldDepth = 4;
inline constexpr int kSquareFoldDepth = 6;

// det(xi) cubic over the reference tetrahedron {r, s, t >= 0, r + s + t <= 1}: a callable
// double(const std::array<double, 3>&).
template <typename Det>
JacobianCheck check_cubic_on_tetrahedron(const Det& det);
// det(s, t) of degree 3 in each variable over the square [-1, 1]^2 (at[2] = 0).
template <typename Det>
JacobianCheck check_bicubic_on_square(const Det& det);

// The ten-node tetrahedron (gmsh's node order, mesh/tet10.hpp) with reference positions X and
// current positions x: det(dx/dxi) times the sign of det(dX/dxi) at the centroid, so that a
// positive result means J = det F > 0 everywhere. min_found is J = det F at `at`.
JacobianCheck check_tet10(const std::array<std::array<double, 3>, 10>& X,
                          const std::array<std::array<double, 3>, 10>& x);

namespace detail {
// Bernstein coefficients of a cubic on a tetrahedron from its values at the degree-3 lattice
// points (lattice order: tet_lattice()), and on a square from its 4 x 4 lattice values (index
// 4 * i + j, i along s, j along t).
std::array<double, 20> tet_bernstein(const std::array<double, 20>& values);
std::array<double, 16> square_bernstein(const std::array<double, 16>& values);
// The degree-3 lattice of a tetrahedron as barycentric weights of its four corners.
const std::array<std::array<double, 4>, 20>& tet_lattice();

// One cell's verdict from its Bernstein coefficients b (its lattice values already in out):
// true when it must be split; otherwise its bound is taken into out.
template <std::size_t N>
bool needs_split(const std::array<double, N>& b, bool last_level, JacobianCheck& out) {
  double low = b[0];
  for (double x : b) low = x < low ? x : low;
  if (low > 0.0 || last_level) {
    out.lower_bound = low < out.lower_bound ? low : out.lower_bound;
    if (!(low > 0.0)) out.positive = false;
    return false;
  }
  return true;
}
// Keeps the smallest value seen and where.
inline void note_value(JacobianCheck& out, double value, const std::array<double, 3>& at) {
  if (value < out.min_found) {
    out.min_found = value;
    out.at = at;
  }
}
// A lattice value at or below zero: the fold is found, and the search ends.
inline bool found_fold(JacobianCheck& out) {
  if (out.min_found > 0.0) return false;
  out.positive = false;
  out.lower_bound = out.min_found;
  return true;
}
}  // namespace detail

template <typename Det>
JacobianCheck check_cubic_on_tetrahedron(const Det& det) {
  using P = std::array<double, 3>;
  struct Cell {
    std::array<P, 4> c;
    int depth;
  };
  JacobianCheck out;
  out.min_found = 1e300;
  out.lower_bound = 1e300;
  Cell stack[8 * kTetFoldDepth + 8];
  int top = 0;
  stack[top++] = {{P{0, 0, 0}, P{1, 0, 0}, P{0, 1, 0}, P{0, 0, 1}}, 0};
  while (top > 0) {
    const Cell cell = stack[--top];
    ++out.cells;
    std::array<double, 20> v{};
    const auto& lat = detail::tet_lattice();
    for (int p = 0; p < 20; ++p) {
      P xi{0, 0, 0};
      for (int k = 0; k < 4; ++k) {
        for (int d = 0; d < 3; ++d) xi[d] += lat[p][k] * cell.c[k][d];
      }
      v[p] = det(xi);
      detail::note_value(out, v[p], xi);
    }
    if (detail::found_fold(out)) return out;
    if (!detail::needs_split(detail::tet_bernstein(v), cell.depth == kTetFoldDepth, out)) continue;
    // Eight pieces: four at the corners, four from the inner octahedron (split along the
    // diagonal between the midpoints of edges 01 and 23).
    const auto mid = [&](int i, int j) {
      return P{0.5 * (cell.c[i][0] + cell.c[j][0]), 0.5 * (cell.c[i][1] + cell.c[j][1]),
               0.5 * (cell.c[i][2] + cell.c[j][2])};
    };
    const P m01 = mid(0, 1), m02 = mid(0, 2), m03 = mid(0, 3), m12 = mid(1, 2), m13 = mid(1, 3),
            m23 = mid(2, 3);
    const int d = cell.depth + 1;
    const std::array<std::array<P, 4>, 8> pieces{{{cell.c[0], m01, m02, m03},
                                                  {m01, cell.c[1], m12, m13},
                                                  {m02, m12, cell.c[2], m23},
                                                  {m03, m13, m23, cell.c[3]},
                                                  {m01, m23, m02, m03},
                                                  {m01, m23, m03, m13},
                                                  {m01, m23, m13, m12},
                                                  {m01, m23, m12, m02}}};
    for (const auto& piece : pieces) stack[top++] = {piece, d};
  }
  return out;
}

template <typename Det>
JacobianCheck check_bicubic_on_square(const Det& det) {
  struct Cell {
    double s0, s1, t0, t1;
    int depth;
  };
  JacobianCheck out;
  out.min_found = 1e300;
  out.lower_bound = 1e300;
  Cell stack[4 * kSquareFoldDepth + 4];
  int top = 0;
  stack[top++] = {-1.0, 1.0, -1.0, 1.0, 0};
  while (top > 0) {
    const Cell cell = stack[--top];
    ++out.cells;
    std::array<double, 16> v{};
    for (int i = 0; i < 4; ++i) {
      const double s = cell.s0 + (cell.s1 - cell.s0) * i / 3.0;
      for (int j = 0; j < 4; ++j) {
        const double t = cell.t0 + (cell.t1 - cell.t0) * j / 3.0;
        v[4 * i + j] = det(s, t);
        detail::note_value(out, v[4 * i + j], {s, t, 0.0});
      }
    }
    if (detail::found_fold(out)) return out;
    if (!detail::needs_split(detail::square_bernstein(v), cell.depth == kSquareFoldDepth, out)) {
      continue;
    }
    const double sm = 0.5 * (cell.s0 + cell.s1), tm = 0.5 * (cell.t0 + cell.t1);
    const int d = cell.depth + 1;
    stack[top++] = {cell.s0, sm, cell.t0, tm, d};
    stack[top++] = {sm, cell.s1, cell.t0, tm, d};
    stack[top++] = {cell.s0, sm, tm, cell.t1, d};
    stack[top++] = {sm, cell.s1, tm, cell.t1, d};
  }
  return out;
}

}  // namespace snapjump::fem
