// The crease fan (axi::MeshSpec::crease_fan_from_rim): the same solid of revolution as the
// structured mesh, elements that pass the patch test, three elements at the root, and a closed
// form of a closing crease (the angle about the root scaled, det F = the scale everywhere) that
// the fan holds without a fold where the structured mesh folds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "axi/body.hpp"
#include "fem/fold_check.hpp"
#include "mesh_checks.hpp"

namespace snapjump::axi {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 0.025, kH = 0.002, kE = 1.2e6, kRho = 1160.0;
const double kPhi = 80.0 * kPi / 180.0;

MeshSpec spec(double fan, int through = 4, int along = 70) {
  MeshSpec s{kR, kH, kPhi, through, along};
  s.crease_fan_from_rim = fan;
  return s;
}

Body body(const MeshSpec& s) { return Body(s, fem::Material::from_young(kE, 0.45, kRho)); }

TEST(CreaseFan, TheSolidAndItsSurfacesAreTheStructuredMeshs) {
  const auto plain = body(spec(0.0));
  const auto fan = body(spec(1.5e-3));
  ASSERT_GE(fan.crease_root(), 0);
  EXPECT_EQ(plain.crease_root(), -1);
  // The node nearest 1.5 mm of 0.4986 mm elements: 3 elements, 1.496 mm.
  EXPECT_NEAR(fan.crease_root_from_rim(), 3 * (kR - 0.5 * kH) * kPhi / 70, 1e-12);
  EXPECT_TRUE(std::isnan(plain.crease_root_from_rim()));
  EXPECT_EQ(fan.num_elements(), plain.num_elements() + 1);
  // Nine lattice nodes inside the block dropped; two corners, six inner edges' middles and five
  // centres added.
  EXPECT_EQ(fan.num_nodes(), plain.num_nodes() - 9 + 2 + 6 + 5);
  EXPECT_NEAR(fan.reference_volume() / plain.reference_volume(), 1.0, 1e-12);
  EXPECT_NEAR(fan.total_mass() / plain.total_mass(), 1.0, 1e-12);
  EXPECT_NEAR(fan.cavity_volume(fan.nodes()) / plain.cavity_volume(plain.nodes()), 1.0, 1e-14);
  for (double m : fan.mass()) EXPECT_GT(m, 0.0);
  // The node sets hold the same places.
  for (const auto set : {&Body::axis, &Body::rim, &Body::outer, &Body::inner}) {
    ASSERT_EQ((fan.*set)().size(), (plain.*set)().size());
    for (std::size_t k = 0; k < (fan.*set)().size(); ++k) {
      EXPECT_EQ(fan.nodes().r[(fan.*set)()[k]], plain.nodes().r[(plain.*set)()[k]]);
      EXPECT_EQ(fan.nodes().z[(fan.*set)()[k]], plain.nodes().z[(plain.*set)()[k]]);
    }
  }
  int at_root = 0;
  for (const auto& el : fan.elements()) {
    at_root += static_cast<int>(std::count(el.begin(), el.end(), fan.crease_root()));
  }
  EXPECT_EQ(at_root, 3);
  EXPECT_NO_THROW(fan.check_folds(fan.nodes()));
}

// A band of roots: every second corner node within half the band on either side of the one
// nearest crease_fan_from_rim, each with its own block and three elements at its root.
TEST(CreaseFan, ABandHasARootAtEverySecondNodeWithinIt) {
  const auto plain = body(spec(0.0, 4, 140));
  auto s = spec(1.5e-3, 4, 140);
  s.crease_fan_band = 1.5e-3;
  const auto band = body(s);
  // 0.2393 mm between corner nodes on the inner surface: roots at 1.44 mm and 0.479 mm on either
  // side of it (0.96 to 1.92 mm from the rim), the next (0.48 or 2.40 mm) outside the band.
  const double step = (kR - 0.5 * kH) * kPhi / 140;
  EXPECT_NEAR(band.crease_root_from_rim(), 6 * step, 1e-12);
  EXPECT_EQ(band.crease_fans(), 3);
  EXPECT_EQ(band.num_elements(), plain.num_elements() + 3);
  EXPECT_EQ(band.num_nodes(), plain.num_nodes() + 3 * 4);
  EXPECT_NEAR(band.reference_volume() / plain.reference_volume(), 1.0, 1e-12);
  std::vector<int> elements_at(band.num_nodes(), 0);
  for (const auto& el : band.elements()) {
    for (int m : el) ++elements_at[m];
  }
  int roots = 0;
  for (int a : band.inner()) roots += elements_at[a] == 3 ? 1 : 0;
  EXPECT_EQ(roots, 3);
  EXPECT_NO_THROW(band.check_folds(band.nodes()));
}

// A uniform dilatation's stress is uniform and isotropic, in equilibrium without body forces, so
// no node inside the body carries a force; the full 3 x 3 rule integrates it exactly on any
// 9-node quadrilateral. Flat, square and tall elements give the fan three different shapes.
TEST(CreaseFan, ItsElementsPassThePatchTest) {
  for (const int along : {35, 70, 140}) {
    SCOPED_TRACE(along);
    auto s = spec(1.5e-3, 4, along);
    s.reduced_bulk = false;
    const auto b = body(s);
    EXPECT_LT(mesh_checks::patch_test_residual(b), 1e-9);
  }
}

TEST(CreaseFan, HoldsACreaseClosedToWhereTwoElementsFold) {
  const auto plain = body(spec(0.0));
  const auto fan = body(spec(1.5e-3));
  // The structured mesh's node at the same place.
  int root = -1;
  for (int a : plain.inner()) {
    if (plain.nodes().r[a] == fan.nodes().r[fan.crease_root()] &&
        plain.nodes().z[a] == fan.nodes().z[fan.crease_root()]) {
      root = a;
    }
  }
  ASSERT_GE(root, 0);
  // Closing within 0.2 mm of the root (the elements are 0.5 mm), opening out to 0.6 mm.
  const double r1 = 0.2e-3, r2 = 0.6e-3;
  EXPECT_NO_THROW(plain.check_folds(mesh_checks::close_crease(plain, root, 1.7, r1, r2)));
  EXPECT_NO_THROW(fan.check_folds(mesh_checks::close_crease(fan, fan.crease_root(), 1.7, r1, r2)));
  // The surface turned through 144 degrees: the structured elements' corners at the root
  // (162 degrees each) fold them between their nodes.
  EXPECT_THROW(plain.check_folds(mesh_checks::close_crease(plain, root, 1.8, r1, r2)),
               fem::FoldedElement);
  // Closed, the surface turned through 180 degrees.
  EXPECT_NO_THROW(fan.check_folds(mesh_checks::close_crease(fan, fan.crease_root(), 2.0, r1, r2)));
}

TEST(CreaseFan, ANodeItCannotUseIsRefused) {
  EXPECT_THROW(body(spec(1.5e-3, 1)), std::invalid_argument);  // one element through h
  EXPECT_THROW(body(spec(-1e-3)), std::invalid_argument);
  EXPECT_THROW(body(spec(std::nan(""))), std::invalid_argument);
  auto s = spec(1.5e-3);
  s.crease_fan_band = -1e-3;
  EXPECT_THROW(body(s), std::invalid_argument);
}

}  // namespace
}  // namespace snapjump::axi
