#include "axi/contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "axi/quadratic.hpp"

namespace snapjump::axi {

double RimCone::gap(double r, double z, double dz) const {
  return r * std::cos(phi) + (z - dz) * std::sin(phi);
}
double RimCone::along(double r, double z, double dz) const {
  return r * std::sin(phi) - (z - dz) * std::cos(phi);
}
double RimCone::nr() const { return std::cos(phi); }
double RimCone::nz() const { return std::sin(phi); }

double RimCone::stop(double r, double z, double vr, double vz, double dt, double dz) const {
  const double re = r + dt * vr, ze = z + dt * vz;
  const double g = gap(re, ze, dz);
  if (!(g > 0.0) || along(re, ze, dz) < s_min) return 0.0;
  return g / dt;
}

RimCone rim_cone(const MeshSpec& spec) { return {spec.phi, spec.R - 0.5 * spec.h}; }

double default_contact_stiffness(const Body& body) {
  const auto& m = body.material();
  return (m.lambda + 2.0 * m.mu) / (body.spec().h / body.spec().through);
}

InnerSelfContact::InnerSelfContact(const Body& body, double stiffness)
    : body_(&body), k_(stiffness), depth_limit_(body.spec().h) {
  // Each node's share of the reference inner surface: the integral of N_a dA, dA = 2 pi rho ds.
  const auto& in = body.inner();
  const auto& X = body.nodes();
  area_.assign(in.size(), 0.0);
  const auto g = gauss(3);
  for (std::size_t k = 0; k + 2 < in.size(); k += 2) {
    for (int p = 0; p < 3; ++p) {
      const auto L = lagrange(g.x[p]);
      const auto dL = lagrange_d(g.x[p]);
      double rho = 0, dr = 0, dz = 0;
      for (int m = 0; m < 3; ++m) {
        rho += L[m] * X.r[in[k + m]];
        dr += dL[m] * X.r[in[k + m]];
        dz += dL[m] * X.z[in[k + m]];
      }
      const double dA = g.w[p] * 2.0 * std::numbers::pi * rho * std::hypot(dr, dz);
      for (int m = 0; m < 3; ++m) area_[k + m] += L[m] * dA;
    }
  }
}

namespace {

struct Projection {
  double xi = 0.0, dist2 = 1e300;
};

// The closest point of the quadratic segment (p0, p1, p2) to q: Newton's method on
// d/dxi |x(xi) - q|^2 = 0 from the best of five samples, kept within [-1, 1].
Projection project(const double pr[3], const double pz[3], double qr, double qz) {
  Projection best;
  const auto at = [&](double xi, double& r, double& z) {
    const auto L = lagrange(xi);
    r = L[0] * pr[0] + L[1] * pr[1] + L[2] * pr[2];
    z = L[0] * pz[0] + L[1] * pz[1] + L[2] * pz[2];
  };
  for (double xi : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
    double r, z;
    at(xi, r, z);
    const double d2 = (r - qr) * (r - qr) + (z - qz) * (z - qz);
    if (d2 < best.dist2) best = {xi, d2};
  }
  double xi = best.xi;
  for (int it = 0; it < 8; ++it) {
    double r, z;
    at(xi, r, z);
    const auto dL = lagrange_d(xi);
    const double tr = dL[0] * pr[0] + dL[1] * pr[1] + dL[2] * pr[2];
    const double tz = dL[0] * pz[0] + dL[1] * pz[1] + dL[2] * pz[2];
    // x'' is constant on a quadratic: (p0 - 2 p1 + p2).
    const double cr = pr[0] - 2.0 * pr[1] + pr[2], cz = pz[0] - 2.0 * pz[1] + pz[2];
    const double g = (r - qr) * tr + (z - qz) * tz;
    const double H = tr * tr + tz * tz + (r - qr) * cr + (z - qz) * cz;
    if (!(H > 0.0)) break;
    xi = std::clamp(xi - g / H, -1.0, 1.0);
  }
  double r, z;
  at(xi, r, z);
  return {xi, (r - qr) * (r - qr) + (z - qz) * (z - qz)};
}

}  // namespace

double InnerSelfContact::add_forces(const Points& x, Points& f) const {
  const auto& in = body_->inner();
  const std::size_t n = in.size();
  deepest_ = 0.0;
  touching_ = 0;
  double energy = 0.0;
  // Segment k holds inner nodes 2k, 2k + 1, 2k + 2 (from the axis to the rim).
  for (std::size_t a = 0; a < n; ++a) {
    const double qr = x.r[in[a]], qz = x.z[in[a]];
    for (std::size_t k = 0; k + 2 < n; k += 2) {
      if (a >= k && a <= k + 2) continue;  // its own segment
      const double pr[3] = {x.r[in[k]], x.r[in[k + 1]], x.r[in[k + 2]]};
      const double pz[3] = {x.z[in[k]], x.z[in[k + 1]], x.z[in[k + 2]]};
      // Cheap rejection: farther than the depth limit from every node of the segment's hull.
      const double lo_r = std::min({pr[0], pr[1], pr[2]}) - depth_limit_;
      const double hi_r = std::max({pr[0], pr[1], pr[2]}) + depth_limit_;
      const double lo_z = std::min({pz[0], pz[1], pz[2]}) - depth_limit_;
      const double hi_z = std::max({pz[0], pz[1], pz[2]}) + depth_limit_;
      if (qr < lo_r || qr > hi_r || qz < lo_z || qz > hi_z) continue;
      const auto pj = project(pr, pz, qr, qz);
      // Only a projection inside the segment is a crossing of it (an end point belongs to the
      // neighbour's interior or to the surface's ends).
      if (pj.xi <= -1.0 || pj.xi >= 1.0) continue;
      const auto L = lagrange(pj.xi);
      const auto dL = lagrange_d(pj.xi);
      const double cr = L[0] * pr[0] + L[1] * pr[1] + L[2] * pr[2];
      const double cz = L[0] * pz[0] + L[1] * pz[1] + L[2] * pz[2];
      const double tr = dL[0] * pr[0] + dL[1] * pr[1] + dL[2] * pr[2];
      const double tz = dL[0] * pz[0] + dL[1] * pz[1] + dL[2] * pz[2];
      const double tn = std::hypot(tr, tz);
      if (!(tn > 0.0)) continue;
      // Normal into the cavity (away from the material): (-dz, dr) / |t| along the surface's
      // direction from the axis to the rim.
      const double nr = -tz / tn, nz = tr / tn;
      const double g = (qr - cr) * nr + (qz - cz) * nz;
      if (!(g < 0.0) || g < -depth_limit_) continue;
      const double push = k_ * area_[a] * (-g);  // along n on the node
      f.r[in[a]] += push * nr;
      f.z[in[a]] += push * nz;
      for (int m = 0; m < 3; ++m) {
        f.r[in[k + m]] -= push * L[m] * nr;
        f.z[in[k + m]] -= push * L[m] * nz;
      }
      energy += 0.5 * k_ * area_[a] * g * g;
      deepest_ = std::max(deepest_, -g);
      ++touching_;
    }
  }
  return energy;
}

}  // namespace snapjump::axi
