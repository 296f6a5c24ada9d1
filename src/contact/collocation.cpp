#include "contact/collocation.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace snapjump::contact::detail {

namespace {

double cheb_T(int k, double z) {
  z = std::clamp(z, -1.0, 1.0);
  return std::cos(k * std::acos(z));
}

// Antiderivative S_k of T_k (any constant).
double cheb_S(int k, double z) {
  if (k == 0) return z;
  if (k == 1) return 0.5 * z * z;
  return cheb_T(k + 1, z) / (2.0 * (k + 1)) - cheb_T(k - 1, z) / (2.0 * (k - 1));
}

}  // namespace

ChebBasis::ChebBasis(int degree) : p(degree) {
  if (p < 2) throw std::invalid_argument("ChebBasis: degree must be >= 2");
  const int n = p + 1;
  z.resize(n);
  bw.resize(n);
  for (int j = 0; j < n; ++j) {
    z(j) = -std::cos(std::numbers::pi * j / p);
    bw(j) = (j % 2 == 0 ? 1.0 : -1.0) * ((j == 0 || j == p) ? 0.5 : 1.0);
  }
  z(0) = -1.0;
  z(p) = 1.0;
  if (p % 2 == 0) z(p / 2) = 0.0;
  D1 = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    double diag = 0;
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      D1(i, j) = (bw(j) / bw(i)) / (z(i) - z(j));
      diag -= D1(i, j);
    }
    D1(i, i) = diag;
  }
  D2 = D1 * D1;
  Eigen::MatrixXd V(n, n), A(n, n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      V(j, k) = cheb_T(k, z(j));
      A(j, k) = cheb_S(k, z(j)) - cheb_S(k, -1.0);
    }
  Q = A * V.inverse();
  w = Q.row(p).transpose();
}

double ChebBasis::interpolate(const double* f, double zz) const {
  double num = 0, den = 0;
  for (int j = 0; j <= p; ++j) {
    const double d = zz - z(j);
    if (d == 0.0) return f[j];
    const double c = bw(j) / d;
    num += c * f[j];
    den += c;
  }
  return num / den;
}

int Mesh::locate(double xx) const {
  const int K = elements();
  if (xx <= breaks.front()) return 0;
  if (xx >= breaks.back()) return K - 1;
  const auto it = std::upper_bound(breaks.begin(), breaks.end(), xx);
  return std::clamp(static_cast<int>(it - breaks.begin()) - 1, 0, K - 1);
}

int unknowns(const BVP& P) { return kFields * P.mesh.nodes() + P.nparams; }

Eigen::VectorXd element_values(const Mesh& m, const ChebBasis& B, const Eigen::VectorXd& U,
                               int field, int e, int deriv) {
  const int n = m.p + 1;
  const Eigen::VectorXd u = U.segment(index(m, field, e, 0), n);
  const double hs = m.half(e);
  if (deriv == 0) return u;
  if (deriv == 1) return B.D1 * u / hs;
  return B.D2 * u / (hs * hs);
}

