#include "theory/shell_branch.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

namespace snapjump::theory {
namespace {

constexpr double kPi = std::numbers::pi;

// --- Second-order forward automatic differentiation ---------------------------------------------
// A value with its gradient and Hessian with respect to N independent variables.
template <int N>
struct Jet {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  double v = 0.0;
  Vec g = Vec::Zero();
  Mat H = Mat::Zero();

  static Jet variable(int i, double value) {
    Jet j;
    j.v = value;
    j.g(i) = 1.0;
    return j;
  }
  // f(this) from f, f', f'' at this->v.
  Jet chain(double f, double df, double ddf) const {
    Jet r;
    r.v = f;
    r.g = df * g;
    r.H = df * H + ddf * g * g.transpose();
    return r;
  }
};

template <int N>
Jet<N> operator+(Jet<N> a, const Jet<N>& b) {
  a.v += b.v;
  a.g += b.g;
  a.H += b.H;
  return a;
}
template <int N>
Jet<N> operator-(Jet<N> a, const Jet<N>& b) {
  a.v -= b.v;
  a.g -= b.g;
  a.H -= b.H;
  return a;
}
template <int N>
Jet<N> operator-(Jet<N> a) {
  a.v = -a.v;
  a.g = -a.g;
  a.H = -a.H;
  return a;
}
template <int N>
Jet<N> operator*(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> r;
  r.v = a.v * b.v;
  r.g = a.v * b.g + b.v * a.g;
  r.H = a.v * b.H + b.v * a.H + a.g * b.g.transpose() + b.g * a.g.transpose();
  return r;
}
template <int N>
Jet<N> operator*(Jet<N> a, double s) {
  a.v *= s;
  a.g *= s;
  a.H *= s;
  return a;
}
template <int N>
Jet<N> operator*(double s, const Jet<N>& a) {
  return a * s;
}
template <int N>
Jet<N> operator+(Jet<N> a, double s) {
  a.v += s;
  return a;
}
template <int N>
Jet<N> operator-(Jet<N> a, double s) {
  a.v -= s;
  return a;
}
template <int N>
Jet<N> inverse(const Jet<N>& a) {
  const double i = 1.0 / a.v;
  return a.chain(i, -i * i, 2.0 * i * i * i);
}
template <int N>
Jet<N> operator/(const Jet<N>& a, const Jet<N>& b) {
  return a * inverse(b);
}
template <int N>
Jet<N> operator/(const Jet<N>& a, double s) {
  return a * (1.0 / s);
}
template <int N>
Jet<N> sqrt(const Jet<N>& a) {
  const double s = std::sqrt(a.v);
  return a.chain(s, 0.5 / s, -0.25 / (s * a.v));
}
using std::sqrt;

// --- The discrete shell (lengths in R, stresses in E, energies in E R^3) ------------------------
// Full degrees of freedom: 4 per node, (r, r', z, z'), ' = d/dxi with xi = s0 / R.
// Reduced ones: those left free by the boundary conditions; each full one is
// offset + coef * reduced[index] (index -1: fixed).
struct DofLink {
  int index = -1;
  double coef = 0.0;
  double offset = 0.0;
};

// Reference data at one Gauss point of one element.
struct RefPoint {
  double r0 = 0.0, lam0 = 0.0, dbeta0 = 0.0, sinb0 = 0.0;
  double w = 0.0;  // Gauss weight times element length (dxi)
};

// Local variables at a Gauss point, q = (r, r', r'', z', z''), are B d with d the element's
// full dofs (r_i, r'_i, z_i, z'_i, r_j, r'_j, z_j, z'_j).
using BMat = Eigen::Matrix<double, 5, 8>;

struct Model {
  int ne = 0;
  double dxi = 0.0, nu = 0.0, cm = 0.0, cb = 0.0, pcl = 0.0, V0 = 0.0;
  std::vector<DofLink> links;   // per full dof
  int nred = 0;                 // reduced dofs
  std::vector<BMat> B;          // per Gauss point (uniform mesh)
  std::vector<double> gauss_w;  // per Gauss point, times dxi
  std::vector<RefPoint> ref;    // per element and Gauss point
  Eigen::VectorXd full0, red0;  // natural cap
};

Eigen::VectorXd to_full(const Model& m, const Eigen::VectorXd& red) {
  Eigen::VectorXd f(m.links.size());
  for (std::size_t k = 0; k < m.links.size(); ++k) {
    const DofLink& l = m.links[k];
    f(static_cast<Eigen::Index>(k)) = l.offset + (l.index >= 0 ? l.coef * red(l.index) : 0.0);
  }
  return f;
}

// Hermite cubic shape functions on [0, 1] of an element of length le: values and the first
// and second derivatives with respect to xi, ordered (value_i, slope_i, value_j, slope_j).
std::array<Eigen::Vector4d, 3> hermite(double t, double le) {
  Eigen::Vector4d n, d1, d2;
  n << 1 - 3 * t * t + 2 * t * t * t, le * (t - 2 * t * t + t * t * t), 3 * t * t - 2 * t * t * t,
      le * (t * t * t - t * t);
  d1 << (-6 * t + 6 * t * t) / le, 1 - 4 * t + 3 * t * t, (6 * t - 6 * t * t) / le,
      3 * t * t - 2 * t;
  d2 << (-6 + 12 * t) / (le * le), (-4 + 6 * t) / le, (6 - 12 * t) / (le * le), (6 * t - 2) / le;
  return {n, d1, d2};
}

void build_quadrature(Model& m) {
  // Five-point Gauss-Legendre on [0, 1].
  const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
  const double wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
  const std::array<double, 5> x{-b, -a, 0.0, a, b};
  const std::array<double, 5> w{wb, wa, 128.0 / 225.0, wa, wb};
  for (int g = 0; g < 5; ++g) {
    const auto [n, d1, d2] = hermite(0.5 * (1.0 + x[g]), m.dxi);
    BMat B = BMat::Zero();
    const std::array<int, 4> rdof{0, 1, 4, 5}, zdof{2, 3, 6, 7};
    for (int k = 0; k < 4; ++k) {
      B(0, rdof[k]) = n(k);
      B(1, rdof[k]) = d1(k);
      B(2, rdof[k]) = d2(k);
      B(3, zdof[k]) = d1(k);
      B(4, zdof[k]) = d2(k);
    }
    m.B.push_back(B);
    m.gauss_w.push_back(0.5 * w[g] * m.dxi);
  }
}

void build_dofs(Model& m, double phi) {
  const int nn = m.ne + 1;
  m.links.assign(static_cast<std::size_t>(4 * nn), DofLink{});
  int next = 0;
  auto link = [&](int node, int k) -> DofLink& {
    return m.links[static_cast<std::size_t>(4 * node + k)];
  };
  for (int i = 0; i < nn; ++i) {
    for (int k = 0; k < 4; ++k) link(i, k) = DofLink{-1, 0.0, 0.0};
  }
  // Apex: r = 0, z' = 0 (tangent normal to the axis); r' and z free.
  link(0, 1) = DofLink{next++, 1.0, 0.0};
  link(0, 2) = DofLink{next++, 1.0, 0.0};
  for (int i = 1; i < m.ne; ++i) {
    for (int k = 0; k < 4; ++k) link(i, k) = DofLink{next++, 1.0, 0.0};
  }
  // Rim: r and z fixed, the tangent (r', z') = t (cos phi, -sin phi) with its length t free.
  link(m.ne, 0) = DofLink{-1, 0.0, std::sin(phi)};
  link(m.ne, 2) = DofLink{-1, 0.0, 0.0};
  link(m.ne, 1) = DofLink{next, std::cos(phi), 0.0};
  link(m.ne, 3) = DofLink{next++, -std::sin(phi), 0.0};
  m.nred = next;

  m.full0.resize(4 * nn);
  for (int i = 0; i < nn; ++i) {
    const double xi = i * m.dxi;
    m.full0.segment<4>(4 * i) << std::sin(xi), std::cos(xi), std::cos(xi) - std::cos(phi),
        -std::sin(xi);
  }
  m.red0 = Eigen::VectorXd::Zero(m.nred);
  for (std::size_t k = 0; k < m.links.size(); ++k) {
    const DofLink& l = m.links[k];
    if (l.index >= 0 && l.coef != 0.0) {
      m.red0(l.index) = (m.full0(static_cast<Eigen::Index>(k)) - l.offset) / l.coef;
    }
  }
}

Eigen::Matrix<double, 8, 1> element_dofs(const Eigen::VectorXd& full, int e) {
  return full.segment<8>(4 * e);
}

// The natural meridian as the discretisation represents it, at every Gauss point.
void build_reference(Model& m) {
  m.ref.clear();
  for (int e = 0; e < m.ne; ++e) {
    const Eigen::Matrix<double, 8, 1> d = element_dofs(m.full0, e);
    for (std::size_t g = 0; g < m.B.size(); ++g) {
      const Eigen::Matrix<double, 5, 1> q = m.B[g] * d;
      const double lam0 = std::hypot(q(1), q(3));
      RefPoint p;
      p.r0 = q(0);
      p.lam0 = lam0;
      p.dbeta0 = (q(3) * q(2) - q(1) * q(4)) / (lam0 * lam0);
      p.sinb0 = -q(3) / lam0;
      p.w = m.gauss_w[g];
      m.ref.push_back(p);
    }
  }
}

// Strain energy per unit xi at a Gauss point (weights included), q = (r, r', r'', z', z'').
template <class T>
T energy_density(const std::array<T, 5>& q, const RefPoint& p, const Model& m) {
  const T& r = q[0];
  const T& rp = q[1];
  const T& rpp = q[2];
  const T& zp = q[3];
  const T& zpp = q[4];
  const T lam2 = rp * rp + zp * zp;
  const T lam = sqrt(lam2);
  const T es = lam / p.lam0 - 1.0;
  const T et = r / p.r0 - 1.0;
  const T ks = ((zp * rpp - rp * zpp) / lam2 - p.dbeta0) / p.lam0;
  const T kt = (-(zp / lam) - p.sinb0) / p.r0;
  const T membrane = es * es + et * et + 2.0 * m.nu * (es * et);
  const T bending = ks * ks + kt * kt + 2.0 * m.nu * (ks * kt);
  return (0.5 * m.cm * membrane + 0.5 * m.cb * bending) * (2.0 * kPi * p.r0 * p.lam0 * p.w);
}

// Volume between the meridian and the rim plane per unit xi: -pi r^2 z'.
template <class T>
T volume_density(const std::array<T, 5>& q, const RefPoint& p) {
  return -kPi * p.w * (q[0] * q[0] * q[3]);
}

Model make_model(const ShellBranchSpec& s, int segments) {
  Model m;
  m.ne = segments;
  m.dxi = s.phi / segments;
  m.nu = s.nu;
  const double t = s.h / s.R;
  m.cm = t / (1.0 - s.nu * s.nu);
  m.cb = t * t * t / (12.0 * (1.0 - s.nu * s.nu));
  m.pcl = 2.0 * t * t / std::sqrt(3.0 * (1.0 - s.nu * s.nu));
  build_quadrature(m);
  build_dofs(m, s.phi);
  build_reference(m);
  double V0 = 0.0;
  for (int e = 0; e < m.ne; ++e) {
    const Eigen::Matrix<double, 8, 1> d = element_dofs(m.full0, e);
    for (std::size_t g = 0; g < m.B.size(); ++g) {
      const Eigen::Matrix<double, 5, 1> q = m.B[g] * d;
      V0 += volume_density<double>({q(0), q(1), q(2), q(3), q(4)},
                                   m.ref[static_cast<std::size_t>(e) * m.B.size() + g]);
    }
  }
  m.V0 = V0;
  return m;
}

// --- Assembly ------------------------------------------------------------------------------------
struct Assembled {
  double U = 0.0, V = 0.0;
  Eigen::VectorXd gU, gV;                 // reduced gradients
  std::vector<Eigen::Triplet<double>> K;  // reduced Hessian of U + P V
};

Assembled assemble(const Model& m, const Eigen::VectorXd& red, double P, bool hessian) {
  using J5 = Jet<5>;
  Assembled a;
  a.gU = Eigen::VectorXd::Zero(m.nred);
  a.gV = Eigen::VectorXd::Zero(m.nred);
  if (hessian) a.K.reserve(static_cast<std::size_t>(m.ne) * 64);
  const Eigen::VectorXd full = to_full(m, red);
  for (int e = 0; e < m.ne; ++e) {
    const Eigen::Matrix<double, 8, 1> d = element_dofs(full, e);
    Eigen::Matrix<double, 8, 1> gU = Eigen::Matrix<double, 8, 1>::Zero(), gV = gU;
    Eigen::Matrix<double, 8, 8> H = Eigen::Matrix<double, 8, 8>::Zero();
    for (std::size_t g = 0; g < m.B.size(); ++g) {
      const BMat& B = m.B[g];
      const Eigen::Matrix<double, 5, 1> qv = B * d;
      std::array<J5, 5> q;
      for (int i = 0; i < 5; ++i) q[static_cast<std::size_t>(i)] = J5::variable(i, qv(i));
      const RefPoint& p = m.ref[static_cast<std::size_t>(e) * m.B.size() + g];
      const J5 u = energy_density(q, p, m);
      const J5 v = volume_density(q, p);
      a.U += u.v;
      a.V += v.v;
      gU += B.transpose() * u.g;
      gV += B.transpose() * v.g;
      if (hessian) H += B.transpose() * (u.H + P * v.H) * B;
    }
    for (int i = 0; i < 8; ++i) {
      const DofLink& li = m.links[static_cast<std::size_t>(4 * e + i)];
      if (li.index < 0) continue;
      a.gU(li.index) += li.coef * gU(i);
      a.gV(li.index) += li.coef * gV(i);
      if (!hessian) continue;
      for (int j = 0; j < 8; ++j) {
        const DofLink& lj = m.links[static_cast<std::size_t>(4 * e + j)];
        if (lj.index >= 0) a.K.emplace_back(li.index, lj.index, li.coef * lj.coef * H(i, j));
      }
    }
  }
  return a;
}

// --- Newton on the bordered system ---------------------------------------------------------------
// Unknowns: the reduced dofs x and q = dp / p_cl. Equations: grad U + q p_cl grad V = 0 and one
// constraint ax . x + av V(x) / V0 + aq q = rhs.
struct Constraint {
  Eigen::VectorXd ax;  // empty: zero
  double av = 0.0, aq = 0.0, rhs = 0.0;
};

struct State {
  Eigen::VectorXd red;
  double q = 0.0;
};

double constraint_value(const Model& m, const Constraint& c, const State& s, double V) {
  return (c.ax.size() > 0 ? c.ax.dot(s.red) : 0.0) + c.av * V / m.V0 + c.aq * s.q - c.rhs;
}

// Factorises the bordered Jacobian [K, p_cl gV; ax + av gV / V0, aq] of the state in a.
using SparseLu = Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>;
bool factorise(const Model& m, const Assembled& a, const Constraint& c, SparseLu& lu) {
  const int n = m.nred;
  std::vector<Eigen::Triplet<double>> t = a.K;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, n, m.pcl * a.gV(i));
    t.emplace_back(n, i, (c.ax.size() > 0 ? c.ax(i) : 0.0) + c.av * a.gV(i) / m.V0);
  }
  t.emplace_back(n, n, c.aq);
  Eigen::SparseMatrix<double> J(n + 1, n + 1);
  J.setFromTriplets(t.begin(), t.end());
  lu.compute(J);
  return lu.info() == Eigen::Success;
}

