// The contacts of the 3D model. The container's face around the rim as an obstacle
// (core::ContainerFace), in both of the 3D model's phases: the finite elements alone
// (fem::ExplicitDriver) and the MPM grid (mpm::ContainerFaceRule). Checked against what a
// frictionless rigid wall must do: nothing crosses it, the tangential motion is kept, the momentum
// the wall takes is the container's, and the hole (the face inside s_min) stops nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/container_face.hpp"
#include "fem/body.hpp"
#include "fem/explicit.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/solid_mesher.hpp"
#include "mpm/stepper.hpp"

namespace snapjump {
namespace {

constexpr double kPhi = 80.0 * std::numbers::pi / 180.0;
constexpr double kR = 0.030, kH = 0.002;

const core::ContainerFace& face() {
  static const auto f = core::container_face(kR, kH, kPhi);
  return f;
}

// A 6 mm block whose top lies 0.5 mm below the face at r = 37-43 mm, over the acrylic (along
// about 41 mm against s_min = 29 mm); `r0` moves it along the axis x.
fem::Body block(double r0 = 0.040) {
  const double a = 0.006;
  const double top = -(r0 + a / 2) * face().cos_phi / face().sin_phi - 0.5e-3;
  return {mesh::make_box_mesh(r0 - a / 2, -a / 2, top - a, a, a, a, 0.003),
          fem::Material::from_young(1.2e6, 0.45, 1160.0)};
}

double deepest_gap(const mesh::Points& x, double dz) {
  double g = -1.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = std::hypot(x.x[i], x.y[i]);
    if (face().along(r, x.z[i], dz) >= face().s_min) g = std::max(g, face().gap(r, x.z[i], dz));
  }
  return g;
}

TEST(ContainerFace, GeometryOfTheCone) {
  const auto& f = face();
  // On the rim face's cone (polar angle phi about the centre) the gap is zero and "along" is the
  // distance from the centre.
  const double s = 0.035;
  const double r = s * std::sin(kPhi), z = -s * std::cos(kPhi);
  EXPECT_NEAR(f.gap(r, z, 0.0), 0.0, 1e-15);
  EXPECT_NEAR(f.along(r, z, 0.0), s, 1e-15);
  EXPECT_TRUE(f.inside(r + 1e-6, z, 0.0));
  EXPECT_FALSE(f.inside(r - 1e-6, z, 0.0));
  // Shifted with the container.
  EXPECT_NEAR(f.gap(r, z + 0.01, 0.01), 0.0, 1e-15);
  // Over the hole (s < R - h/2) nothing is rigid.
  const double sh = 0.9 * f.s_min;
  EXPECT_FALSE(f.inside(sh * std::sin(kPhi) + 1e-4, -sh * std::cos(kPhi), 0.0));
  // A step that would end 1 mm across ends on the face.
  EXPECT_NEAR(f.stop(r, z, f.nr(), f.nz(), 1e-3, 0.0), 1.0, 1e-12);
  EXPECT_EQ(f.stop(r, z, -f.nr(), -f.nz(), 1e-3, 0.0), 0.0);
}

// Finite elements alone: pushed up into the face (gravity reversed), the block stops on it (no
// node across by more than round-off) and slides down the frictionless incline at
// g cos(phi), the tangential part of the push.
TEST(ContainerFace, TheElementsStopOnItAndSlideFreely) {
  const auto b = block();
  fem::ExplicitOptions o;
  o.gravity = -50.0;  // 50 m/s^2 upwards
  o.tune_threads = false;
  o.container_face = face();
  fem::ExplicitDriver d(b, o);
  const double tx = std::sin(kPhi), tz = -std::cos(kPhi);  // the tangent at y = 0, along grows
  const auto tangential = [&] {
    const auto& v = d.velocities();
    double s = 0.0, m = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      s += b.mass()[i] * (v.x[i] * tx + v.z[i] * tz);
      m += b.mass()[i];
    }
    return s / m;
  };
  int contacts = 0;
  double worst = -1.0;
  d.run_until(0.01, [&](const fem::ExplicitDriver& e) {
    contacts = std::max(contacts, e.face_contacts());
    worst = std::max(worst, deepest_gap(e.positions(), 0.0));
  });
  EXPECT_GT(contacts, 0);
  EXPECT_LT(worst, 1e-12);
  const double t1 = d.time(), v1 = tangential();
  d.run_until(0.03);
  const double a = (tangential() - v1) / (d.time() - t1);
  // The push's tangential part: -50 ez . t = -50 cos(phi) (towards the hole, along falling).
  EXPECT_NEAR(a / (-50.0 * std::cos(kPhi)), 1.0, 0.05) << a;
  EXPECT_LT(deepest_gap(d.positions(), 0.0), 1e-12);
}

struct Thrown {
  double normal_before = 0, normal_after = 0, tangential_before = 0, tangential_after = 0;
  double pz_before = 0, pz_after = 0;  // the block's and the container's z momentum [kg m/s]
  long contacts = 0;
  double deepest = -1;
};

