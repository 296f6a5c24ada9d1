// The graded cap (mesh::CapSpec's rim and contact zones): the triangles of its inner surface have
// the sizes asked for in each zone and the uniform size between, the mesh is a valid shell of the
// right volume, and a graded mesh leaves the next uniform one untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "fem/body.hpp"
#include "mesh/cap_mesher.hpp"

namespace snapjump::mesh {
namespace {

constexpr double kR = 0.030, kH = 0.002;
const double kPhi = 80.0 * std::numbers::pi / 180.0;

// Mean corner-edge length of the inner faces whose centroid lies at arc length [from, to) from
// the apex (on the mid-surface).
double mean_edge(const Mesh& m, double from, double to) {
  double sum = 0.0;
  int n = 0;
  for (const auto& f : m.inner_faces) {
    double c[3] = {}, len = 0.0;
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      c[0] += m.nodes.x[a] / 3;
      c[1] += m.nodes.y[a] / 3;
      c[2] += m.nodes.z[a] / 3;
      len += std::hypot(m.nodes.x[a] - m.nodes.x[b], m.nodes.y[a] - m.nodes.y[b],
                        m.nodes.z[a] - m.nodes.z[b]) /
             3;
    }
    const double arc = kR * std::acos(-c[2] / std::hypot(c[0], c[1], c[2]));
    if (arc >= from && arc < to) {
      sum += len;
      ++n;
    }
  }
  EXPECT_GT(n, 5) << "zone " << from << " to " << to;
  // Edges of the inner surface, radius R - h/2: scale to the mid-surface.
  return n > 0 ? sum / n * kR / (kR - kH / 2) : 0.0;
}

CapSpec graded() {
  return {.R = kR,
          .h = kH,
          .phi = kPhi,
          .element_size = 0.005,
          .layers = 1,
          .rim_size = 0.001,
          .rim_band = 0.004,
          .contact_size = 0.002,
          .contact_band = 0.012};
}

TEST(GradedCap, EachZoneHasTheSizeAskedFor) {
  const auto s = graded();
  const Mesh m = make_cap_mesh(s);
  const double arc = kR * kPhi;  // 41.9 mm
  // Inside the zones (off their edges by a size), and where neither zone reaches: growth from
  // the contact zone reaches 5 mm at 12 + 3 / 0.3 = 22 mm, from the rim at 4 + 4 / 0.3 = 17.3 mm
  // from the rim, so 22 to 24 mm is uniform.
  const double rim = mean_edge(m, arc - 0.003, arc), contact = mean_edge(m, 0.0, 0.010),
               between = mean_edge(m, 0.022, 0.0245);
  std::printf("mean edge: rim zone %.3f mm, contact zone %.3f mm, between %.3f mm\n", 1e3 * rim,
              1e3 * contact, 1e3 * between);
  EXPECT_NEAR(rim, 0.001, 0.25 * 0.001);
  EXPECT_NEAR(contact, 0.002, 0.25 * 0.002);
  EXPECT_NEAR(between, 0.005, 0.25 * 0.005);
  EXPECT_NEAR(cap_element_size(s, 0.0), 0.002, 1e-15);
  EXPECT_NEAR(cap_element_size(s, 0.017), 0.002 + 0.3 * 0.005, 1e-12);
  EXPECT_NEAR(cap_element_size(s, arc - 0.002), 0.001, 1e-15);
  EXPECT_EQ(cap_element_size(s, 0.023), 0.005);
}

TEST(GradedCap, IsAValidShellOfTheCapsVolumeAndFinerThanTheUniformOne) {
  const auto s = graded();
  const Mesh m = make_cap_mesh(s);  // make_cap_mesh checks elements and the shell's sets
  auto u = s;
  u.rim_size = u.contact_size = 0.0;
  const Mesh uniform = make_cap_mesh(u);
  EXPECT_GT(m.tets.size(), 2 * uniform.tets.size());
  // (2 pi / 3)((R + h/2)^3 - (R - h/2)^3)(1 - cos phi): the shell segment.
  const double exact = 2.0 * std::numbers::pi / 3.0 *
                       (std::pow(kR + kH / 2, 3) - std::pow(kR - kH / 2, 3)) *
                       (1.0 - std::cos(kPhi));
  const fem::Body body(m, fem::Material::from_young(1.2e6, 0.45, 1160.0));
  EXPECT_NEAR(body.reference_volume() / exact, 1.0, 1e-3);
}

TEST(GradedCap, LeavesTheNextUniformMeshAsItWas) {
  auto u = graded();
  u.rim_size = u.contact_size = 0.0;
  const Mesh before = make_cap_mesh(u);
  (void)make_cap_mesh(graded());
  const Mesh after = make_cap_mesh(u);
  ASSERT_EQ(before.nodes.size(), after.nodes.size());
  for (std::size_t a = 0; a < before.nodes.size(); ++a) {
    ASSERT_EQ(before.nodes.x[a], after.nodes.x[a]);
    ASSERT_EQ(before.nodes.z[a], after.nodes.z[a]);
  }
}

TEST(GradedCap, RefusesSizesItCannotMesh) {
  auto s = graded();
  s.rim_size = 1e-5;  // below h / 10
  EXPECT_THROW((void)make_cap_mesh(s), MeshError);
  s = graded();
  s.contact_band = std::nan("");
  EXPECT_THROW((void)make_cap_mesh(s), MeshError);
  s = graded();
  s.rim_band = -1.0;
  EXPECT_THROW((void)make_cap_mesh(s), MeshError);
}

}  // namespace
}  // namespace snapjump::mesh

namespace snapjump::mesh {
namespace {

// The elastic time step against the linear stability limit 2 / omega_max of the free cap, on
// uniform and graded meshes of the default popper: printed (docs/performance.md, "The time step
// of a graded cap"), and the limit is above the step on the uniform default cap.
TEST(GradedCap, StepAgainstTheStabilityLimit) {
  const auto material = fem::Material::from_young(1.2e6, 0.45, 1160.0);
  auto uniform = graded();
  uniform.element_size = 0.00387;
  uniform.rim_size = uniform.contact_size = 0.0;
  auto g = graded();
  g.element_size = 0.00387;
  for (const auto& [name, spec] : {std::pair{"uniform 3.87 mm", uniform}, {"graded", g}}) {
    const fem::Body body(make_cap_mesh(spec), material);
    const double limit = 2.0 / body.highest_frequency();
    const double step = body.stable_time_step(1.0);
    std::printf("%s: 2 / omega_max = %.4g us = %.3f x spacing / c_p\n", name, 1e6 * limit,
                limit / step);
    if (std::string(name) == "uniform 3.87 mm") {
      EXPECT_GT(limit, 0.5 * step);
    }
  }
}

}  // namespace
}  // namespace snapjump::mesh