std::optional<Eigen::VectorXd> solve(SparseLu& lu, const Eigen::VectorXd& b) {
  Eigen::VectorXd x = lu.solve(b);
  if (lu.info() != Eigen::Success || !x.allFinite()) return std::nullopt;
  return x;
}

// Newton iterations from s; the number taken on convergence.
std::optional<int> correct(const Model& m, State& s, const Constraint& c) {
  constexpr int kMaxIterations = 12;
  constexpr double kTol = 1e-10;
  const int n = m.nred;
  SparseLu lu;
  for (int it = 1; it <= kMaxIterations; ++it) {
    const Assembled a = assemble(m, s.red, s.q * m.pcl, true);
    Eigen::VectorXd rhs(n + 1);
    rhs.head(n) = -(a.gU + s.q * m.pcl * a.gV);
    rhs(n) = -constraint_value(m, c, s, a.V);
    if (!factorise(m, a, c, lu)) return std::nullopt;
    const std::optional<Eigen::VectorXd> dx = solve(lu, rhs);
    if (!dx) return std::nullopt;
    s.red += dx->head(n);
    s.q += (*dx)(n);
    const double step = std::max(dx->head(n).lpNorm<Eigen::Infinity>(), std::abs((*dx)(n)));
    if (step > 0.5) return std::nullopt;  // left the neighbourhood of the branch
    if (step < kTol) return it;
  }
  return std::nullopt;
}

