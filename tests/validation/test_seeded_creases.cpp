// Two seeded creases on the (25, 2.0) mm cap, square 0.25 mm elements (8 x 140), rosettes 3.35 and
// 2.15 mm from the rim: as the cap inverts further, the first crease closes and stays closed
// while the second one starts and closes too. The continuation has to pass each touch, where the
// branch turns a corner from the crease open (the volume rising as it deepens) to the crease
// closed (the volume falling again). About ten minutes each: label `long`.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "axi/body.hpp"
#include "axi/static_branch.hpp"
#include "theory/scaling.hpp"

namespace snapjump::axi {
namespace {

TEST(SeededCreases, BothCloseOneAfterTheOtherAsTheCapInverts) {
  constexpr double kE = 1.2e6, kR = 0.025, kH = 0.002;
  const Body body({.R = kR,
                   .h = kH,
                   .phi = 80.0 * std::numbers::pi / 180.0,
                   .through = 8,
                   .along = 140,
                   .crease_seeds_from_rim = {3.35e-3, 2.15e-3},
                   .crease_seed_depth = 12.5e-6},
                  fem::Material::from_young(kE, 0.45, 1160.0));
  BranchOptions o;
  o.p_ref = theory::zoelly_pressure(kE, kH, kR, 0.45);
  o.end_volume = -0.70;
  const auto b = trace_static_branch(body, o);
  ASSERT_FALSE(b.fold) << b.stop_reason;
  ASSERT_TRUE(b.reached_end) << b.stop_reason;
  const auto& p = b.points;
  const auto first =
      std::find_if(p.begin(), p.end(), [](const BranchPoint& q) { return q.contact_regions == 1; });
  ASSERT_NE(first, p.end()) << "the first crease never closed";
  // From its touch on, the first crease stays closed (one region at least) to the end.
  EXPECT_TRUE(
      std::all_of(first, p.end(), [](const BranchPoint& q) { return q.contact_regions >= 1; }));
  EXPECT_TRUE(std::any_of(first, p.end(), [](const BranchPoint& q) {
    return q.contact_regions == 2;
  })) << "the second crease never closed";
  EXPECT_LT(p.back().volume / b.V0, -0.70);
}

// The (25, 2.5) mm cap on square 0.3125 mm elements (8 x 112), rosettes 3.26 and 2.07 mm from the
// rim: the first crease deepens with the volume turning back, and its faces meet with the volume
// rising. The closed branch leaves that touch the way the volume was moving before it turns to
// fall; a first step with the volume falling finds only the open branch, and the trace stopped
// at the touch.
TEST(SeededCreases, TheClosedBranchLeavesATouchTheWayTheVolumeWasMoving) {
  constexpr double kE = 1.2e6, kR = 0.025, kH = 0.0025;
  const Body body({.R = kR,
                   .h = kH,
                   .phi = 80.0 * std::numbers::pi / 180.0,
                   .through = 8,
                   .along = 112,
                   .crease_seeds_from_rim = {3.26e-3, 2.07e-3},
                   .crease_seed_depth = 12.5e-6},
                  fem::Material::from_young(kE, 0.45, 1160.0));
  BranchOptions o;
  o.p_ref = theory::zoelly_pressure(kE, kH, kR, 0.45);
  o.end_volume = -0.55;
  const auto b = trace_static_branch(body, o);
  ASSERT_FALSE(b.fold) << b.stop_reason;
  ASSERT_TRUE(b.reached_end) << b.stop_reason;
  const auto& p = b.points;
  const auto first =
      std::find_if(p.begin(), p.end(), [](const BranchPoint& q) { return q.contact_regions == 1; });
  ASSERT_NE(first, p.end()) << "the first crease never closed";
  ASSERT_GT(first - p.begin(), 1);
  // It came to the touch with the volume rising, on the inverted side.
  EXPECT_LT(first->volume / b.V0, 0.0);
  EXPECT_GT(first->volume, (first - 1)->volume);
  EXPECT_TRUE(
      std::all_of(first, p.end(), [](const BranchPoint& q) { return q.contact_regions >= 1; }));
  EXPECT_LT(p.back().volume / b.V0, -0.55);
}

}  // namespace
}  // namespace snapjump::axi
