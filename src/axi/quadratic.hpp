// The 1D quadratic Lagrange functions and Gauss rules the axisymmetric elements are built from.
#pragma once

#include <array>
#include <cmath>
#include <vector>

namespace snapjump::axi {

// On [-1, 1] at the nodes -1, 0, 1, and their derivatives.
inline std::array<double, 3> lagrange(double s) {
  return {0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)};
}
inline std::array<double, 3> lagrange_d(double s) { return {s - 0.5, -2.0 * s, s + 0.5}; }

struct Gauss {
  std::vector<double> x, w;
};
// Gauss-Legendre with n = 2 or 3 points on [-1, 1].
inline Gauss gauss(int n) {
  if (n == 2) {
    const double a = 1.0 / std::sqrt(3.0);
    return {{-a, a}, {1.0, 1.0}};
  }
  const double a = std::sqrt(0.6);
  return {{-a, 0.0, a}, {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0}};
}

}  // namespace snapjump::axi
