#include "fem/fold_check.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "mesh/tet10.hpp"

namespace snapjump::fem::detail {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// The multi-indices (i, j, k, l), i + j + k + l = 3, in one fixed order.
std::array<std::array<int, 4>, 20> tet_indices() {
  std::array<std::array<int, 4>, 20> out{};
  int n = 0;
  for (int i = 3; i >= 0; --i) {
    for (int j = 3 - i; j >= 0; --j) {
      for (int k = 3 - i - j; k >= 0; --k) out[n++] = {i, j, k, 3 - i - j - k};
    }
  }
  return out;
}

// Values to Bernstein coefficients: the inverse of the matrix whose row p holds the basis
// functions at lattice point p.
Eigen::Matrix<double, 20, 20> tet_inverse() {
  const auto idx = tet_indices();
  Eigen::Matrix<double, 20, 20> M;
  for (int p = 0; p < 20; ++p) {
    for (int q = 0; q < 20; ++q) {
      double b = factorial(3);
      for (int c = 0; c < 4; ++c) {
        b *= std::pow(idx[p][c] / 3.0, idx[q][c]) / factorial(idx[q][c]);
      }
      M(p, q) = b;
    }
  }
  return M.fullPivLu().inverse();
}

Eigen::Matrix4d cubic_inverse() {
  Eigen::Matrix4d M;
  for (int p = 0; p < 4; ++p) {
    const double t = p / 3.0;
    for (int k = 0; k < 4; ++k) {
      M(p, k) = factorial(3) / (factorial(k) * factorial(3 - k)) * std::pow(t, k) *
                std::pow(1.0 - t, 3 - k);
    }
  }
  return M.fullPivLu().inverse();
}

}  // namespace

const std::array<std::array<double, 4>, 20>& tet_lattice() {
  static const std::array<std::array<double, 4>, 20> lattice = [] {
    std::array<std::array<double, 4>, 20> out{};
    const auto idx = tet_indices();
    for (int p = 0; p < 20; ++p) {
      for (int c = 0; c < 4; ++c) out[p][c] = idx[p][c] / 3.0;
    }
    return out;
  }();
  return lattice;
}

std::array<double, 20> tet_bernstein(const std::array<double, 20>& values) {
  static const Eigen::Matrix<double, 20, 20> inverse = tet_inverse();
  const Eigen::Map<const Eigen::Matrix<double, 20, 1>> v(values.data());
  std::array<double, 20> out{};
  Eigen::Map<Eigen::Matrix<double, 20, 1>>(out.data()) = inverse * v;
  return out;
}

std::array<double, 16> square_bernstein(const std::array<double, 16>& values) {
  static const Eigen::Matrix4d inverse = cubic_inverse();
  // values(i, j) with i along s: the coefficients are A V A^T with A the 1D inverse.
  Eigen::Matrix4d V;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) V(i, j) = values[4 * i + j];
  }
  const Eigen::Matrix4d B = inverse * V * inverse.transpose();
  std::array<double, 16> out{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out[4 * i + j] = B(i, j);
  }
  return out;
}

}  // namespace snapjump::fem::detail

namespace snapjump::fem {
namespace {

double tet10_det(const std::array<std::array<double, 3>, 10>& x, const std::array<double, 3>& xi) {
  const auto G = mesh::tet10_shape_gradients(xi[0], xi[1], xi[2]);
  double A[3][3] = {};
  for (int a = 0; a < 10; ++a) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) A[i][j] += x[a][i] * G[a][j];
    }
  }
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
         A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

}  // namespace

JacobianCheck check_tet10(const std::array<std::array<double, 3>, 10>& X,
                          const std::array<std::array<double, 3>, 10>& x) {
  const double sign = tet10_det(X, {0.25, 0.25, 0.25}) < 0.0 ? -1.0 : 1.0;
  auto out = check_cubic_on_tetrahedron(
      [&](const std::array<double, 3>& xi) { return sign * tet10_det(x, xi); });
  // From det(dx/dxi) to det F = det(dx/dxi) / det(dX/dxi) at the point found.
  out.min_found /= sign * tet10_det(X, out.at);
  return out;
}

}  // namespace snapjump::fem
