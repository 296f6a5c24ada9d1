#include "axi/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "axi/quadratic.hpp"

namespace snapjump::axi {

RimCone rim_cone(const MeshSpec& spec) { return core::container_face(spec.R, spec.h, spec.phi); }

double default_contact_stiffness(const Body& body) {
  const auto& m = body.material();
  return (m.lambda + 2.0 * m.mu) / (body.spec().h / body.spec().through);
}

Penalty penalty(double depth, double smoothing) {
  if (depth >= smoothing) {
    const double g0 = smoothing;
    return {depth - 0.5 * g0, 0.5 * depth * depth - 0.5 * g0 * depth + g0 * g0 / 6.0};
  }
  return {0.5 * depth * depth / smoothing, depth * depth * depth / (6.0 * smoothing)};
}

InnerSelfContact::InnerSelfContact(const Body& body, double stiffness, double smoothing)
    : body_(&body), k_(stiffness), smoothing_(smoothing), depth_limit_(body.spec().h) {
  // Each node's share of the reference inner surface: the integral of N_a dA, dA = 2 pi rho ds.
  area_.assign(body.inner().size(), 0.0);
  body.for_each_inner_point(
      body.nodes(), [&](std::size_t k, double w, const std::array<double, 3>& L, double rho,
                        double dr, double dz) {
        const double dA = w * 2.0 * std::numbers::pi * rho * std::hypot(dr, dz);
        for (int m = 0; m < 3; ++m) area_[k + m] += L[m] * dA;
      });
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
    const double next = std::clamp(xi - g / H, -1.0, 1.0);
    if (next == xi) break;  // a fixed point: further steps would return it again
    xi = next;
  }
  double r, z;
  at(xi, r, z);
  return {xi, (r - qr) * (r - qr) + (z - qz) * (z - qz)};
}

}  // namespace

InnerSelfContact::Touch InnerSelfContact::touch(const Points& x) const {
  Points f{std::vector<double>(x.size(), 0.0), std::vector<double>(x.size(), 0.0)};
  add_forces(x, f);
  return {deepest_, regions_};
}

// Each segment's box (its three nodes widened by the depth limit) and its unit tangents at its two
// ends, from the axis towards the rim.
void InnerSelfContact::prepare(const Points& x) const {
  const auto& in = body_->inner();
  const std::size_t n = in.size();
  segments_.resize(n / 2);
  for (std::size_t k = 0; k + 2 < n; k += 2) {
    const double r[3] = {x.r[in[k]], x.r[in[k + 1]], x.r[in[k + 2]]};
    const double z[3] = {x.z[in[k]], x.z[in[k + 1]], x.z[in[k + 2]]};
    Segment& s = segments_[k / 2];
    s.lo_r = std::min({r[0], r[1], r[2]}) - depth_limit_;
    s.hi_r = std::max({r[0], r[1], r[2]}) + depth_limit_;
    s.lo_z = std::min({z[0], z[1], z[2]}) - depth_limit_;
    s.hi_z = std::max({z[0], z[1], z[2]}) + depth_limit_;
    for (int end = 0; end < 2; ++end) {
      const auto dL = lagrange_d(end == 0 ? -1.0 : 1.0);
      const double tr = dL[0] * r[0] + dL[1] * r[1] + dL[2] * r[2];
      const double tz = dL[0] * z[0] + dL[1] * z[1] + dL[2] * z[2];
      const double tn = std::hypot(tr, tz);
      s.t[end][0] = tn > 0.0 ? tr / tn : 0.0;
      s.t[end][1] = tn > 0.0 ? tz / tn : 0.0;
    }
  }
}

// Whether a point at q (inner node a, or none) may take its crossing from the interior of the
// segment from inner node k: at each end shared with a neighbouring segment that does not hold a
// either, q lies on this segment's side of the corner's split (the line through the corner across
// the mean of the two tangents, where the two segments' gaps are equal).
bool InnerSelfContact::owns(const Points& x, std::size_t a, double qr, double qz,
                            std::size_t k) const {
  const auto& in = body_->inner();
  const std::size_t n = in.size();
  const auto beyond = [&](std::size_t corner, const double* ta, const double* tb) {
    return (qr - x.r[in[corner]]) * (ta[0] + tb[0]) + (qz - x.z[in[corner]]) * (ta[1] + tb[1]);
  };
  const auto holds = [&](std::size_t seg) { return a >= seg && a <= seg + 2; };
  if (k >= 2 && !holds(k - 2) &&
      beyond(k, segments_[k / 2 - 1].t[1], segments_[k / 2].t[0]) < 0.0) {
    return false;
  }
  if (k + 4 < n && !holds(k + 2) &&
      beyond(k + 2, segments_[k / 2].t[1], segments_[k / 2 + 1].t[0]) > 0.0) {
    return false;
  }
  return true;
}

