#include "axi/surface_stretch.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "axi/quadratic.hpp"

namespace snapjump::axi {
namespace {

// d(r, z)/d(s, t) of the element at the local point (s, t).
struct Jacobian {
  double rs = 0, rt = 0, zs = 0, zt = 0;
  [[nodiscard]] double det() const { return rs * zt - rt * zs; }
};

Jacobian jacobian(const std::array<int, 9>& el, const Points& x, double s, double t) {
  const auto La = lagrange(s), Lb = lagrange(t);
  const auto dLa = lagrange_d(s), dLb = lagrange_d(t);
  Jacobian j;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      const int n = el[3 * a + b];
      j.rs += dLa[a] * Lb[b] * x.r[n];
      j.zs += dLa[a] * Lb[b] * x.z[n];
      j.rt += La[a] * dLb[b] * x.r[n];
      j.zt += La[a] * dLb[b] * x.z[n];
    }
  }
  return j;
}

// The singular values of the 2 x 2 matrix [[a, b], [c, d]], largest first: with the matrix
// split into a rotation-like part (e, h) and a reflection-like part (f, g), they are
// |(e, h)| + |(f, g)| and their difference's magnitude, free of the cancellation that the
// roots of the characteristic polynomial of its square suffer near equal values.
std::pair<double, double> singular_values(double a, double b, double c, double d) {
  const double q = std::hypot(0.5 * (a + d), 0.5 * (c - b));
  const double r = std::hypot(0.5 * (a - d), 0.5 * (c + b));
  return {q + r, std::abs(q - r)};
}

}  // namespace

std::vector<SurfaceStretch> inner_surface_stretches(const Body& body, const Points& x,
                                                    int per_element) {
  if (per_element < 2) {
    throw std::invalid_argument("inner_surface_stretches: at least 2 points per element");
  }
  const auto& spec = body.spec();
  const auto& X = body.nodes();
  std::vector<SurfaceStretch> out;
  out.reserve(static_cast<std::size_t>(spec.along * per_element));
  for (int e = 0; e < spec.along; ++e) {
    const auto& el = body.elements()[static_cast<std::size_t>(e * spec.through)];  // k = 0
    for (int p = 0; p < per_element; ++p) {
      const double s = -1.0 + 2.0 * p / (per_element - 1);
      const auto J0 = jacobian(el, X, s, -1.0), J = jacobian(el, x, s, -1.0);
      // F = J J0^-1 in the meridian plane.
      const double inv = 1.0 / J0.det();
      const double f11 = (J.rs * J0.zt - J.rt * J0.zs) * inv,
                   f12 = (J.rt * J0.rs - J.rs * J0.rt) * inv;
      const double f21 = (J.zs * J0.zt - J.zt * J0.zs) * inv,
                   f22 = (J.zt * J0.rs - J.zs * J0.rt) * inv;
      const auto [big, small] = singular_values(f11, f12, f21, f22);
      SurfaceStretch st;
      st.tangential = std::hypot(J.rs, J.zs) / std::hypot(J0.rs, J0.zs);
      st.ratio = small > 0.0 ? big / small : std::numeric_limits<double>::infinity();
      // The stretch along the surface is the smaller principal one (where the two differ beyond
      // rounding: an unstretched surface is not compressed).
      st.compressed = big - small > 1e-9 * big && st.tangential - small < big - st.tangential;
      double R0 = 0, Z0 = 0;
      const auto La = lagrange(s);
      for (int a = 0; a < 3; ++a) {
        R0 += La[a] * X.r[el[3 * a]];
        Z0 += La[a] * X.z[el[3 * a]];
      }
      st.from_rim = inner_arc_from_rim(spec, std::atan2(R0, -Z0));
      out.push_back(st);
    }
  }
  return out;
}

SurfaceStretch largest_compressed_ratio(const std::vector<SurfaceStretch>& stretches) {
  SurfaceStretch best;
  best.from_rim = std::numeric_limits<double>::quiet_NaN();
  for (const auto& s : stretches) {
    if (s.compressed && s.ratio > best.ratio) best = s;
  }
  return best;
}

}  // namespace snapjump::axi
