// The axisymmetric shell's contacts at the rim (axi/contact.hpp): the self-contact's forces are
// minus the gradient of its energy and push ring against ring (no z resultant), its gap is at
// least the one built in; the rim face's cone stops a point on the container's face, frictionless,
// and leaves the hole open.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "axi/body.hpp"
#include "axi/contact.hpp"
#include "axi/quadratic.hpp"

namespace snapjump::axi {
namespace {

constexpr double kR = 0.03, kH = 0.002;
const double kPhi = 80.0 * std::numbers::pi / 180.0;

Body make_body() {
  return Body({kR, kH, kPhi, 2, elements_along(kR, kH, kPhi, 2)},
              fem::Material::from_young(1.2e6, 0.45, 1160.0));
}

void check_self_contact_gradient(const Body& b, const Points& x, double depth, double smoothing);

// Inner node a put `depth` across the segment from inner node k (k, k + 1, k + 2) at xi = 0.3,
// along that segment's normal: a kink of the inner surface folded through itself.
void kink(const Body& b, Points& x, std::size_t k, std::size_t a, double depth) {
  const auto& in = b.inner();
  const double xi = 0.3;
  const auto L = lagrange(xi), dL = lagrange_d(xi);
  double cr = 0, cz = 0, tr = 0, tz = 0;
  for (int m = 0; m < 3; ++m) {
    cr += L[m] * x.r[in[k + m]];
    cz += L[m] * x.z[in[k + m]];
    tr += dL[m] * x.r[in[k + m]];
    tz += dL[m] * x.z[in[k + m]];
  }
  const double tn = std::hypot(tr, tz);
  // Into the material: minus the normal into the cavity, (-tz, tr) / |t|.
  x.r[in[a]] = cr + depth * tz / tn;
  x.z[in[a]] = cz - depth * tr / tn;
}

// An inner node put 0.1 mm across the next segment but one.
TEST(AxiContact, SelfContactForcesAreMinusTheGradientOfItsEnergyAndPushRingAgainstRing) {
  const Body b = make_body();
  auto x = b.nodes();
  const double depth = 1e-4;
  kink(b, x, 30, 33, depth);  // segment (in[30], in[31], in[32]); the node in[33]
  // The plain law, a smoothing length shorter than the crossing and one longer.
  for (const double smoothing : {0.0, 2e-5, 5e-4}) {
    SCOPED_TRACE(smoothing);
    check_self_contact_gradient(b, x, depth, smoothing);
  }
}

void check_self_contact_gradient(const Body& b, const Points& x, double depth, double smoothing) {
  const InnerSelfContact contact(b, default_contact_stiffness(b), smoothing);
  Points f{std::vector<double>(x.size(), 0.0), std::vector<double>(x.size(), 0.0)};
  const double energy = contact.add_forces(x, f);
  // The kink drags the nodes next to the moved one across too: at least the crossing built in.
  EXPECT_GE(contact.touching(), 1);
  EXPECT_GE(contact.deepest(), depth * (1.0 - 1e-9));
  double fz = 0.0, fmax = 0.0;
  for (std::size_t n = 0; n < f.size(); ++n) {
    fz += f.z[n];
    fmax = std::max(fmax, std::hypot(f.r[n], f.z[n]));
  }
  EXPECT_GT(fmax, 0.0);
  EXPECT_LT(std::abs(fz), 1e-12 * fmax);
  // Forces against central differences of the energy, at every node with a contact force.
  const auto energy_at = [&](Points y) {
    Points g{std::vector<double>(y.size(), 0.0), std::vector<double>(y.size(), 0.0)};
    return contact.add_forces(y, g);
  };
  EXPECT_GT(energy, 0.0);
  const double eps = 1e-9;
  int checked = 0;
  for (std::size_t node = 0; node < f.size(); ++node) {
    if (f.r[node] == 0.0 && f.z[node] == 0.0) continue;
    ++checked;
    for (const bool radial : {true, false}) {
      auto xp = x, xm = x;
      (radial ? xp.r : xp.z)[node] += eps;
      (radial ? xm.r : xm.z)[node] -= eps;
      const double fd = -(energy_at(xp) - energy_at(xm)) / (2.0 * eps);
      EXPECT_NEAR(fd, (radial ? f.r : f.z)[node], 1e-5 * fmax) << "node " << node;
    }
  }
  EXPECT_GE(checked, 4);  // the node and its segment's three at least
  // The undeformed shell touches nothing.
  Points g{std::vector<double>(x.size(), 0.0), std::vector<double>(x.size(), 0.0)};
  EXPECT_EQ(contact.add_forces(b.nodes(), g), 0.0);
  EXPECT_EQ(contact.touching(), 0);
}

// Two kinks far apart touch in two regions, as two closed creases do; one kink's touching nodes
// are one region however many of them cross.
TEST(AxiContact, CountsTheSeparateRegionsThatTouch) {
  const Body b = make_body();
  const InnerSelfContact contact(b, default_contact_stiffness(b));
  Points f{std::vector<double>(b.num_nodes(), 0.0), std::vector<double>(b.num_nodes(), 0.0)};
  auto x = b.nodes();
  contact.add_forces(x, f);
  EXPECT_EQ(contact.regions(), 0);
  kink(b, x, 30, 33, 1e-4);
  contact.add_forces(x, f);
  EXPECT_EQ(contact.regions(), 1);
  EXPECT_GE(contact.touching(), 1);
  kink(b, x, 4, 7, 1e-4);
  contact.add_forces(x, f);
  EXPECT_EQ(contact.regions(), 2);
}

// A point slid at a fixed depth under a corner of the inner surface (a segments' shared node moved
// off the surface, so that the surface turns there towards the material or away from it) crosses
// one feature of the surface at a time, neither both segments at once nor neither, so the push it
// feels changes smoothly. The nodes' forces use the same crossings.
TEST(AxiContact, APointSlidingPastACornerCrossesOneFeatureAtATime) {
  const Body b = make_body();
  const auto& in = b.inner();
  const InnerSelfContact contact(b, default_contact_stiffness(b));
  const std::size_t j = 40;                   // the corner in[j]
  for (const double lift : {+0.05, -0.05}) {  // into the cavity, into the material
    SCOPED_TRACE(lift);
    auto x = b.nodes();
    const double tr = x.r[in[j + 1]] - x.r[in[j - 1]], tz = x.z[in[j + 1]] - x.z[in[j - 1]];
    const double len = std::hypot(tr, tz);                         // about one segment
    const double ur = tr / len, uz = tz / len, nr = -uz, nz = ur;  // along; into the cavity
    x.r[in[j]] += lift * len * nr;
    x.z[in[j]] += lift * len * nz;
    const double depth = 0.02 * len;
    double before = -1.0, largest_change = 0.0;
    const int samples = 4000;
    for (int i = 0; i <= samples; ++i) {
      const double u = (static_cast<double>(i) / samples - 0.5) * 0.1 * len;
      const auto c = contact.crossing_at(x, x.r[in[j]] + u * ur - depth * nr,
                                         x.z[in[j]] + u * uz - depth * nz);
      ASSERT_EQ(c.features, 1) << "at " << u / len << " of a segment from the corner";
      const double size = std::hypot(c.push_r, c.push_z);
      if (before >= 0.0) largest_change = std::max(largest_change, std::abs(size - before));
      before = size;
    }
    // Over 4000 samples across a tenth of a segment (the corner's wedge is 0.3 rad wide): no step
    // of more than a hundredth of the push.
    EXPECT_LT(largest_change, 1e-2 * before);
  }
}

// The regularised law: the plain one (k A d, k A d^2 / 2) at no smoothing; with a smoothing length
// g0 the energy's derivative is the force and the force's is continuous (0 at first touch, 1 from
// g0 on), so a Newton solver sees no jump of the stiffness.
TEST(AxiContact, TheSmoothedPenaltyIsThePlainOneWithAContinuousStiffness) {
  for (const double d : {1e-9, 3e-6, 0.7}) {
    EXPECT_EQ(penalty(d, 0.0).force, d);
    EXPECT_DOUBLE_EQ(penalty(d, 0.0).energy, 0.5 * d * d);
  }
  const double g0 = 1e-6, e = 1e-12;
  const auto stiffness = [&](double d) {
    return (penalty(d + e, g0).force - penalty(d - e, g0).force) / (2.0 * e);
  };
  for (const double d : {0.1e-6, 0.5e-6, 0.99e-6, 1.01e-6, 2e-6, 1e-4}) {
    const double de = 1e-3 * std::min(d, std::abs(d - g0));
    const double slope = (penalty(d + de, g0).energy - penalty(d - de, g0).energy) / (2.0 * de);
    EXPECT_NEAR(slope, penalty(d, g0).force, 1e-6 * penalty(d, g0).force) << d;
  }
  EXPECT_NEAR(penalty(g0 * (1 - 1e-9), g0).force, penalty(g0 * (1 + 1e-9), g0).force, 1e-14);
  EXPECT_NEAR(penalty(g0 * (1 - 1e-9), g0).energy, penalty(g0 * (1 + 1e-9), g0).energy, 1e-20);
  EXPECT_NEAR(stiffness(g0 - 1e-10), 1.0, 1e-3);
  EXPECT_NEAR(stiffness(g0 + 1e-10), 1.0, 1e-3);
  EXPECT_NEAR(stiffness(2e-11), 0.0, 1e-4);
  // Past g0 the law is the plain one moved by g0 / 2.
  EXPECT_NEAR(penalty(5e-6, g0).force, 5e-6 - 0.5e-6, 1e-18);
}

// A point moving towards the container's face ends its step on it with its tangential velocity
// kept; over the hole, or moving away, it is left alone; the cone moves with the container.
TEST(AxiContact, TheRimConeStopsAPointOnItsFaceAndLeavesTheHoleOpen) {
  const RimCone cone = rim_cone(MeshSpec{kR, kH, kPhi, 2, 21});
  const double tr = std::sin(kPhi), tz = -std::cos(kPhi);  // along the face, outwards
  const double dt = 1e-6, dz = 0.004;
  for (const double s : {kR - 0.5 * kH, kR, kR + 0.01}) {
    // 1 um short of the face at s along it, moving 3 m/s into it and 2 m/s along it.
    const double r = s * tr - 1e-6 * cone.nr(), z = s * tz - 1e-6 * cone.nz() + dz;
    const double vr = 3.0 * cone.nr() + 2.0 * tr, vz = 3.0 * cone.nz() + 2.0 * tz;
    const double dv = cone.stop(r, z, vr, vz, dt, dz);
    EXPECT_NEAR(dv, 2.0, 1e-9) << "s = " << s;  // 3 m/s less the 1 m/s that closes the gap
    const double wr = vr - dv * cone.nr(), wz = vz - dv * cone.nz();
    EXPECT_NEAR(cone.gap(r + dt * wr, z + dt * wz, dz), 0.0, 1e-15);
    EXPECT_NEAR(wr * tr + wz * tz, 2.0, 1e-12);         // frictionless
    EXPECT_EQ(cone.stop(r, z, -vr, -vz, dt, dz), 0.0);  // moving away
  }
  // Over the hole (inside the clamped face's inner corner) the container is open.
  const double s = kR - kH;
  EXPECT_EQ(cone.stop(s * tr, s * tz + dz, 3.0 * cone.nr(), 3.0 * cone.nz(), dt, dz), 0.0);
  // The rim face's own nodes lie on the cone.
  const Body b = make_body();
  for (int a : b.rim()) {
    EXPECT_NEAR(cone.gap(b.nodes().r[a], b.nodes().z[a], 0.0), 0.0, 1e-15);
    EXPECT_GE(cone.along(b.nodes().r[a], b.nodes().z[a], 0.0), cone.s_min - 1e-15);
  }
}

}  // namespace
}  // namespace snapjump::axi