// The block thrown at the face on the grid, against a free container of mass M.
Thrown throw_at_face(double r0) {
  const auto b = block(r0);
  hybrid::BodyForces forces(b, 0.0);
  auto p = hybrid::particles_of(b);
  const double nx = face().nr(), nz = face().nz(), tx = face().sin_phi, tz = -face().cos_phi;
  const double vn = 0.5, vt = 0.2;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v.x[i] = vn * nx + vt * tx;
    p.v.z[i] = vn * nz + vt * tz;
  }
  const double dx = 1e-3;
  mpm::Stepper s(std::move(p), forces, {b.stable_time_step(0.3), dx, 0.5});
  core::RigidBody container;
  container.mass = 0.05;
  s.add_rule(
      std::make_unique<mpm::ClampRule>(container));  // no clamped particles: resets the force
  auto& rule = dynamic_cast<mpm::ContainerFaceRule&>(
      s.add_rule(std::make_unique<mpm::ContainerFaceRule>(container, face())));
  s.add_rigid_body(container);
  const auto means = [&](Thrown& t, bool before) {
    const auto& q = s.particles();
    double m = 0, n = 0, tg = 0, pz = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      m += q.mass[i];
      n += q.mass[i] * (q.v.x[i] * nx + (q.v.z[i] - container.vz) * nz);
      tg += q.mass[i] * (q.v.x[i] * tx + q.v.z[i] * tz);
      pz += q.mass[i] * q.v.z[i];
    }
    (before ? t.normal_before : t.normal_after) = n / m;
    (before ? t.tangential_before : t.tangential_after) = tg / m;
    (before ? t.pz_before : t.pz_after) = pz + container.mass * container.vz;
  };
  Thrown t;
  means(t, true);
  while (s.time() < 0.012) {
    rule.set_dz(container.z);  // the face moves with the container
    s.step();
    t.contacts = std::max(t.contacts, rule.contacts());
    t.deepest = std::max(t.deepest, deepest_gap(s.particles().x, container.z));
  }
  means(t, false);
  return t;
}

// On the grid: the block thrown at the face stops or rebounds (never on through it), keeps its
// tangential speed (frictionless), and the z momentum of block and container together is what it
// was: the face's impulse on the block is the container's.
TEST(ContainerFace, TheGridStopsABlockThrownAtItAndTheContainerTakesTheImpulse) {
  const auto t = throw_at_face(0.040);
  EXPECT_GT(t.contacts, 0);
  EXPECT_LT(t.normal_after, 0.1 * t.normal_before);  // stopped or bouncing back
  EXPECT_LT(t.deepest, 1e-3);                        // within one cell of the face
  EXPECT_NEAR(t.tangential_after, t.tangential_before, 0.03 * t.tangential_before);
  EXPECT_NEAR(t.pz_after, t.pz_before, 1e-3 * std::abs(t.pz_before));
}

// Over the hole (along below R - h/2) the face is not there: the same throw goes on unchanged.
TEST(ContainerFace, TheHoleStopsNothing) {
  const auto t = throw_at_face(0.012);
  EXPECT_EQ(t.contacts, 0);
  EXPECT_NEAR(t.normal_after, t.normal_before, 1e-9);
  EXPECT_NEAR(t.tangential_after, t.tangential_before, 1e-9);
}

// Where the shell meets itself on the grid: one velocity per node, so two parts of one body that
// come within a cell share it and cannot pass through each other. Two blocks of one body thrown
// at each other at 0.5 m/s: the momentum stays zero (no rule acts) and the gap between their
// facing surfaces never closes past zero.
TEST(GridSelfContact, TwoPartsOfOneBodyThrownAtEachOtherDoNotPassThrough) {
  const double a = 0.006, gap = 0.003;
  auto m = mesh::make_box_mesh(-gap / 2 - a, -a / 2, 0.0, a, a, a, 0.003);
  const auto right = mesh::make_box_mesh(gap / 2, -a / 2, 0.0, a, a, a, 0.003);
  const int offset = static_cast<int>(m.nodes.size());
  for (std::size_t i = 0; i < right.nodes.size(); ++i) {
    m.nodes.x.push_back(right.nodes.x[i]);
    m.nodes.y.push_back(right.nodes.y[i]);
    m.nodes.z.push_back(right.nodes.z[i]);
  }
  for (auto t : right.tets) {
    for (auto& k : t) k += offset;
    m.tets.push_back(t);
  }
  const fem::Body b(std::move(m), fem::Material::from_young(1.2e6, 0.45, 1160.0));
  hybrid::BodyForces forces(b, 0.0);
  auto p = hybrid::particles_of(b);
  const std::size_t n = p.size(), left_n = static_cast<std::size_t>(offset);
  for (std::size_t i = 0; i < n; ++i) p.v.x[i] = i < left_n ? 0.5 : -0.5;
  mpm::Stepper s(std::move(p), forces, {b.stable_time_step(0.3), 1e-3, 0.5});
  double closest = gap, worst_momentum = 0.0, scale = 0.0;
  while (s.time() < 0.01) {
    s.step();
    const auto& q = s.particles();
    double left_max = -1.0, right_min = 1.0, px = 0.0;
    scale = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (i < left_n) left_max = std::max(left_max, q.x.x[i]);
      if (i >= left_n) right_min = std::min(right_min, q.x.x[i]);
      px += q.mass[i] * q.v.x[i];
      scale += q.mass[i] * 0.5;
    }
    closest = std::min(closest, right_min - left_max);
    worst_momentum = std::max(worst_momentum, std::abs(px));
  }
  EXPECT_LT(closest, gap);  // they met
  EXPECT_GT(closest, 0.0);  // and did not pass through each other
  EXPECT_LT(worst_momentum, 1e-12 * scale);
}

}  // namespace
}  // namespace snapjump