void assemble(const BVP& P, const ChebBasis& B, const Eigen::VectorXd& U, Eigen::VectorXd& F,
              Eigen::SparseMatrix<double>* J) {
  const Mesh& m = P.mesh;
  const int K = m.elements();
  const int p = m.p;
  const int n = unknowns(P);
  const int poff = kFields * m.nodes();
  if (static_cast<int>(P.bcs.size()) != 2 * kFields + P.nparams)
    throw std::logic_error("BVP: wrong number of boundary rows");
  F.setZero(n);
  std::vector<Eigen::Triplet<double>> trip;
  if (J) trip.reserve(static_cast<size_t>(n) * (2 * (p + 1) + 4));
  double prm[kMaxParams] = {0, 0};
  for (int k = 0; k < P.nparams; ++k) prm[k] = U(poff + k);

  int row = 0;
  std::vector<int> pde_row_start(K);
  // Collocation rows: for element e, interior node j, equation f at row
  // base + f*K*(p-1) + e*(p-1) + (j-1).
  const int per_field = K * (p - 1);
  for (int e = 0; e < K; ++e) {
    const double hs = m.half(e);
    Eigen::VectorXd v[kFields][3];
    for (int g = 0; g < kFields; ++g)
      for (int d = 0; d < 3; ++d) v[g][d] = element_values(m, B, U, g, e, d);
    for (int j = 1; j < p; ++j) {
      const double x = m.x(B, e, j);
      double u[kFields], du[kFields], d2u[kFields];
      for (int g = 0; g < kFields; ++g) {
        u[g] = v[g][0](j);
        du[g] = v[g][1](j);
        d2u[g] = v[g][2](j);
      }
      PointLin L;
      P.f(e, x, u, du, d2u, prm, L);
      for (int f = 0; f < kFields; ++f) {
        const int r = f * per_field + e * (p - 1) + (j - 1);
        F(r) = L.r[f];
        if (!J) continue;
        for (int g = 0; g < kFields; ++g) {
          const double a = L.A[f][g], b = L.B[f][g] / hs, c = L.C[f][g] / (hs * hs);
          if (a == 0 && b == 0 && c == 0) continue;
          for (int k = 0; k <= p; ++k) {
            double val = b * B.D1(j, k) + c * B.D2(j, k);
            if (k == j) val += a;
            trip.emplace_back(r, index(m, g, e, k), val);
          }
        }
        for (int k = 0; k < P.nparams; ++k)
          if (L.P[f][k] != 0) trip.emplace_back(r, poff + k, L.P[f][k]);
      }
    }
  }
  row = kFields * per_field;
  // C^1 continuity across interfaces.
  for (int f = 0; f < kFields; ++f) {
    for (int e = 0; e + 1 < K; ++e) {
      const int iL = index(m, f, e, p), iR = index(m, f, e + 1, 0);
      F(row) = U(iL) - U(iR);
      if (J) {
        trip.emplace_back(row, iL, 1.0);
        trip.emplace_back(row, iR, -1.0);
      }
      ++row;
      const double hL = m.half(e), hR = m.half(e + 1);
      double val = 0;
      for (int k = 0; k <= p; ++k) {
        val += B.D1(p, k) / hL * U(index(m, f, e, k));
        val -= B.D1(0, k) / hR * U(index(m, f, e + 1, k));
        if (J) {
          trip.emplace_back(row, index(m, f, e, k), B.D1(p, k) / hL);
          trip.emplace_back(row, index(m, f, e + 1, k), -B.D1(0, k) / hR);
        }
      }
      F(row) = val;
      ++row;
    }
  }
  // User rows.
  for (const BCRow& bc : P.bcs) {
    double val = -bc.rhs;
    for (const BCTerm& t : bc.terms) {
      const double hs = m.half(t.elem);
      if (t.deriv == 0) {
        const int i = index(m, t.field, t.elem, t.node);
        val += t.coef * U(i);
        if (J) trip.emplace_back(row, i, t.coef);
      } else {
        const Eigen::MatrixXd& D = (t.deriv == 1) ? B.D1 : B.D2;
        const double sc = (t.deriv == 1) ? 1.0 / hs : 1.0 / (hs * hs);
        for (int k = 0; k <= p; ++k) {
          const int i = index(m, t.field, t.elem, k);
          const double c = t.coef * D(t.node, k) * sc;
          val += c * U(i);
          if (J) trip.emplace_back(row, i, c);
        }
      }
    }
    for (int k = 0; k < P.nparams; ++k) {
      val += bc.pcoef[k] * prm[k];
      if (J && bc.pcoef[k] != 0) trip.emplace_back(row, poff + k, bc.pcoef[k]);
    }
    F(row) = val;
    ++row;
  }
  if (row != n) throw std::logic_error("BVP: row count mismatch");
  if (J) {
    J->resize(n, n);
    J->setFromTriplets(trip.begin(), trip.end());
  }
}

