#include "contact/contact.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>

#include "contact/collocation.hpp"

namespace snapjump::contact {

namespace {

using detail::BCRow;
using detail::BCTerm;
using detail::BVP;
using detail::ChebBasis;
using detail::Mesh;
using detail::PointLin;
using Eigen::VectorXd;

constexpr double kPi = std::numbers::pi;
constexpr double kGapTolerance = -1e-9;
constexpr double kApexGapTolerance = 1e-6;
constexpr double kPaperN2 = 20.83;

// ---------------------------------------------------------------------------------------
// The shell equations (t = field 0, s = field 1, N = parameter 0), each multiplied by
// x^2/(1+x^2) so that the rows stay O(1) near x = 0 and at large x.  Elements with index
// >= first_loaded carry the line-load term N/(2 pi x).
detail::PointResidual shell_residual(int first_loaded) {
  return [first_loaded](int e, double x, const double* u, const double* du, const double* d2u,
                        const double* prm, PointLin& L) {
    const double w = x * x / (1.0 + x * x);
    const double t = u[0], s = u[1];
    const double H = (e >= first_loaded) ? 1.0 : 0.0;
    const double N = prm[0];
    const double ix = 1.0 / x;
    L.r[0] = w * (d2u[0] + du[0] * ix - t * ix * ix - s * (1.0 + t * ix) - H * N * ix / (2 * kPi));
    L.A[0][0] = w * (-ix * ix - s * ix);
    L.A[0][1] = -w * (1.0 + t * ix);
    L.B[0][0] = w * ix;
    L.C[0][0] = w;
    L.P[0][0] = -w * H * ix / (2 * kPi);
    L.r[1] = w * (d2u[1] + du[1] * ix - s * ix * ix + t + 0.5 * t * t * ix);
    L.A[1][0] = w * (1.0 + t * ix);
    L.A[1][1] = -w * ix * ix;
    L.B[1][1] = w * ix;
    L.C[1][1] = w;
  };
}

BCRow bc_point(int field, int elem, int node, int deriv, double rhs) {
  BCRow r;
  r.terms.push_back(BCTerm{field, elem, node, deriv, 1.0});
  r.rhs = rhs;
  return r;
}

// Far-field rows at the right end X: t(X) = 0 and s(X) + N/(2 pi X) = 0.
void add_far_field(BVP& P) {
  const int K = P.mesh.elements();
  const double X = P.mesh.breaks.back();
  P.bcs.push_back(bc_point(0, K - 1, P.mesh.p, 0, 0.0));
  BCRow r = bc_point(1, K - 1, P.mesh.p, 0, 0.0);
  r.pcoef[0] = 1.0 / (2 * kPi * X);
  P.bcs.push_back(r);
}

// Breaks from x0 to x0 + L: h0, 2 h0, 4 h0, ... below 2, then equal steps <= hmax.
std::vector<double> graded_breaks(double x0, double L, double h0, double hmax) {
  std::vector<double> y{0.0};
  double yy = h0;
  while (yy < 2.0 - 1e-12 && yy < L) {
    y.push_back(yy);
    yy *= 2.0;
  }
  if (y.back() < 2.0 && L > 2.0) y.push_back(2.0);
  const double rest = L - y.back();
  if (rest > 1e-12) {
    const int n = std::max(1, static_cast<int>(std::ceil(rest / hmax - 1e-9)));
    const double y0 = y.back();
    for (int k = 1; k <= n; ++k) y.push_back(y0 + rest * k / n);
  }
  for (double& v : y) v += x0;
  return y;
}

// Gap x^2/2 + w(x) - e_hat at all nodes, w = -int_x^X t.
VectorXd gaps(const Mesh& m, const ChebBasis& B, const VectorXd& U, double e_hat) {
  const VectorXd w = -detail::integral_to_right(m, B, U, 0);
  VectorXd g(m.nodes());
  for (int e = 0; e < m.elements(); ++e)
    for (int j = 0; j <= m.p; ++j) {
      const double x = m.x(B, e, j);
      g(e * (m.p + 1) + j) = 0.5 * x * x + w(e * (m.p + 1) + j) - e_hat;
    }
  return g;
}

// Illinois (modified regula falsi) for g(x) = 0 on [lo, hi] with g(lo) g(hi) <= 0.
template <class G>
double refine_root(G&& g, double lo, double glo, double hi, double ghi) {
  int side = 0;
  for (int it = 0; it < 100; ++it) {
    const double x = (lo * ghi - hi * glo) / (ghi - glo);
    const double gx = g(x);
    if (gx == 0.0) return x;
    if ((gx > 0) == (ghi > 0)) {
      hi = x;
      ghi = gx;
      if (side == -1) glo *= 0.5;
      side = -1;
    } else {
      lo = x;
      glo = gx;
      if (side == +1) ghi *= 0.5;
      side = +1;
    }
    if (std::abs(hi - lo) < 1e-12 * (1.0 + std::abs(x)) || std::abs(gx) < 1e-13) return x;
  }
  return 0.5 * (lo + hi);
}

// Parabola through (x[k], y[k]), k = 0..2: abscissa of its vertex (clamped to [x0, x2]) and
// its value anywhere.
double parabola_vertex(const double x[3], const double y[3]) {
  const double d01 = (y[1] - y[0]) / (x[1] - x[0]);
  const double d12 = (y[2] - y[1]) / (x[2] - x[1]);
  const double c2 = (d12 - d01) / (x[2] - x[0]);
  if (c2 <= 0) return x[1];
  // y = y0 + d01 (x - x0) + c2 (x - x0)(x - x1)
  return std::clamp(0.5 * (x[0] + x[1]) - d01 / (2 * c2), x[0], x[2]);
}
double parabola_value(const double x[3], const double y[3], double xs) {
  const double d01 = (y[1] - y[0]) / (x[1] - x[0]);
  const double d12 = (y[2] - y[1]) / (x[2] - x[1]);
  const double c2 = (d12 - d01) / (x[2] - x[0]);
  return y[0] + d01 * (xs - x[0]) + c2 * (xs - x[0]) * (xs - x[1]);
}

// ---------------------------------------------------------------------------------------
// Disk contact: outer problem on [a, a + L], parameters N (0) and c1 (1).
struct DiskState {
  Mesh mesh;
  VectorXd U;
  DiskPoint pt{0, 0, 0, 0};
};

BVP disk_bvp(const SolverOptions& o, double a) {
  BVP P;
  P.mesh.p = o.resolution;
  P.mesh.breaks = graded_breaks(a, o.domain_length, std::min(0.5, 0.5 * a), o.element_length);
  P.nparams = 2;
  P.f = shell_residual(0);
  P.bcs.push_back(bc_point(0, 0, 0, 0, -a));         // t(a) = -a
  P.bcs.push_back(bc_point(0, 0, 0, 1, -1.0));       // t'(a) = -1
  BCRow r = bc_point(1, 0, 0, 0, a * a * a / 16.0);  // s(a) - c1 a = a^3/16
  r.pcoef[1] = -a;
  P.bcs.push_back(r);
  r = bc_point(1, 0, 0, 1, 3.0 * a * a / 16.0);  // s'(a) - c1 = 3 a^2/16
  r.pcoef[1] = -1.0;
  P.bcs.push_back(r);
  add_far_field(P);
  return P;
}

VectorXd disk_guess(const BVP& P, const ChebBasis& B, double a, const DiskState* prev) {
  const Mesh& m = P.mesh;
  VectorXd U(detail::unknowns(P));
  const int n = m.nodes();
  const double N0 = prev ? prev->pt.N : 1.0;
  const double c10 = prev ? prev->pt.c1 : 0.0;
  for (int e = 0; e < m.elements(); ++e)
    for (int j = 0; j <= m.p; ++j) {
      const double x = m.x(B, e, j);
      const int i = e * (m.p + 1) + j;
      double t = 0, s = 0;
      if (!prev) {
        t = -a * std::exp(-(x - a));
        s = -N0 / (2 * kPi * x) * (1.0 - std::exp(-(x - a)));
      } else if (x < prev->pt.a) {
        t = -x;
        s = x * x * x / 16.0 + c10 * x;
      } else if (x > prev->mesh.breaks.back()) {
        t = 0;
        s = -N0 / (2 * kPi * x);
      } else {
        t = detail::evaluate(prev->mesh, B, prev->U, 0, x);
        s = detail::evaluate(prev->mesh, B, prev->U, 1, x);
      }
      U(i) = t;
      U(n + i) = s;
    }
  U(2 * n) = N0;
  U(2 * n + 1) = c10;
  return U;
}

DiskState solve_disk(const SolverOptions& o, const ChebBasis& B, double a, const DiskState* prev) {
  const BVP P = disk_bvp(o, a);
  const auto res =
      detail::newton_solve(P, B, disk_guess(P, B, a, prev), o.newton_tol, o.max_newton_iterations);
  if (!res.converged)
    throw std::runtime_error("contact: disk solve did not converge at a = " + std::to_string(a));
  DiskState st;
  st.mesh = P.mesh;
  st.U = res.U;
  const int n = P.mesh.nodes();
  st.pt.a = a;
  st.pt.N = res.U(2 * n);
  st.pt.c1 = res.U(2 * n + 1);
  st.pt.e_hat = 0.5 * a * a - detail::integrate(P.mesh, B, res.U, 0);
  st.pt.residual = res.residual_inf;
  st.pt.offgrid_residual = detail::offgrid_residual(P, B, res.U);
  st.pt.min_gap = gaps(P.mesh, B, res.U, st.pt.e_hat).minCoeff();
  st.pt.plate_function = clamped_plate_function(a, st.pt.c1);
  return st;
}

// Disk branch with full states, up to the first zero of the clamped-plate function (located to
// round-off) or a_stop.
std::vector<DiskState> disk_states(const SolverOptions& o, const ChebBasis& B, double a_stop) {
  std::vector<DiskState> out;
  double a = o.a_min;
  while (true) {
    const bool last = a >= a_stop;
    if (last) a = a_stop;
    DiskState st = solve_disk(o, B, a, out.empty() ? nullptr : &out.back());
    if (!out.empty() && out.back().pt.plate_function > 0 && st.pt.plate_function <= 0) {
      const DiskState prev = out.back();
      DiskState best = st;
      auto g = [&](double aa) {
        best = solve_disk(o, B, aa, &prev);
        return best.pt.plate_function;
      };
      const double root =
          refine_root(g, prev.pt.a, prev.pt.plate_function, a, st.pt.plate_function);
      if (best.pt.a != root) best = solve_disk(o, B, root, &prev);
      out.push_back(std::move(best));
      break;
    }
    out.push_back(std::move(st));
    if (last) break;
    if (a > 50.0) throw std::runtime_error("contact: disk branch did not buckle by a = 50");
    a = (a < 0.5 - 1e-12) ? std::min(0.5, a * o.small_a_ratio) : a + o.da;
  }
  return out;
}

// Crossing of the disk branch with N = law(e_hat) (first sign change of N - law from below),
// refined to round-off.  Returns false if there is none.
bool disk_crossing(const SolverOptions& o, const ChebBasis& B, const std::vector<DiskState>& br,
                   const std::function<double(double)>& law, DiskState& at) {
  for (size_t i = 1; i < br.size(); ++i) {
    const double g0 = br[i - 1].pt.N - law(br[i - 1].pt.e_hat);
    const double g1 = br[i].pt.N - law(br[i].pt.e_hat);
    if (g0 < 0 && g1 >= 0) {
      const DiskState& prev = br[i - 1];
      DiskState best = br[i];
      auto g = [&](double aa) {
        best = solve_disk(o, B, aa, &prev);
        return best.pt.N - law(best.pt.e_hat);
      };
      const double root = refine_root(g, prev.pt.a, g0, br[i].pt.a, g1);
      if (best.pt.a != root) best = solve_disk(o, B, root, &prev);
      at = std::move(best);
      return true;
    }
  }
  return false;
}

// ---------------------------------------------------------------------------------------
// Ridge boundary layer: phi = field 0, sigma = field 1, no parameters.
struct RidgeState {
  Mesh mesh;
  VectorXd U;
  RidgeSolution sol;
};

RidgeState ridge_state(const SolverOptions& o, const ChebBasis& B) {
  BVP P;
  P.mesh.p = o.resolution;
  P.mesh.breaks = graded_breaks(0.0, o.domain_length, 0.5, o.element_length);
  P.nparams = 0;
  P.f = [](int, double, const double* u, const double*, const double* d2u, const double*,
           PointLin& L) {
    L.r[0] = d2u[0] - u[1] * u[0];
    L.A[0][0] = -u[1];
    L.A[0][1] = -u[0];
    L.C[0][0] = 1.0;
    L.r[1] = d2u[1] - 0.5 * (1.0 - u[0] * u[0]);
    L.A[1][0] = u[0];
    L.C[1][1] = 1.0;
  };
  const int K = P.mesh.elements();
  P.bcs.push_back(bc_point(0, 0, 0, 0, 0.0));             // phi(0) = 0
  P.bcs.push_back(bc_point(1, 0, 0, 1, 0.0));             // sigma'(0) = 0
  P.bcs.push_back(bc_point(0, K - 1, P.mesh.p, 0, 1.0));  // phi(X) = 1
  P.bcs.push_back(bc_point(1, K - 1, P.mesh.p, 0, 0.0));  // sigma(X) = 0
  const int n = P.mesh.nodes();
  VectorXd U0(2 * n);
  for (int e = 0; e < K; ++e)
    for (int j = 0; j <= P.mesh.p; ++j) {
      const double x = P.mesh.x(B, e, j);
      U0(e * (P.mesh.p + 1) + j) = std::tanh(x);
      U0(n + e * (P.mesh.p + 1) + j) = -0.5 / std::cosh(x);
    }
  const auto res = detail::newton_solve(P, B, U0, o.newton_tol, o.max_newton_iterations);
  if (!res.converged) throw std::runtime_error("contact: ridge solve did not converge");
  RidgeState st;
  st.mesh = P.mesh;
  st.U = res.U;
  double half = 0;
  for (int e = 0; e < K; ++e) {
    const VectorXd dphi = detail::element_values(P.mesh, B, res.U, 0, e, 1);
    const VectorXd dsig = detail::element_values(P.mesh, B, res.U, 1, e, 1);
    half += P.mesh.half(e) * B.w.dot((dphi.array().square() + dsig.array().square()).matrix());
  }
  st.sol.I = 2.0 * half;
  st.sol.n2 = 3.0 * kPi * st.sol.I;
  st.sol.phi_prime0 = detail::evaluate(P.mesh, B, res.U, 0, 0.0, 1);
  st.sol.sigma0 = res.U(n);
  st.sol.hamiltonian0 = st.sol.phi_prime0 * st.sol.phi_prime0 + st.sol.sigma0;
  st.sol.residual = res.residual_inf;
  st.sol.offgrid_residual = detail::offgrid_residual(P, B, res.U);
  for (int e = 0; e < K; ++e)
    for (int j = 0; j <= P.mesh.p; ++j) {
      if (e > 0 && j == 0) continue;
      st.sol.xi.push_back(P.mesh.x(B, e, j));
      st.sol.phi.push_back(res.U(e * (P.mesh.p + 1) + j));
      st.sol.sigma.push_back(res.U(n + e * (P.mesh.p + 1) + j));
    }
  return st;
}

// ---------------------------------------------------------------------------------------
// Ring contact: inner [0, a] (no load) and outer [a, a + L] (line load), parameter N.
struct RingState {
  Mesh mesh;
  VectorXd U;
  RingPoint pt{0, 0, 0};
};

BVP ring_bvp(const SolverOptions& o, double a) {
  BVP P;
  P.mesh.p = o.resolution;
  // Inner: coarse elements away from the ridge, elements of length <= 1 over the last 4 l.
  std::vector<double> br{0.0};
  const double b = std::max(0.0, a - 4.0);
  if (b > 1e-12) {
    const int n = std::max(1, static_cast<int>(std::ceil(b / o.element_length - 1e-9)));
    for (int k = 1; k <= n; ++k) br.push_back(b * k / n);
  }
  const double base = br.back();
  const double rest = a - base;
  const int nr = std::max(1, static_cast<int>(std::ceil(rest - 1e-9)));
  for (int k = 1; k <= nr; ++k) br.push_back(base + rest * k / nr);
  const int k_in = static_cast<int>(br.size()) - 1;
  const std::vector<double> outer = graded_breaks(a, o.domain_length, 0.5, o.element_length);
  br.insert(br.end(), outer.begin() + 1, outer.end());
  P.mesh.breaks = br;
  P.nparams = 1;
  P.f = shell_residual(k_in);
  P.bcs.push_back(bc_point(0, 0, 0, 0, 0.0));               // t(0) = 0
  P.bcs.push_back(bc_point(1, 0, 0, 0, 0.0));               // s(0) = 0
  P.bcs.push_back(bc_point(0, k_in - 1, P.mesh.p, 0, -a));  // t(a) = -a (tangent to the plane)
  add_far_field(P);
  return P;
}

using GuessFn = std::function<void(double x, double& t, double& s)>;

bool solve_ring(const SolverOptions& o, const ChebBasis& B, double a, const GuessFn& guess,
                double N0, RingState& out) {
  const BVP P = ring_bvp(o, a);
  const int n = P.mesh.nodes();
  VectorXd U0(2 * n + 1);
  for (int e = 0; e < P.mesh.elements(); ++e)
    for (int j = 0; j <= P.mesh.p; ++j) {
      double t = 0, s = 0;
      guess(P.mesh.x(B, e, j), t, s);
      U0(e * (P.mesh.p + 1) + j) = t;
      U0(n + e * (P.mesh.p + 1) + j) = s;
    }
  U0(2 * n) = N0;
  const auto res = detail::newton_solve(P, B, U0, o.newton_tol, o.max_newton_iterations);
  if (!res.converged) return false;
  out.mesh = P.mesh;
  out.U = res.U;
  out.pt.a = a;
  out.pt.N = res.U(2 * n);
  const VectorXd w = -detail::integral_to_right(P.mesh, B, res.U, 0);
  // The ring is the left end of the first outer element.
  int k_in = 0;
  while (P.mesh.breaks[k_in] < a - 1e-14 * (1.0 + a)) ++k_in;
  out.pt.e_hat = 0.5 * a * a + w(k_in * (P.mesh.p + 1));
  out.pt.residual = res.residual_inf;
  out.pt.offgrid_residual = detail::offgrid_residual(P, B, res.U);
  out.pt.min_gap = gaps(P.mesh, B, res.U, out.pt.e_hat).minCoeff();
  out.pt.apex_gap = w(0) - out.pt.e_hat;
  return std::isfinite(out.pt.N);
}

bool acceptable_ring(const RingState& st) {
  return st.pt.N > 0 && st.pt.min_gap >= kGapTolerance && st.pt.apex_gap > kApexGapTolerance;
}

// Ring state at radius a from the boundary-layer solution: total slope x + t = x phi_odd(x - a),
// s = a sigma(|x - a|) plus a smooth stand-in for the membrane tail -N/(2 pi x).
bool ring_from_ridge(const SolverOptions& o, const ChebBasis& B, const RidgeState& R, double a,
                     RingState& out) {
  const double N0 = R.sol.n2 * a;
  auto guess = [&](double x, double& t, double& s) {
    const double xi = x - a;
    const double ph = detail::evaluate(R.mesh, B, R.U, 0, std::abs(xi));
    const double sg = detail::evaluate(R.mesh, B, R.U, 1, std::abs(xi));
    t = x * (xi < 0 ? -ph : ph) - x;
    s = a * sg - N0 / (2 * kPi) * x / std::pow(std::max(x, a), 2);
  };
  return solve_ring(o, B, a, guess, N0, out) && acceptable_ring(out);
}

// Ring state at radius an from a nearby ring state: the previous solution stretched so that the
// ridge stays at the ring (t scaled likewise).
bool ring_continue(const SolverOptions& o, const ChebBasis& B, const RingState& prev, double an,
                   RingState& out) {
  auto guess = [&](double x, double& t, double& s) {
    if (x > prev.mesh.breaks.back()) {
      t = 0;
      s = -prev.pt.N / (2 * kPi * x);
      return;
    }
    const double xs = std::clamp(x * prev.pt.a / an, 0.0, prev.mesh.breaks.back());
    t = detail::evaluate(prev.mesh, B, prev.U, 0, xs) * an / prev.pt.a;
    s = detail::evaluate(prev.mesh, B, prev.U, 1, xs);
  };
  return solve_ring(o, B, an, guess, prev.pt.N, out) && acceptable_ring(out);
}

// Minimum over a of key(ring state) near the continuation point ring[i]: successive parabolas
// through solves at a* - h, a*, a* + h with h = 0.05, 0.01, 0.002.  Fills the minimiser, the
// minimum and other(state) there.  Falls back to the discrete minimum if a solve fails.
template <class Key, class Other>
void ring_minimum(const SolverOptions& o, const ChebBasis& B, const std::vector<RingState>& ring,
                  size_t i, Key key, Other other, double& a_star, double& k_star, double& o_star) {
  a_star = ring[i].pt.a;
  k_star = key(ring[i].pt);
  o_star = other(ring[i].pt);
  if (i == 0 || i + 1 >= ring.size()) return;
  RingState centre = ring[i];
  for (const double h : {0.05, 0.01, 0.002}) {
    RingState lo, hi;
    if (!ring_continue(o, B, centre, a_star - h, lo) ||
        !ring_continue(o, B, centre, a_star + h, hi))
      return;
    const double xa[3] = {a_star - h, a_star, a_star + h};
    const double ya[3] = {key(lo.pt), key(centre.pt), key(hi.pt)};
    const double za[3] = {other(lo.pt), other(centre.pt), other(hi.pt)};
    const double an = parabola_vertex(xa, ya);
    RingState nc;
    if (!ring_continue(o, B, centre, an, nc)) {
      a_star = an;
      k_star = parabola_value(xa, ya, an);
      o_star = parabola_value(xa, za, an);
      return;
    }
    centre = nc;
    a_star = an;
    k_star = key(nc.pt);
    o_star = other(nc.pt);
  }
}

std::vector<RingState> ring_states(const SolverOptions& o, const ChebBasis& B, const RidgeState& R,
                                   double a_min) {
  std::vector<RingState> out;
  RingState st;
  if (!ring_from_ridge(o, B, R, o.ring_a_max, st))
    throw std::runtime_error("contact: ring solve from the ridge guess did not converge at a = " +
                             std::to_string(o.ring_a_max));
  out.push_back(std::move(st));
  double step = o.ring_da;
  while (step > 1e-3 * o.ring_da) {
    const double an = out.back().pt.a - step;
    if (an < a_min - 1e-12) break;
    RingState nxt;
    if (ring_continue(o, B, out.back(), an, nxt)) {
      out.push_back(std::move(nxt));
    } else {
      step *= 0.5;
    }
  }
  std::reverse(out.begin(), out.end());
  return out;
}

// Least-squares polynomial fit of y(x); returns the value at x = 0.
double fit_intercept(const std::vector<double>& x, const std::vector<double>& y, int degree) {
  const int m = static_cast<int>(x.size());
  Eigen::MatrixXd A(m, degree + 1);
  VectorXd b(m);
  for (int i = 0; i < m; ++i) {
    for (int k = 0; k <= degree; ++k) A(i, k) = std::pow(x[i], k);
    b(i) = y[i];
  }
  return A.colPivHouseholderQr().solve(b)(0);
}

// The worst residuals over the solutions used (Constants::max_residual, max_offgrid_residual).
struct WorstResiduals {
  double residual = 0, offgrid = 0;
  void add(double r, double off) {
    residual = std::max(residual, r);
    offgrid = std::max(offgrid, off);
  }
};

// The ridge boundary layer's constants: I, n2 and the mirror-buckling energy prefactors.
void ridge_constants(const RidgeState& R, Constants& c, WorstResiduals& worst) {
  c.ridge_I = R.sol.I;
  c.n2 = R.sol.n2;
  c.mirror_energy_prefactor = kPi * c.ridge_I / std::pow(12.0, 0.75);
  c.mirror_energy_prefactor_cap_height = std::pow(2.0, 1.5) * c.mirror_energy_prefactor;
  worst.add(R.sol.residual, R.sol.offgrid_residual);
}

// The disk branch's end (N+), its gaps and the least slope dN/de along it (the inflection).
void disk_end_constants(const std::vector<DiskState>& disk, Constants& c, WorstResiduals& worst) {
  const DiskPoint& end = disk.back().pt;
  c.N_plus = end.N;
  c.a_plus = end.a;
  c.e_hat_plus = end.e_hat;
  c.c1_plus = end.c1;
  c.plate_eigenvalue_at_plus = clamped_plate_top_eigenvalue(end.a, end.c1);
  c.e_hat_ring_law_at_plus = std::pow(c.N_plus / c.n2, 2);
  c.min_disk_gap = 1e300;
  for (const auto& s : disk) {
    worst.add(s.pt.residual, s.pt.offgrid_residual);
    c.min_disk_gap = std::min(c.min_disk_gap, s.pt.min_gap);
  }
  c.disk_min_slope = 1e300;
  for (size_t i = 1; i < disk.size(); ++i) {
    const double de = disk[i].pt.e_hat - disk[i - 1].pt.e_hat;
    const double slope = (disk[i].pt.N - disk[i - 1].pt.N) / de;
    if (slope < c.disk_min_slope) {
      c.disk_min_slope = slope;
      c.disk_e_hat_inflection = 0.5 * (disk[i].pt.e_hat + disk[i - 1].pt.e_hat);
    }
  }
}

// The Reissner slope from the small-load end of the disk branch.
void reissner_constants(const std::vector<DiskState>& disk, Constants& c) {
  std::vector<double> ex, ry;
  for (const auto& s : disk)
    if (s.pt.e_hat <= 0.3) {
      ex.push_back(s.pt.e_hat);
      ry.push_back(s.pt.N / s.pt.e_hat);
    }
  if (ex.size() >= 8) {
    const double q2 = fit_intercept(ex, ry, 2);
    const double q3 = fit_intercept(ex, ry, 3);
    c.reissner_slope = q3;
    c.reissner_fit_spread = std::abs(q3 - q2);
  }
}

// The lower bounds: where the disk branch meets the ring law N = n2 sqrt(e_hat) (the paper's
// construction, with the computed n2 and with the paper's), and N = n2 sqrt(2 e_hat) (the
// reference note's geometry).
void lower_bound_constants(const SolverOptions& o, const ChebBasis& B,
                           const std::vector<DiskState>& disk, Constants& c) {
  DiskState cross;
  const double n2 = c.n2;
  if (disk_crossing(
          o, B, disk, [n2](double e) { return n2 * std::sqrt(e); }, cross)) {
    c.N_minus = cross.pt.N;
    c.a_minus = cross.pt.a;
    c.e_hat_minus = cross.pt.e_hat;
    c.c1_minus = cross.pt.c1;
    c.ring_radius_minus = std::sqrt(cross.pt.e_hat);
  }
  if (disk_crossing(
          o, B, disk, [](double e) { return kPaperN2 * std::sqrt(e); }, cross)) {
    c.N_minus_paper_n2 = cross.pt.N;
    c.a_minus_paper_n2 = cross.pt.a;
    c.e_hat_minus_paper_n2 = cross.pt.e_hat;
  }
  const auto note_law = [n2](double e) { return n2 * std::sqrt(2.0 * e); };
  c.max_disk_over_note_law = 0;
  for (const auto& s : disk)
    c.max_disk_over_note_law = std::max(c.max_disk_over_note_law, s.pt.N / note_law(s.pt.e_hat));
  if (disk_crossing(o, B, disk, note_law, cross)) {
    c.N_minus_note = cross.pt.N;
    c.a_minus_note = cross.pt.a;
    c.e_hat_minus_note = cross.pt.e_hat;
  }
}

// The computed ring branch, down to its end on the disk branch: its gaps, its end and its
// minima in N and in e_hat.
void ring_constants(const SolverOptions& o, const ChebBasis& B, const RidgeState& R, Constants& c,
                    WorstResiduals& worst) {
  const std::vector<RingState> ring = ring_states(o, B, R, 0.0);
  c.min_ring_gap = 1e300;
  c.min_ring_apex_gap = 1e300;
  for (const auto& s : ring) {
    worst.add(s.pt.residual, s.pt.offgrid_residual);
    c.min_ring_gap = std::min(c.min_ring_gap, s.pt.min_gap);
    c.min_ring_apex_gap = std::min(c.min_ring_apex_gap, s.pt.apex_gap);
  }
  c.ring_a_end = ring.front().pt.a;
  c.ring_N_end = ring.front().pt.N;
  c.ring_e_hat_end = ring.front().pt.e_hat;
  size_t iN = 0, iE = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    if (ring[i].pt.N < ring[iN].pt.N) iN = i;
    if (ring[i].pt.e_hat < ring[iE].pt.e_hat) iE = i;
  }
  const auto getN = [](const RingPoint& p) { return p.N; };
  const auto getE = [](const RingPoint& p) { return p.e_hat; };
  ring_minimum(o, B, ring, iN, getN, getE, c.ring_a_at_N_min, c.ring_N_min, c.ring_e_hat_at_N_min);
  ring_minimum(o, B, ring, iE, getE, getN, c.ring_a_at_e_hat_min, c.ring_e_hat_min,
               c.ring_N_at_e_hat_min);
}

// n2 from large rings of the full problem: N/a = n2 + c1/a + c2/a^2 + c3/a^3, extrapolated to
// a -> infinity (Lagrange through the four points in u = 1/a).
void large_ring_n2(const SolverOptions& o, const ChebBasis& B, const RidgeState& R, Constants& c,
                   WorstResiduals& worst) {
  std::vector<double> u, y;
  for (const double a : {20.0, 30.0, 40.0, 60.0}) {
    RingState big;
    if (!ring_from_ridge(o, B, R, a, big))
      throw std::runtime_error("contact: large ring solve failed at a = " + std::to_string(a));
    worst.add(big.pt.residual, big.pt.offgrid_residual);
    c.min_ring_gap = std::min(c.min_ring_gap, big.pt.min_gap);
    u.push_back(1.0 / a);
    y.push_back(big.pt.N / a);
  }
  double v = 0;
  for (size_t i = 0; i < u.size(); ++i) {
    double wgt = 1;
    for (size_t j = 0; j < u.size(); ++j)
      if (j != i) wgt *= (0.0 - u[j]) / (u[i] - u[j]);
    v += wgt * y[i];
  }
  c.n2_ring_extrapolated = v;
}

Constants compute_core(const SolverOptions& o) {
  const ChebBasis B(o.resolution);
  Constants c;
  WorstResiduals worst;
  const RidgeState R = ridge_state(o, B);
  ridge_constants(R, c, worst);
  const std::vector<DiskState> disk = disk_states(o, B, std::numeric_limits<double>::infinity());
  disk_end_constants(disk, c, worst);
  reissner_constants(disk, c);
  lower_bound_constants(o, B, disk, c);
  ring_constants(o, B, R, c, worst);
  large_ring_n2(o, B, R, c, worst);
  c.max_residual = worst.residual;
  c.max_offgrid_residual = worst.offgrid;
  return c;
}

}  // namespace