// --- Continuation --------------------------------------------------------------------------------
// Pseudo-arclength in the scaled space of (V / V0, dp / p_cl, the nodal positions over the cap's
// rise with weight 1 / nodes); see the header for why the shape enters the metric.
struct Sample {
  double v = 0.0, q = 0.0;  // V / V0, dp / p_cl
  double apex = 0.0;        // apex z minus its natural value, in R
  double U = 0.0;           // in E R^3
};

// The unit tangent, and the sign of the bordered Jacobian's determinant it was found with: along
// a regular branch the sign stays; it changes where a step crosses a bifurcation or cuts across
// the corner of a nearly bifurcating one onto a neighbouring branch.
struct Tangent {
  Eigen::VectorXd x;
  double v = 0.0, q = 0.0;
  double orientation = 0.0;
};

struct Trace {
  std::vector<Sample> samples;
  bool reached = false;
  std::string stop;   // why it stopped short, empty if it did not
  int newton = 0;     // Newton iterations in all
  State before, end;  // the last two states
};

Sample sample_of(const Model& m, const State& s) {
  const Assembled a = assemble(m, s.red, 0.0, false);
  const Eigen::VectorXd full = to_full(m, s.red);
  return Sample{a.V / m.V0, s.q, full(2) - m.full0(2), a.U};
}