template <typename Visit>
void InnerSelfContact::crossings(const Points& x, std::size_t a, double qr, double qz,
                                 Visit visit) const {
  const auto& in = body_->inner();
  const std::size_t n = in.size();
  // The interiors of the segments (from inner node k: k, k + 1, k + 2) that do not hold a.
  for (std::size_t k = 0; k + 2 < n; k += 2) {
    if (a >= k && a <= k + 2) continue;
    const Segment& b = segments_[k / 2];
    if (qr < b.lo_r || qr > b.hi_r || qz < b.lo_z || qz > b.hi_z) continue;
    const double pr[3] = {x.r[in[k]], x.r[in[k + 1]], x.r[in[k + 2]]};
    const double pz[3] = {x.z[in[k]], x.z[in[k + 1]], x.z[in[k + 2]]};
    const auto pj = project(pr, pz, qr, qz);
    // A projection onto an end belongs to the corner there (below) or to the surface's end.
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
    if (!(g < 0.0) || g < -depth_limit_ || !owns(x, a, qr, qz, k)) continue;
    visit(k, pj.xi, nr, nz, -g);
  }
  // The corners (the node shared by the segments from j - 2 and from j, neither holding a) where
  // the surface turns away from the cavity: on the material's side, beyond the first segment's
  // end and before the second's start, the closest point is the corner itself.
  for (std::size_t j = 2; j + 2 < n; j += 2) {
    if (a >= j - 2 && a <= j + 2) continue;
    const double dr = qr - x.r[in[j]], dz = qz - x.z[in[j]];
    // (Outside the corner's box no hypot: this runs for every node and corner at every step.)
    if (std::abs(dr) > depth_limit_ || std::abs(dz) > depth_limit_) continue;
    const double d = std::hypot(dr, dz);
    if (!(d > 0.0) || d > depth_limit_) continue;
    const double* ta = segments_[j / 2 - 1].t[1];
    const double* tb = segments_[j / 2].t[0];
    if (dr * ta[0] + dz * ta[1] < 0.0 || dr * tb[0] + dz * tb[1] > 0.0) continue;
    // The two normals into the cavity, (-t_z, t_r): q on the material's side of both.
    if (-dr * (ta[1] + tb[1]) + dz * (ta[0] + tb[0]) >= 0.0) continue;
    visit(j, -1.0, -dr / d, -dz / d, d);
  }
}

InnerSelfContact::PointCrossing InnerSelfContact::crossing_at(const Points& x, double r,
                                                              double z) const {
  prepare(x);
  PointCrossing c;
  crossings(x, std::numeric_limits<std::size_t>::max(), r, z,
            [&](std::size_t, double, double nr, double nz, double depth) {
              c.push_r += depth * nr;
              c.push_z += depth * nz;
              ++c.features;
            });
  return c;
}

double InnerSelfContact::add_forces(const Points& x, Points& f) const {
  const auto& in = body_->inner();
  deepest_ = 0.0;
  touching_ = 0;
  regions_ = 0;
  std::size_t last = 0;  // the last touching node, in the order of inner()
  double energy = 0.0;
  prepare(x);
  for (std::size_t a = 0; a < in.size(); ++a) {
    crossings(x, a, x.r[in[a]], x.z[in[a]],
              [&](std::size_t k, double xi, double nr, double nz, double depth) {
                const auto law = penalty(depth, smoothing_);
                const double push = k_ * area_[a] * law.force;  // along n on the node
                f.r[in[a]] += push * nr;
                f.z[in[a]] += push * nz;
                const auto L = lagrange(xi);
                for (int m = 0; m < 3; ++m) {
                  f.r[in[k + m]] -= push * L[m] * nr;
                  f.z[in[k + m]] -= push * L[m] * nz;
                }
                energy += k_ * area_[a] * law.energy;
                deepest_ = std::max(deepest_, depth);
                if (touching_ == 0 || a > last + kRegionGap) ++regions_;
                last = a;
                ++touching_;
              });
  }
  return energy;
}

}  // namespace snapjump::axi