// ---------------------------------------------------------------------------------------

double clamped_plate_function(double a, double c1) {
  // theta = sum_k b_k x^(2k+1) with b_0 = 1 and b_{k+1} ((2k+3)^2 - 1) = c1 b_k + b_{k-1}/16.
  double bkm1 = 0, bk = 1, sum = 1, pw = 1;
  const double a2 = a * a;
  for (int k = 0; k < 500; ++k) {
    const double bk1 = (c1 * bk + bkm1 / 16.0) / ((2.0 * k + 3) * (2.0 * k + 3) - 1.0);
    pw *= a2;
    const double term = bk1 * pw;
    sum += term;
    bkm1 = bk;
    bk = bk1;
    if (k > 8 && std::abs(term) < 1e-17 * (1.0 + std::abs(sum))) break;
  }
  return sum;
}

double clamped_plate_top_eigenvalue(double a, double c1, int n) {
  const ChebBasis B(n);
  const double hs = 0.5 * a;
  const int m = n - 1;  // interior nodes; theta(0) = theta(a) = 0 eliminated
  Eigen::MatrixXd M(m, m);
  for (int i = 1; i < n; ++i) {
    const double x = (B.z(i) + 1.0) * hs;
    for (int j = 1; j < n; ++j) M(i - 1, j - 1) = B.D2(i, j) / (hs * hs) + B.D1(i, j) / (hs * x);
    M(i - 1, i - 1) += -1.0 / (x * x) - (x * x / 16.0 + c1);
  }
  // Inverse iteration: converges to the eigenvalue of smallest modulus.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
  VectorXd v = VectorXd::Ones(m);
  double mu = 0;
  for (int it = 0; it < 500; ++it) {
    const VectorXd w = lu.solve(v);
    const double lam = w.dot(v) / v.dot(v);  // ~ 1/mu
    const double mu_new = 1.0 / lam;
    v = w / w.norm();
    if (it > 5 && std::abs(mu_new - mu) <= 1e-14 * (1.0 + std::abs(mu_new))) {
      mu = mu_new;
      break;
    }
    mu = mu_new;
  }
  return mu;
}