// Weights of the reduced dofs in the arclength metric: positions only.
Eigen::VectorXd metric_weights(const Model& m, double depth) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.nred);
  for (std::size_t k = 0; k < m.links.size(); ++k) {
    const DofLink& l = m.links[k];
    if (l.index >= 0 && k % 2 == 0) w(l.index) = 1.0 / ((m.ne + 1) * depth * depth);
  }
  return w;
}

// The unit tangent at s, oriented along the constraint c's normal (the previous tangent).
std::optional<Tangent> tangent_at(const Model& m, const State& s, const Constraint& c,
                                  const Eigen::VectorXd& w) {
  const Assembled a = assemble(m, s.red, s.q * m.pcl, true);
  SparseLu lu;
  if (!factorise(m, a, c, lu)) return std::nullopt;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m.nred + 1);
  b(m.nred) = 1.0;
  const std::optional<Eigen::VectorXd> t = solve(lu, b);
  if (!t) return std::nullopt;
  Tangent tg{t->head(m.nred), a.gV.dot(t->head(m.nred)) / m.V0, (*t)(m.nred), lu.signDeterminant()};
  const double norm = std::sqrt(tg.x.dot(w.cwiseProduct(tg.x)) + tg.v * tg.v + tg.q * tg.q);
  tg.x /= norm;
  tg.v /= norm;
  tg.q /= norm;
  return tg;
}