NewtonResult newton_solve(const BVP& P, const ChebBasis& B, Eigen::VectorXd U0, double tol,
                          int max_iter) {
  NewtonResult res;
  res.U = std::move(U0);
  Eigen::VectorXd F, Fn;
  Eigen::SparseMatrix<double> J;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  assemble(P, B, res.U, F, &J);
  double fn = F.lpNorm<Eigen::Infinity>();
  for (int it = 1; it <= max_iter; ++it) {
    res.iterations = it;
    lu.compute(J);
    if (lu.info() != Eigen::Success) break;
    const Eigen::VectorXd dU = lu.solve(-F);
    if (lu.info() != Eigen::Success || !dU.allFinite()) break;
    // Converged: the full Newton correction is at the round-off level.  Take it and stop
    // (a line search would only chase round-off noise in the residual).
    if (dU.lpNorm<Eigen::Infinity>() <= tol * (1.0 + res.U.lpNorm<Eigen::Infinity>())) {
      res.U += dU;
      assemble(P, B, res.U, F, nullptr);
      fn = F.lpNorm<Eigen::Infinity>();
      res.converged = std::isfinite(fn);
      break;
    }
    // Backtracking on the residual norm.
    double lam = 1.0;
    Eigen::VectorXd Un;
    double fnew = 0;
    for (int ls = 0; ls < 30; ++ls) {
      Un = res.U + lam * dU;
      assemble(P, B, Un, Fn, nullptr);
      fnew = Fn.lpNorm<Eigen::Infinity>();
      if (std::isfinite(fnew) && (fnew <= (1.0 - 1e-4 * lam) * fn || fnew < 1e-12)) break;
      lam *= 0.5;
    }
    if (!std::isfinite(fnew)) break;
    const double step = lam * dU.lpNorm<Eigen::Infinity>();
    res.U = Un;
    fn = fnew;
    F = Fn;
    if (step <= tol * (1.0 + res.U.lpNorm<Eigen::Infinity>()) && lam == 1.0) {
      res.converged = true;
      break;
    }
    if (lam < 1e-6) break;  // stalled
    assemble(P, B, res.U, F, &J);
  }
  res.residual_inf = fn;
  return res;
}

double evaluate(const Mesh& m, const ChebBasis& B, const Eigen::VectorXd& U, int field, double x,
                int deriv) {
  const int e = m.locate(x);
  const double xc = std::clamp(x, m.breaks[e], m.breaks[e + 1]);
  const double zz = (xc - m.breaks[e]) / m.half(e) - 1.0;
  const Eigen::VectorXd v = element_values(m, B, U, field, e, deriv);
  return B.interpolate(v.data(), std::clamp(zz, -1.0, 1.0));
}

double integrate(const Mesh& m, const ChebBasis& B, const Eigen::VectorXd& U, int field) {
  double s = 0;
  for (int e = 0; e < m.elements(); ++e)
    s += m.half(e) * B.w.dot(U.segment(index(m, field, e, 0), m.p + 1));
  return s;
}

Eigen::VectorXd integral_to_right(const Mesh& m, const ChebBasis& B, const Eigen::VectorXd& U,
                                  int field) {
  const int n = m.p + 1;
  Eigen::VectorXd out(m.nodes());
  double tail = 0;  // integral from the right end of element e to the mesh end
  for (int e = m.elements() - 1; e >= 0; --e) {
    const Eigen::VectorXd u = U.segment(index(m, field, e, 0), n);
    const Eigen::VectorXd left = m.half(e) * (B.Q * u);  // int from element start
    const double whole = left(m.p);
    for (int j = 0; j < n; ++j) out(e * n + j) = tail + (whole - left(j));
    tail += whole;
  }
  return out;
}

double offgrid_residual(const BVP& P, const ChebBasis& B, const Eigen::VectorXd& U) {
  const Mesh& m = P.mesh;
  const int poff = kFields * m.nodes();
  double prm[kMaxParams] = {0, 0};
  for (int k = 0; k < P.nparams; ++k) prm[k] = U(poff + k);
  double worst = 0;
  for (int e = 0; e < m.elements(); ++e) {
    Eigen::VectorXd v[kFields][3];
    for (int g = 0; g < kFields; ++g)
      for (int d = 0; d < 3; ++d) v[g][d] = element_values(m, B, U, g, e, d);
    for (int j = 0; j < m.p; ++j) {
      const double zz = 0.5 * (B.z(j) + B.z(j + 1));
      const double x = m.breaks[e] + (zz + 1.0) * m.half(e);
      double u[kFields], du[kFields], d2u[kFields];
      for (int g = 0; g < kFields; ++g) {
        u[g] = B.interpolate(v[g][0].data(), zz);
        du[g] = B.interpolate(v[g][1].data(), zz);
        d2u[g] = B.interpolate(v[g][2].data(), zz);
      }
      PointLin L;
      P.f(e, x, u, du, d2u, prm, L);
      for (int f = 0; f < kFields; ++f) worst = std::max(worst, std::abs(L.r[f]));
    }
  }
  return worst;
}

}  // namespace snapjump::contact::detail
