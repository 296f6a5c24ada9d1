// The seeded crease (axi::MeshSpec::crease_seeds_from_rim, crease_seed_depth): a rosette of four
// elements at one inner corner node, in a block that conforms to the structured mesh around it,
// and a notch there. Checked against the structured mesh (the same solid without a notch), a
// closed form for the notch's volume, the patch test and the closed crease of the crease fan's
// test.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "axi/body.hpp"
#include "axi/static_branch.hpp"
#include "fem/fold_check.hpp"
#include "mesh_checks.hpp"
#include "theory/scaling.hpp"

namespace snapjump::axi {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 0.025, kH = 0.002, kE = 1.2e6, kRho = 1160.0;
const double kPhi = 80.0 * kPi / 180.0;

MeshSpec spec(double from_rim, double depth, int through = 4, int along = 70) {
  MeshSpec s{kR, kH, kPhi, through, along};
  if (from_rim != 0.0) s.crease_seeds_from_rim = {from_rim};
  s.crease_seed_depth = depth;
  return s;
}

Body body(const MeshSpec& s) { return Body(s, fem::Material::from_young(kE, 0.45, kRho)); }

int elements_at(const Body& b, int node) {
  int count = 0;
  for (const auto& el : b.elements()) {
    for (int m : el) count += m == node ? 1 : 0;
  }
  return count;
}

TEST(CreaseSeed, WithoutANotchTheSolidAndItsSurfacesAreTheStructuredMeshs) {
  for (const auto& [through, along] : {std::pair{2, 35}, {4, 70}, {4, 140}}) {
    SCOPED_TRACE(testing::Message() << through << " x " << along);
    const auto plain = body(spec(0.0, 0.0, through, along));
    const auto seeded = body(spec(3.35e-3, 0.0, through, along));
    EXPECT_EQ(seeded.num_elements(), plain.num_elements() + 4);
    EXPECT_NEAR(seeded.reference_volume() / plain.reference_volume(), 1.0, 1e-12);
    EXPECT_NEAR(seeded.total_mass() / plain.total_mass(), 1.0, 1e-12);
    EXPECT_NEAR(seeded.cavity_volume(seeded.nodes()) / plain.cavity_volume(plain.nodes()), 1.0,
                1e-14);
    for (const auto set : {&Body::outer, &Body::inner, &Body::axis, &Body::rim}) {
      ASSERT_EQ((seeded.*set)().size(), (plain.*set)().size());
      for (std::size_t k = 0; k < (seeded.*set)().size(); ++k) {
        EXPECT_EQ(seeded.nodes().r[(seeded.*set)()[k]], plain.nodes().r[(plain.*set)()[k]]);
        EXPECT_EQ(seeded.nodes().z[(seeded.*set)()[k]], plain.nodes().z[(plain.*set)()[k]]);
      }
    }
    ASSERT_GE(seeded.crease_seed(), 0);
    EXPECT_EQ(elements_at(seeded, seeded.crease_seed()), 4);
    // The inner corner node nearest 3.35 mm from the rim.
    const double element = (kR - 0.5 * kH) * kPhi / along;
    EXPECT_LE(std::abs(seeded.from_rim(seeded.crease_seed()) - 3.35e-3), 0.5 * element + 1e-12);
    EXPECT_NO_THROW(seeded.check_folds(seeded.nodes()));
  }
}

// Two rosettes, as many as the block's width allows: the same solid, each root with its four
// kites, listed from the rim inwards; blocks that would overlap are refused.
TEST(CreaseSeed, TwoRosettesAreTheStructuredMeshsSolidWithFourElementsAtEachRoot) {
  for (const auto& [through, along] : {std::pair{4, 140}, {8, 140}}) {
    SCOPED_TRACE(testing::Message() << through << " x " << along);
    const auto plain = body(spec(0.0, 0.0, through, along));
    auto two = spec(3.35e-3, 0.0, through, along);
    two.crease_seeds_from_rim = {2.0e-3, 3.35e-3};
    const auto seeded = body(two);
    EXPECT_EQ(seeded.num_elements(), plain.num_elements() + 8);
    EXPECT_NEAR(seeded.reference_volume() / plain.reference_volume(), 1.0, 1e-12);
    EXPECT_NEAR(seeded.total_mass() / plain.total_mass(), 1.0, 1e-12);
    ASSERT_EQ(seeded.crease_seeds().size(), 2U);
    const double element = (kR - 0.5 * kH) * kPhi / along;
    EXPECT_LE(std::abs(seeded.from_rim(seeded.crease_seeds()[0]) - 2.0e-3), 0.5 * element + 1e-12);
    EXPECT_LE(std::abs(seeded.from_rim(seeded.crease_seeds()[1]) - 3.35e-3), 0.5 * element + 1e-12);
    for (const int root : seeded.crease_seeds()) EXPECT_EQ(elements_at(seeded, root), 4);
    EXPECT_NO_THROW(seeded.check_folds(seeded.nodes()));
  }
  auto overlapping = spec(3.35e-3, 0.0);  // 4 x 70: 0.5 mm elements, roots 3 elements apart
  overlapping.crease_seeds_from_rim = {3.35e-3, 1.9e-3};
  try {
    body(overlapping);
    ADD_FAILURE() << "overlapping rosettes were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("overlap"), std::string::npos) << e.what();
  }
}

// The notch moves the root by d into the solid while its neighbours on the surface stay: each of
// the two quadratic surface edges at the root, of length L, loses the area of its shape function
// at the root times d, integral of xi (xi - 1) / 2 over [-1, 1] times L / 2, that is d L / 6, and
// the ring 2 pi rho those areas (to first order in d and in L / R).
TEST(CreaseSeed, TheNotchTakesTheVolumeOfItsTwoQuadraticEdges) {
  for (int along : {70, 140}) {
    SCOPED_TRACE(along);
    const double d = 25e-6;
    const auto plain = body(spec(3.35e-3, 0.0, 4, along));
    const auto notched = body(spec(3.35e-3, d, 4, along));
    const int root = notched.crease_seed();
    const double rho = plain.nodes().r[root];
    const double L = (kR - 0.5 * kH) * kPhi / along;
    const double expected = 2.0 * kPi * rho * d * L / 3.0;
    EXPECT_NEAR((plain.reference_volume() - notched.reference_volume()) / expected, 1.0, 0.02);
    EXPECT_NEAR(std::hypot(notched.nodes().r[root], notched.nodes().z[root]) -
                    std::hypot(plain.nodes().r[root], plain.nodes().z[root]),
                d, 1e-12);
    EXPECT_NO_THROW(notched.check_folds(notched.nodes()));
  }
}

// A uniform dilatation's stress is uniform and isotropic, in equilibrium without body forces;
// the full 3 x 3 rule integrates it exactly on any 9-node quadrilateral. Flat, square and tall
// elements, with and without the notch.
TEST(CreaseSeed, ItsElementsPassThePatchTest) {
  for (const auto& [through, along] : {std::pair{2, 35}, {4, 70}, {4, 140}}) {
    for (double depth : {0.0, 25e-6}) {
      SCOPED_TRACE(testing::Message() << through << " x " << along << ", notch " << depth);
      auto s = spec(2e-3, depth, through, along);
      s.reduced_bulk = false;
      EXPECT_LT(mesh_checks::patch_test_residual(body(s)), 1e-9);
    }
  }
}

// The closed crease about the root (the closed form of test_crease_fan.cpp, det F = k > 0
// everywhere, k = 2 closing the crease), within 0.8 elements' sizes of the root and opening out
// to 2 (the larger of the element's length and depth; nearer, the closed form's rotation varies
// faster than the elements around the block can follow): the rosette holds it, on square and
// tall elements, and the structured mesh folds at the same node.
TEST(CreaseSeed, TheRosetteHoldsAClosedCrease) {
  for (const auto& [through, along] : {std::pair{2, 35}, {4, 70}, {4, 140}}) {
    SCOPED_TRACE(testing::Message() << through << " x " << along);
    const auto b = body(spec(3.35e-3, 25e-6, through, along));
    const auto plain = body(spec(0.0, 0.0, through, along));
    const double element = (kR - 0.5 * kH) * kPhi / along;
    const double size = std::max(element, kH / through), r1 = 0.8 * size, r2 = 2.0 * size;
    EXPECT_NO_THROW(b.check_folds(mesh_checks::close_crease(b, b.crease_seed(), 2.0, r1, r2)));
    // The same corner node of the structured mesh (the notch does not move the inner list).
    std::size_t k = 0;
    while (b.inner()[k] != b.crease_seed()) ++k;
    EXPECT_THROW(plain.check_folds(mesh_checks::close_crease(plain, plain.inner()[k], 2.0, r1, r2)),
                 fem::FoldedElement);
  }
}

// The rosette's cap at 4 x 140 buckles at a maximum so sharp that the secant of the step onto it
// lies more than the continuation's turn limit off the branch's tangent beyond it: no step from
// there is kept, however short, until that point is taken again with a shorter step. The
// buckling pressure is then the structured mesh's, to the per mille that separates 4 x 70 from
// 4 x 140 (the rosette sits 3.35 mm from the rim, where the unbuckled cap is hardly strained).
TEST(StaticBranch, TakesAPointAgainWhereItsStepTurnedPastTheLimit) {
  const auto trace = [](const Body& b) {
    BranchOptions o;
    o.p_ref = theory::zoelly_pressure(kE, kH, kR, 0.45);
    o.end_volume = 0.885;
    return trace_static_branch(b, o);
  };
  const auto plain = trace(body(spec(0.0, 0.0, 4, 70)));
  const auto seeded = trace(body(spec(3.35e-3, 25e-6, 4, 140)));
  ASSERT_TRUE(plain.reached_end) << plain.stop_reason;
  ASSERT_TRUE(seeded.reached_end) << seeded.stop_reason;
  EXPECT_NEAR(seeded.p_c / plain.p_c, 1.0, 1e-3);
}

TEST(CreaseSeed, IsRefusedWhereTheMeshCannotTakeIt) {
  auto with_fan = spec(2e-3, 0.0);
  with_fan.crease_fan_from_rim = 2e-3;
  EXPECT_THROW(body(with_fan), std::invalid_argument);
  auto with_layer = spec(2e-3, 0.0);
  with_layer.fan_layer = 1;
  EXPECT_THROW(body(with_layer), std::invalid_argument);
  EXPECT_THROW(body(spec(2e-3, 0.1 * kH)), std::invalid_argument);  // too deep
  EXPECT_THROW(body(spec(2e-3, -1e-6)), std::invalid_argument);
  EXPECT_THROW(body(spec(-2e-3, 0.0)), std::invalid_argument);
  EXPECT_THROW(body(spec(2e-3, 0.0, 1)), std::invalid_argument);      // one layer through h
  EXPECT_THROW(body(spec(2e-3, 0.0, 4, 3)), std::invalid_argument);   // three elements along
  EXPECT_THROW(body(spec(2e-3, 0.0, 4, 35)), std::invalid_argument);  // 1 mm long, 0.5 deep
  EXPECT_NO_THROW(body(spec(2e-3, 0.0, 2, 35)));
}

}  // namespace
}  // namespace snapjump::axi