// The arclength constraint of a step ds from (s, sample) along t.
Constraint arclength(const State& s, const Sample& p, const Tangent& t, const Eigen::VectorXd& w,
                     double ds) {
  Constraint c;
  c.ax = w.cwiseProduct(t.x);
  c.av = t.v;
  c.aq = t.q;
  c.rhs = c.ax.dot(s.red) + c.av * p.v + c.aq * p.q + ds;
  return c;
}

// From the natural state to V <= -V0, or, with a finite q_stop, until dp / p_cl reaches q_stop
// (stop says so if the pressure passes a maximum first).
Trace trace(const Model& m, double depth, double q_stop) {
  constexpr double kDsMax = 0.02, kDsMin = 1e-7, kTurnMax = 0.2, kTurnSoft = 0.08, kJump = 0.02;
  constexpr int kMaxSteps = 20000;
  const Eigen::VectorXd w = metric_weights(m, depth);
  Trace tr;
  State cur{m.red0, 0.0};
  tr.samples.push_back(Sample{1.0, 0.0, 0.0, 0.0});
  std::optional<Tangent> tan = tangent_at(m, cur, Constraint{{}, 0.0, 1.0, 0.0}, w);
  if (!tan) throw std::runtime_error("shell branch: the natural cap's stiffness is singular");
  double ds = 0.005;
  for (int step = 0; step < kMaxSteps; ++step) {
    const Sample& last = tr.samples.back();
    State s{cur.red + ds * tan->x, cur.q + ds * tan->q};
    const Constraint c = arclength(cur, last, *tan, w, ds);
    const std::optional<int> its = correct(m, s, c);
    std::optional<Tangent> next_tan;
    Sample next;
    double turn = 0.0;
    if (its) {
      tr.newton += *its;
      next = sample_of(m, s);
      next_tan = tangent_at(m, s, c, w);
      if (next_tan) {
        const double dot =
            tan->x.dot(w.cwiseProduct(next_tan->x)) + tan->v * next_tan->v + tan->q * next_tan->q;
        turn = std::acos(std::clamp(dot, -1.0, 1.0));
      }
    }
    const bool jump = std::abs(next.v - last.v) > kJump || std::abs(next.q - last.q) > kJump;
    const bool switched = next_tan && next_tan->orientation != tan->orientation;
    if (!its || !next_tan || turn > kTurnMax || jump || switched) {
      ds *= 0.5;
      if (ds < kDsMin) {
        tr.stop = fmt::format("the continuation stalled at V/V0 = {:.4f}, dp/p_cl = {:.4f}", last.v,
                              last.q);
        return tr;
      }
      continue;
    }
    tr.before = cur;
    tr.end = s;
    cur = s;
    tan = next_tan;
    tr.samples.push_back(next);
    if (next.v <= -1.0 || next.q >= q_stop) {
      tr.reached = next.v <= -1.0;
      return tr;
    }
    if (std::isfinite(q_stop) && next.q < last.q) {
      tr.stop = fmt::format("the pressure has a maximum at dp/p_cl = {:.4f}", last.q);
      return tr;
    }
    double grow = *its <= 3 ? 1.5 : (*its >= 6 ? 0.6 : 1.0);
    if (turn > kTurnSoft) grow = std::min(grow, 0.7);
    ds = std::min(ds * grow, kDsMax);
  }
  tr.stop = fmt::format("no inverted state within {} steps", kMaxSteps);
  return tr;
}

