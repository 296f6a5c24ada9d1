#include "fem/surface_instability.hpp"

#include <array>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace snapjump::fem {
namespace {

using Stretches = std::array<double, 3>;

// dW / d lambda_i at the principal stretches l: the diagonal of the first Piola stress there.
double first(const Material& m, const Stretches& l, int i) {
  const double F[9] = {l[0], 0, 0, 0, l[1], 0, 0, 0, l[2]};
  double P[9];
  if (!first_piola_stress(m, F, P)) {
    throw std::runtime_error("biot_instability: the law is not defined at these stretches");
  }
  return P[4 * i];
}

// d^2 W / d lambda_i d lambda_j by central differences of the stress: a step of 1e-5 keeps the
// truncation (~1e-10 relative) and the rounding (~1e-16 / 1e-5) alike small.
constexpr double kStep = 1e-5;

double second(const Material& m, Stretches l, int i, int j) {
  const double lj = l[j];
  l[j] = lj + kStep;
  const double up = first(m, l, i);
  l[j] = lj - kStep;
  return (up - first(m, l, i)) / (2.0 * kStep);
}

// The in-plane instantaneous moduli A_piqj (Ogden's, push-forward of the elasticity tensor at the
// principal axes) that the plane problem needs.
struct Moduli {
  double a1111, a2222, a1122, a1212, a2121, a1221;
};

Moduli moduli(const Material& m, const Stretches& l) {
  const double J = l[0] * l[1] * l[2];
  const double W1 = first(m, l, 0), W2 = first(m, l, 1);
  Moduli a{};
  a.a1111 = l[0] * l[0] * second(m, l, 0, 0) / J;
  a.a2222 = l[1] * l[1] * second(m, l, 1, 1) / J;
  a.a1122 = l[0] * l[1] * second(m, l, 0, 1) / J;
  const double s1 = l[0] * W1 / J, s2 = l[1] * W2 / J;  // Cauchy principal stresses
  if (std::abs(l[0] - l[1]) > 1e-6) {
    const double d = l[0] * l[0] - l[1] * l[1];
    a.a1212 = (l[0] * W1 - l[1] * W2) * l[0] * l[0] / (d * J);
    a.a2121 = (l[1] * W2 - l[0] * W1) * l[1] * l[1] / (-d * J);
  } else {
    a.a1212 = 0.5 * (a.a1111 - a.a1122 + s1);
    a.a2121 = 0.5 * (a.a2222 - a.a1122 + s2);
  }
  a.a1221 = a.a1212 - s1;  // = A_2112
  return a;
}

// The surface's traction determinant over the exponents' difference (real; negative while the
// surface is stable).
double traction_determinant(const Moduli& a) {
  using C = std::complex<double>;
  const double c = a.a1122 + a.a1221;
  // A2121 A2222 q^4 - (A2121 A1212 + A1111 A2222 - c^2) q^2 + A1111 A1212 = 0.
  const double qa = a.a2121 * a.a2222, qb = -(a.a2121 * a.a1212 + a.a1111 * a.a2222 - c * c),
               qc = a.a1111 * a.a1212;
  const C root = std::sqrt(C(qb * qb - 4.0 * qa * qc));
  std::array<C, 2> q = {std::sqrt((-qb + root) / (2.0 * qa)), std::sqrt((-qb - root) / (2.0 * qa))};
  for (auto& x : q) {
    if (x.real() < 0.0) x = -x;  // decaying into x2 < 0
  }
  // A mode (i q c, A1111 - A2121 q^2) has tractions i a(q) along x1 and q b(q) along x2.
  const auto ta = [&](C x) { return a.a2121 * c * x * x + a.a1221 * (a.a1111 - a.a2121 * x * x); };
  const auto tb = [&](C x) { return a.a2222 * (a.a1111 - a.a2121 * x * x) - a.a1122 * c; };
  const C d = ta(q[0]) * q[1] * tb(q[1]) - ta(q[1]) * q[0] * tb(q[0]);
  return (d / (q[1] - q[0])).real();
}

double determinant_at(const Material& m, double tangential, double third) {
  const Stretches l = {tangential, free_normal_stretch(m, tangential, third), third};
  return traction_determinant(moduli(m, l));
}

}  // namespace

double free_normal_stretch(const Material& m, double tangential, double third_stretch) {
  // dW / d lambda_2 rises with lambda_2 (the energy is convex in it): bisect in its logarithm.
  double lo = std::log(0.05), hi = std::log(20.0);
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double w2 = first(m, {tangential, std::exp(mid), third_stretch}, 1);
    (w2 > 0.0 ? hi : lo) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

SurfaceInstability biot_instability(const Material& m, double third_stretch) {
  constexpr double kStart = 0.995, kEnd = 0.2, kScan = 0.005;
  double upper = kStart, f_upper = determinant_at(m, upper, third_stretch);
  for (double l = kStart - kScan; l >= kEnd; l -= kScan) {
    const double f = determinant_at(m, l, third_stretch);
    if ((f > 0.0) != (f_upper > 0.0)) {
      double lo = l, hi = upper;  // the sign changes between lo and hi
      const bool lo_positive = f > 0.0;
      for (int it = 0; it < 100 && hi - lo > 1e-12; ++it) {
        const double mid = 0.5 * (lo + hi);
        ((determinant_at(m, mid, third_stretch) > 0.0) == lo_positive ? lo : hi) = mid;
      }
      SurfaceInstability s;
      s.tangential = 0.5 * (lo + hi);
      s.normal = free_normal_stretch(m, s.tangential, third_stretch);
      s.ratio = s.normal / s.tangential;
      return s;
    }
    upper = l;
    f_upper = f;
  }
  throw std::runtime_error("biot_instability: the surface stays stable down to a stretch of 0.2");
}

}  // namespace snapjump::fem