std::vector<DiskPoint> disk_branch(const SolverOptions& options, double a_stop) {
  const ChebBasis B(options.resolution);
  const auto states = disk_states(options, B, a_stop);
  std::vector<DiskPoint> out;
  out.reserve(states.size());
  for (const auto& s : states) out.push_back(s.pt);
  return out;
}

std::vector<RingPoint> ring_branch(const SolverOptions& options, double a_min) {
  const ChebBasis B(options.resolution);
  const RidgeState R = ridge_state(options, B);
  const auto states = ring_states(options, B, R, a_min);
  std::vector<RingPoint> out;
  out.reserve(states.size());
  for (const auto& s : states) out.push_back(s.pt);
  return out;
}

RingPoint ring_point(const SolverOptions& options, double a) {
  const ChebBasis B(options.resolution);
  const RidgeState R = ridge_state(options, B);
  RingState st;
  if (!ring_from_ridge(options, B, R, a, st))
    throw std::runtime_error("contact: ring solve failed at a = " + std::to_string(a));
  return st.pt;
}

RidgeSolution solve_ridge(const SolverOptions& options) {
  const ChebBasis B(options.resolution);
  return ridge_state(options, B).sol;
}

Constants compute_constants(const SolverOptions& options, bool check_convergence) {
  Constants c = compute_core(options);
  if (check_convergence) {
    SolverOptions fine = options;
    fine.resolution += 8;
    const Constants f = compute_core(fine);
    SolverOptions longer = options;
    longer.domain_length *= 1.5;
    const Constants l = compute_core(longer);
    c.dN_plus_resolution = f.N_plus - c.N_plus;
    c.dN_plus_domain = l.N_plus - c.N_plus;
    c.dN_minus_resolution = f.N_minus - c.N_minus;
    c.dN_minus_domain = l.N_minus - c.N_minus;
    c.de_hat_plus_resolution = f.e_hat_plus - c.e_hat_plus;
    c.de_hat_plus_domain = l.e_hat_plus - c.e_hat_plus;
    c.dn2_resolution = f.n2 - c.n2;
    c.dn2_domain = l.n2 - c.n2;
    c.dreissner_resolution = f.reissner_slope - c.reissner_slope;
    c.dreissner_domain = l.reissner_slope - c.reissner_slope;
    c.dring_N_min_resolution = f.ring_N_min - c.ring_N_min;
    c.dring_N_min_domain = l.ring_N_min - c.ring_N_min;
  }
  return c;
}

void write_curves_csv(std::ostream& os, const std::vector<DiskPoint>& disk,
                      const std::vector<RingPoint>& ring) {
  const auto old = os.precision(12);
  os << "branch,a,N,e_hat,c1,residual,min_gap\n";
  for (const auto& p : disk)
    os << "disk," << p.a << ',' << p.N << ',' << p.e_hat << ',' << p.c1 << ',' << p.residual << ','
       << p.min_gap << '\n';
  for (const auto& p : ring)
    os << "ring," << p.a << ',' << p.N << ',' << p.e_hat << ",," << p.residual << ',' << p.min_gap
       << '\n';
  os.precision(old);
}

}  // namespace snapjump::contact