// --- Extrema -------------------------------------------------------------------------------------
// The extreme value of the parabola q(s) through the samples i - 1, i, i + 1, s the arclength of
// the branch in the (v, q) plane; q_i when the parabola's vertex lies outside them.
double refine_extremum(const std::vector<Sample>& b, std::size_t i) {
  const auto dist = [&](std::size_t j) {
    return std::hypot(b[j].v - b[j - 1].v, b[j].q - b[j - 1].q);
  };
  const double s0 = 0.0, s1 = dist(i), s2 = s1 + dist(i + 1);
  const double q0 = b[i - 1].q, q1 = b[i].q, q2 = b[i + 1].q;
  const double d01 = (q1 - q0) / (s1 - s0), d12 = (q2 - q1) / (s2 - s1);
  const double a = (d12 - d01) / (s2 - s0);
  if (a == 0.0) return q1;
  const double sv = 0.5 * (s0 + s1) - d01 / (2.0 * a);
  if (sv < s0 || sv > s2) return q1;
  return q0 + (sv - s0) * d01 + a * (sv - s0) * (sv - s1);
}

struct Extrema {
  double q_c = 0.0, q_minus = 0.0;
  bool minimum_inside = false;  // the least pressure after p_c is a minimum, not the last point
};

std::optional<Extrema> find_extrema(const std::vector<Sample>& b) {
  std::size_t ic = 0;
  for (std::size_t i = 1; i + 1 < b.size(); ++i) {
    if (b[i].q >= b[i - 1].q && b[i].q > b[i + 1].q) {
      ic = i;
      break;
    }
  }
  if (ic == 0) return std::nullopt;
  std::size_t im = ic + 1;
  for (std::size_t i = ic + 1; i < b.size(); ++i) {
    if (b[i].q < b[im].q) im = i;
  }
  Extrema x;
  x.q_c = refine_extremum(b, ic);
  x.minimum_inside = im + 1 < b.size();
  x.q_minus = x.minimum_inside ? refine_extremum(b, im) : b[im].q;
  return x;
}

