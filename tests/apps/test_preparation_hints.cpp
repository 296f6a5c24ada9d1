// The hints after a preparation that ended the run name the cause the phase points to.
#include <gtest/gtest.h>

#include "app/preparation_hints.hpp"

namespace snapjump::app {
namespace {

// The coarse (30, 2.0) mm branch's suctions (docs/axisymmetric.md) over Zoelly's p_c.
popper::ReverseSnap default_branch() {
  popper::ReverseSnap b;
  b.p_c = 0.943 * 6896.0;
  b.p_minus = 0.2007 * 6896.0;
  b.p_hold = 0.2608 * 6896.0;
  return b;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(PreparationHints, BelowTheHoldingSuctionTheHintAsksForMoreSuction) {
  for (const bool on_plate : {false, true}) {
    const auto h = holding_hint(default_branch(), "", 6896.0, 0.1 * 6896.0, on_plate, 0.48);
    EXPECT_TRUE(has(h, "is below it: raise --delta-p-j")) << h;
  }
}

TEST(PreparationHints, AboveItASnapBackInTheAirIsTheDiscretisations) {
  const auto h = holding_hint(default_branch(), "", 6896.0, 0.5 * 6896.0, false, 0.48);
  EXPECT_TRUE(has(h, "the discretisation let the shell snap back")) << h;
}

TEST(PreparationHints, AboveItASnapBackOnThePlateIsTheNetWeights) {
  const auto h = holding_hint(default_branch(), "", 6896.0, 0.5 * 6896.0, true, 4.0);
  EXPECT_TRUE(has(h, "carrying the net weight of 4 N, it was pushed back")) << h;
  EXPECT_FALSE(has(h, "discretisation")) << h;
}

// A cap whose branch buckles within the preparation's suction and still did not invert: in 3D
// the discretisation (its ramp in time) kept it; one whose branch buckles beyond it needs more
// suction than the ramp gives. The axisymmetric run follows a branch of its own through its
// maximum wherever it lies, so whatever stopped it is what its preparation line names.
TEST(PreparationHints, ABucklingWithinTheSuctionPointsToWhatStoppedTheRun) {
  const auto three_d = buckling_hint(default_branch(), "", 6896.0, 1.4, false);
  EXPECT_TRUE(has(three_d, "the discretisation kept the shell from inverting")) << three_d;
  const auto beyond = buckling_hint(default_branch(), "", 6896.0, 0.9, false);
  EXPECT_TRUE(has(beyond, "beyond the preparation's suction")) << beyond;
  for (const double factor : {1.4, 0.9}) {
    const auto axi = buckling_hint(default_branch(), "", 6896.0, factor, true);
    EXPECT_TRUE(has(axi, "the run's own branch, on the run's mesh, stopped")) << axi;
    EXPECT_FALSE(has(axi, "discretisation")) << axi;
    EXPECT_FALSE(has(axi, "beyond")) << axi;
  }
}

TEST(PreparationHints, ABranchThatCouldNotBeComputedSaysWhy) {
  const auto h = holding_hint(std::nullopt, "no mesh", 6896.0, 3448.0, true, 0.48);
  EXPECT_TRUE(has(h, "could not be computed: no mesh")) << h;
}

}  // namespace
}  // namespace snapjump::app
