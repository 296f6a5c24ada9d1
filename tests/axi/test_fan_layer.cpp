// The fan layer (axi::MeshSpec::fan_layer): the same solid of revolution as the structured mesh,
// three elements at every inner corner node between the axis and the rim, elements that pass
// the patch test, and a crease closed at any of those nodes held without a fold (the closed form
// of the crease fan's test, about each root in turn).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "axi/body.hpp"
#include "fem/fold_check.hpp"
#include "mesh_checks.hpp"

namespace snapjump::axi {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 0.025, kH = 0.002, kE = 1.2e6, kRho = 1160.0;
const double kPhi = 80.0 * kPi / 180.0;

MeshSpec spec(int layer, int through = 4, int along = 70) {
  MeshSpec s{kR, kH, kPhi, through, along};
  s.fan_layer = layer;
  return s;
}

Body body(const MeshSpec& s) { return Body(s, fem::Material::from_young(kE, 0.45, kRho)); }

std::vector<int> elements_at(const Body& b) {
  std::vector<int> count(b.num_nodes(), 0);
  for (const auto& el : b.elements()) {
    for (int m : el) ++count[m];
  }
  return count;
}

TEST(FanLayer, TheSolidAndItsSurfacesAreTheStructuredMeshs) {
  for (const auto& [depth, along] : {std::pair{1, 35}, {1, 140}, {2, 35}, {2, 140}}) {
    SCOPED_TRACE(testing::Message() << depth << " x " << along);
    const auto plain = body(spec(0, 4, along));
    const auto layer = body(spec(depth, 4, along));
    // Per column three elements for `depth`, less the diamond the axis's column has none of.
    EXPECT_EQ(layer.num_elements(), plain.num_elements() + (3 - depth) * along - 1);
    EXPECT_NEAR(layer.reference_volume() / plain.reference_volume(), 1.0, 1e-12);
    EXPECT_NEAR(layer.total_mass() / plain.total_mass(), 1.0, 1e-12);
    EXPECT_NEAR(layer.cavity_volume(layer.nodes()) / plain.cavity_volume(plain.nodes()), 1.0,
                1e-14);
    for (double m : layer.mass()) EXPECT_GT(m, 0.0);
    // The surfaces are the lattice's; with one layer the axis and the rim face gain two nodes
    // each, where the layer's end splits the edge; with two the edge's ends are lattice nodes.
    for (const auto set : {&Body::outer, &Body::inner}) {
      ASSERT_EQ((layer.*set)().size(), (plain.*set)().size());
      for (std::size_t k = 0; k < (layer.*set)().size(); ++k) {
        EXPECT_EQ(layer.nodes().r[(layer.*set)()[k]], plain.nodes().r[(plain.*set)()[k]]);
        EXPECT_EQ(layer.nodes().z[(layer.*set)()[k]], plain.nodes().z[(plain.*set)()[k]]);
      }
    }
    ASSERT_EQ(layer.axis().size(), plain.axis().size() + (depth == 1 ? 2 : 0));
    ASSERT_EQ(layer.rim().size(), plain.rim().size() + (depth == 1 ? 2 : 0));
    for (int a : layer.axis()) EXPECT_EQ(layer.nodes().r[a], 0.0);
    const auto& rim0 = plain.nodes();
    const double rim_angle = std::atan2(rim0.r[plain.rim()[0]], -rim0.z[plain.rim()[0]]);
    for (int a : layer.rim()) {
      EXPECT_NEAR(std::atan2(layer.nodes().r[a], -layer.nodes().z[a]), rim_angle, 1e-12);
    }
    const auto count = elements_at(layer);
    const auto& in = layer.inner();
    for (std::size_t k = 2; k + 2 < in.size(); k += 2) EXPECT_EQ(count[in[k]], 3) << k;
    EXPECT_NO_THROW(layer.check_folds(layer.nodes()));
  }
}

// A uniform dilatation's stress is uniform and isotropic, in equilibrium without body forces, so
// no node inside the body carries a force; the full 3 x 3 rule integrates it exactly on any
// 9-node quadrilateral. Flat, square and tall elements give the layer three shapes.
TEST(FanLayer, ItsElementsPassThePatchTest) {
  for (const auto& [depth, along] : {std::pair{1, 35}, {1, 70}, {1, 140}, {2, 35}, {2, 140}}) {
    SCOPED_TRACE(testing::Message() << depth << " x " << along);
    auto s = spec(depth, 4, along);
    s.reduced_bulk = false;
    const auto b = body(s);
    EXPECT_LT(mesh_checks::patch_test_residual(b), 1e-9);
  }
}

// Every inner corner node from 0.5 to 4 mm from the rim, on square (4 x 70) and tall (4 x 140)
// elements, holds the closed crease; the structured mesh folds at a smaller closing (its test
// in test_crease_fan.cpp).
TEST(FanLayer, HoldsACreaseClosedAtEveryInnerCornerNode) {
  for (const auto& [depth, along] : {std::pair{1, 70}, {1, 140}, {2, 35}, {2, 70}}) {
    SCOPED_TRACE(testing::Message() << depth << " x " << along);
    const auto b = body(spec(depth, 4, along));
    const double element = (kR - 0.5 * kH) * kPhi / along;
    // Closing within 0.4 elements of the root, opening out to 2, the element's larger side
    // (0.5 mm per layer through h here): the nodes sample the closed form, whose shear grows with
    // the slope of the closing, at that spacing.
    const double size = std::max(element, depth * kH / 4), r1 = 0.4 * size, r2 = 2.0 * size;
    const auto& in = b.inner();
    int roots = 0;
    for (std::size_t k = 2; k + 2 < in.size(); k += 2) {
      const double from_rim = element * static_cast<double>(in.size() - 1 - k) / 2.0;
      if (from_rim < 0.5e-3 || from_rim > 4e-3) continue;
      ++roots;
      EXPECT_NO_THROW(b.check_folds(mesh_checks::close_crease(b, in[k], 2.0, r1, r2))) << from_rim;
    }
    EXPECT_GE(roots, static_cast<int>(3.5e-3 / element) - 1);
  }
  // The structured mesh does not hold it.
  const auto plain = body(spec(0, 4, 70));
  const double element = (kR - 0.5 * kH) * kPhi / 70;
  EXPECT_THROW(plain.check_folds(mesh_checks::close_crease(plain, plain.inner()[130], 2.0,
                                                           0.4 * element, 2.0 * element)),
               fem::FoldedElement);
}

TEST(FanLayer, IsRefusedWithACreaseFanOrDeeperThanTwoLayersOrTheMesh) {
  auto s = spec(1);
  s.crease_fan_from_rim = 1.5e-3;
  EXPECT_THROW(body(s), std::invalid_argument);
  EXPECT_THROW(body(spec(3)), std::invalid_argument);
  EXPECT_THROW(body(spec(-1)), std::invalid_argument);
  EXPECT_THROW(body(spec(2, 1)), std::invalid_argument);
  EXPECT_NO_THROW(body(spec(1, 1)));
}

}  // namespace
}  // namespace snapjump::axi