// How often the volume changes direction along the branch.
int volume_turns(const std::vector<Sample>& b) {
  int turns = 0;
  double last = 0.0;
  for (std::size_t i = 1; i < b.size(); ++i) {
    const double dv = b[i].v - b[i - 1].v;
    if (dv * last < 0.0) ++turns;
    if (dv != 0.0) last = dv;
  }
  return turns;
}

void validate(const ShellBranchSpec& s) {
  const auto bad = [](const char* what) {
    throw std::invalid_argument(fmt::format("shell branch: {}", what));
  };
  if (!(s.R > 0.0) || !std::isfinite(s.R)) bad("R must be positive");
  if (!(s.h > 0.0) || !std::isfinite(s.h)) bad("h must be positive");
  if (!(s.h < s.R)) bad("h must be less than R");
  if (!(s.E > 0.0) || !std::isfinite(s.E)) bad("E must be positive");
  if (!(s.phi > 0.0 && s.phi < kPi)) bad("phi must lie in (0, pi)");
  if (!(s.nu > -1.0 && s.nu <= 0.5)) bad("nu must lie in (-1, 0.5]");
  if (s.segments < 0 || (s.segments > 0 && s.segments < 4)) bad("segments must be 0 or >= 4");
}

// The default mesh: six elements per sqrt(R h), the length scale of the rim's boundary layer and
// of the ridge that travels down the meridian during inversion, and at least 32.
int segments_of(const ShellBranchSpec& s) {
  if (s.segments > 0) return s.segments;
  const double per_scale = s.R * s.phi / std::sqrt(s.R * s.h);
  return std::clamp(static_cast<int>(std::ceil(6.0 * per_scale)), 32, 2000);
}

