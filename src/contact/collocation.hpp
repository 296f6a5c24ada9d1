// Internal: piecewise Chebyshev (spectral-element) collocation for two coupled
// second-order ODEs with a few unknown scalar parameters, solved by damped
// Newton iteration with Eigen's sparse LU.  Not part of the public API.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <functional>
#include <vector>

namespace snapjump::contact::detail {

// Chebyshev–Lobatto basis of degree p on the reference interval [-1, 1].
struct ChebBasis {
  int p = 0;
  Eigen::VectorXd z;   // p+1 nodes, ascending
  Eigen::MatrixXd D1;  // first-derivative matrix on [-1, 1]
  Eigen::MatrixXd D2;  // second-derivative matrix on [-1, 1]
  Eigen::MatrixXd Q;   // Q(j,k): weight of f_k in  int_{-1}^{z_j} f
  Eigen::VectorXd w;   // Clenshaw–Curtis weights (last row of Q)
  Eigen::VectorXd bw;  // barycentric weights

  explicit ChebBasis(int degree);
  // Value at z in [-1, 1] of the interpolant of the nodal values f[0..p].
  [[nodiscard]] double interpolate(const double* f, double zz) const;
};

// Elements [breaks[e], breaks[e+1]], each carrying p+1 Lobatto nodes.
struct Mesh {
  std::vector<double> breaks;
  int p = 16;
  [[nodiscard]] int elements() const { return static_cast<int>(breaks.size()) - 1; }
  [[nodiscard]] int nodes() const { return elements() * (p + 1); }
  [[nodiscard]] double half(int e) const { return 0.5 * (breaks[e + 1] - breaks[e]); }
  [[nodiscard]] double x(const ChebBasis& b, int e, int j) const {
    return breaks[e] + (b.z(j) + 1.0) * half(e);
  }
  [[nodiscard]] int locate(double xx) const;  // element containing xx (clamped)
};

constexpr int kFields = 2;
constexpr int kMaxParams = 2;

// Linearisation of the two pointwise residuals r[eq] at one collocation point:
// A = dr/du, B = dr/du', C = dr/du'', P = dr/dparam.
struct PointLin {
  double r[kFields] = {0, 0};
  double A[kFields][kFields] = {{0, 0}, {0, 0}};
  double B[kFields][kFields] = {{0, 0}, {0, 0}};
  double C[kFields][kFields] = {{0, 0}, {0, 0}};
  double P[kFields][kMaxParams] = {{0, 0}, {0, 0}};
};

using PointResidual = std::function<void(int elem, double x, const double* u, const double* du,
                                         const double* d2u, const double* prm, PointLin& out)>;

// One linear boundary / side condition:
//   sum_terms coef * (d^deriv u_field / dx^deriv)(node j of element e) + sum_k pcoef[k] prm[k] =
//   rhs
struct BCTerm {
  int field;
  int elem;
  int node;
  int deriv;
  double coef;
};
struct BCRow {
  std::vector<BCTerm> terms;
  double pcoef[kMaxParams] = {0, 0};
  double rhs = 0;
};

// Unknown vector layout: [field 0 nodal values | field 1 nodal values | params].
// Equations: collocation at interior nodes of every element, C^1 continuity of each
// field across element interfaces, then the user rows (must number 4 + nparams).
struct BVP {
  Mesh mesh;
  int nparams = 0;
  PointResidual f;
  std::vector<BCRow> bcs;
};

struct NewtonResult {
  Eigen::VectorXd U;
  bool converged = false;
  int iterations = 0;
  double residual_inf = 0;  // max |discrete residual| at the returned U
};

[[nodiscard]] int unknowns(const BVP& P);
[[nodiscard]] inline int index(const Mesh& m, int field, int e, int j) {
  return field * m.nodes() + e * (m.p + 1) + j;
}

void assemble(const BVP& P, const ChebBasis& B, const Eigen::VectorXd& U, Eigen::VectorXd& F,
              Eigen::SparseMatrix<double>* J);

[[nodiscard]] NewtonResult newton_solve(const BVP& P, const ChebBasis& B, Eigen::VectorXd U0,
                                        double tol, int max_iter);

// Nodal values of d^deriv u_field/dx^deriv on element e (deriv 0, 1 or 2).
[[nodiscard]] Eigen::VectorXd element_values(const Mesh& m, const ChebBasis& B,
                                             const Eigen::VectorXd& U, int field, int e, int deriv);
// d^deriv u_field/dx^deriv of the piecewise interpolant at any x (clamped to the mesh).
[[nodiscard]] double evaluate(const Mesh& m, const ChebBasis& B, const Eigen::VectorXd& U,
                              int field, double x, int deriv = 0);
// Integral of u_field over the whole mesh.
[[nodiscard]] double integrate(const Mesh& m, const ChebBasis& B, const Eigen::VectorXd& U,
                               int field);
// For every node (same layout as one field): integral of u_field from that node to the
// right end of the mesh.
[[nodiscard]] Eigen::VectorXd integral_to_right(const Mesh& m, const ChebBasis& B,
                                                const Eigen::VectorXd& U, int field);
// Max of |pointwise residual| of the continuous equations evaluated on the interpolant
// at points strictly between collocation nodes (midpoints in the reference variable).
[[nodiscard]] double offgrid_residual(const BVP& P, const ChebBasis& B, const Eigen::VectorXd& U);

}  // namespace snapjump::contact::detail
