// Seeded creases closing on square elements: the (25, 2.0) mm cap at 8 x 140 (rosettes 3.35 and
// 2.15 mm from the rim), where the first crease closes and stays closed while the second one
// starts and closes too, and the (25, 2.5) mm cap at 8 x 112 (rosettes 3.26 and 2.07 mm), whose
// closed branch leaves the touch with the volume rising. The continuation has to pass each touch,
// where the branch turns a corner from the crease open to the crease closed. About fifteen
// minutes each: label `long`.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <utility>
#include <vector>

#include "axi/body.hpp"
#include "axi/static_branch.hpp"
#include "theory/scaling.hpp"

namespace snapjump::axi {
namespace {

// The branch of the cap (R, h) on square elements (8 through h, `along` along), rosettes at
// `seeds` from the rim notched 12.5 um, traced to V / V0 = end_volume.
StaticBranch trace_seeded(double R, double h, int along, std::vector<double> seeds,
                          double end_volume) {
  constexpr double kE = 1.2e6;
  const Body body({.R = R,
                   .h = h,
                   .phi = 80.0 * std::numbers::pi / 180.0,
                   .through = 8,
                   .along = along,
                   .crease_seeds_from_rim = std::move(seeds),
                   .crease_seed_depth = 12.5e-6},
                  fem::Material::from_young(kE, 0.45, 1160.0));
  BranchOptions o;
  o.p_ref = theory::zoelly_pressure(kE, h, R, 0.45);
  o.end_volume = end_volume;
  return trace_static_branch(body, o);
}

bool closed(const BranchPoint& q) { return q.contact_regions >= 1; }

TEST(SeededCreases, BothCloseOneAfterTheOtherAsTheCapInverts) {
  const auto b = trace_seeded(0.025, 0.002, 140, {3.35e-3, 2.15e-3}, -0.70);
  ASSERT_FALSE(b.fold) << b.stop_reason;
  ASSERT_TRUE(b.reached_end) << b.stop_reason;
  const auto& p = b.points;
  const auto first = std::find_if(p.begin(), p.end(), closed);
  ASSERT_NE(first, p.end()) << "the first crease never closed";
  // From its touch on, the first crease stays closed (one region at least) to the end.
  EXPECT_TRUE(std::all_of(first, p.end(), closed));
  EXPECT_TRUE(std::any_of(first, p.end(), [](const BranchPoint& q) {
    return q.contact_regions == 2;
  })) << "the second crease never closed";
  EXPECT_LT(p.back().volume / b.V0, -0.70);
}

// The (25, 2.5) mm cap on square 0.3125 mm elements (8 x 112), rosettes 3.26 and 2.07 mm from the
// rim: the first crease deepens with the volume turning back, and its faces meet with the volume
// rising. A step with the volume falling from that touch finds only the open branch; the closed
// branch leaves it with the volume rising before it turns to fall, and the trace follows it.
TEST(SeededCreases, TheClosedBranchLeavesATouchTheWayTheVolumeWasMoving) {
  const auto b = trace_seeded(0.025, 0.0025, 112, {3.26e-3, 2.07e-3}, -0.55);
  ASSERT_FALSE(b.fold) << b.stop_reason;
  ASSERT_TRUE(b.reached_end) << b.stop_reason;
  const auto& p = b.points;
  const auto first = std::find_if(p.begin(), p.end(), closed);
  ASSERT_NE(first, p.end()) << "the first crease never closed";
  ASSERT_GT(first - p.begin(), 1);
  // It came to the touch with the volume rising, on the inverted side.
  EXPECT_LT(first->volume / b.V0, 0.0);
  EXPECT_GT(first->volume, (first - 1)->volume);
  EXPECT_TRUE(std::all_of(first, p.end(), closed));
  EXPECT_LT(p.back().volume / b.V0, -0.55);
}

}  // namespace
}  // namespace snapjump::axi