// The equilibrium at q = dp / p_cl on the natural branch: traced up to q and corrected at q for
// q > 0, load steps for q <= 0 (an inflated cap has no limit point).
State state_at_pressure(const Model& m, double depth, double q) {
  State s{m.red0, 0.0};
  if (q > 0.0) {
    const Trace tr = trace(m, depth, q);
    if (!tr.stop.empty() || tr.samples.back().q < q) {
      throw std::runtime_error(fmt::format(
          "shell branch: no equilibrium at dp/p_cl = {:.4f} before the buckling pressure: {}", q,
          tr.stop));
    }
    const double t = (q - tr.before.q) / (tr.end.q - tr.before.q);
    s.red = tr.before.red + t * (tr.end.red - tr.before.red);
    s.q = q;
  }
  const int steps = q > 0.0 ? 1 : std::max(1, static_cast<int>(std::ceil(-q / 0.05)));
  for (int k = 1; k <= steps; ++k) {
    const double target = q > 0.0 ? q : q * k / steps;
    if (!correct(m, s, Constraint{{}, 0.0, 1.0, target})) {
      throw std::runtime_error(
          fmt::format("shell branch: no equilibrium found at dp/p_cl = {:.4f}", target));
    }
  }
  return s;
}

}  // namespace

ShellBranch trace_shell_branch(const ShellBranchSpec& spec) {
  validate(spec);
  const Model m = make_model(spec, segments_of(spec));
  const Trace tr = trace(m, 1.0 - std::cos(spec.phi), std::numeric_limits<double>::infinity());
  const std::optional<Extrema> x = find_extrema(tr.samples);
  if (!x) {
    throw std::runtime_error("shell branch: no pressure maximum found: " +
                             (tr.stop.empty() ? std::string("none before inversion") : tr.stop));
  }
  if (!tr.reached && !x->minimum_inside) {
    throw std::runtime_error("shell branch: no pressure minimum after p_c found: " + tr.stop);
  }
  const double R3 = spec.R * spec.R * spec.R;
  ShellBranch b;
  b.segments = m.ne;
  b.V0 = m.V0 * R3;
  b.p_cl = m.pcl * spec.E;
  b.p_c = x->q_c * b.p_cl;
  b.p_minus = x->q_minus * b.p_cl;
  b.reached_inverted = tr.reached;
  b.points.reserve(tr.samples.size());
  for (const Sample& s : tr.samples) {
    b.points.push_back(BranchPoint{s.v * b.V0, s.q * b.p_cl, s.apex * spec.R, s.U * spec.E * R3});
  }
  b.note =
      fmt::format("{} segments, {} branch points, {} Newton iterations, {} turns in volume{}{}",
                  m.ne, tr.samples.size(), tr.newton, volume_turns(tr.samples),
                  tr.stop.empty() ? "" : "; stopped: ", tr.stop);
  if (!x->minimum_inside) b.note += "; the pressure still falls at the end: p_- is its last value";
  return b;
}

ShellState solve_shell_at_pressure(const ShellBranchSpec& spec, double dp) {
  validate(spec);
  if (!std::isfinite(dp)) throw std::invalid_argument("shell branch: dp must be finite");
  const Model m = make_model(spec, segments_of(spec));
  const State s = state_at_pressure(m, 1.0 - std::cos(spec.phi), dp / (m.pcl * spec.E));
  const Assembled a = assemble(m, s.red, 0.0, false);
  const Eigen::VectorXd full = to_full(m, s.red);
  const double R = spec.R;
  ShellState out;
  out.dp = dp;
  out.volume = a.V * R * R * R;
  out.strain_energy = a.U * spec.E * R * R * R;
  for (int i = 0; i <= m.ne; ++i) {
    const Eigen::Index k = 4 * i;
    out.nodes.push_back(MeridianNode{i * m.dxi * R, m.full0(k) * R, m.full0(k + 2) * R, full(k) * R,
                                     full(k + 2) * R});
  }
  return out;
}

}  // namespace snapjump::theory
