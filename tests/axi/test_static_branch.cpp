// The clamped cap's quasi-static pressure-volume branch (axi/static_branch.hpp), on the coarse
// (30, 2.0) mm cap, against laws the continuation itself does not use:
// - the work of the pressure along the branch is the strain energy it stores (the load is
//   conservative and the rim fixed: dW = -dp dV along any path of equilibria);
// - under pressure control the segment between the buckling maximum and the minimum that follows
//   is unstable (there dV/dp > 0) and the segments where the volume falls as the suction rises are
//   stable, which the factorisation of the stiffness at fixed dp must agree with;
// - the equilibrium asked at a given suction on the inverted segment lies at that suction, and
//   one asked below that segment's lowest suction is refused for the segment's foot;
// - p_c moves by less than 0.5 % when the mesh is refined twice along the meridian;
// - the thin-shell theory's branch (theory/shell_branch.hpp, no code shared) has the same p_-
//   within 2 %, and a p_c that differs by less than h / R, the order of the thickness' effects
//   that thin-shell theory leaves out.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "axi/body.hpp"
#include "axi/static_branch.hpp"
#include "theory/shell_branch.hpp"

namespace snapjump::axi {
namespace {

constexpr double kR = 0.03, kH = 0.002, kE = 1.2e6, kNu = 0.45;
const double kPhi = 80.0 * std::numbers::pi / 180.0;
// Zoelly's pressure of the (30, 2.0) mm shell, only a scale here.
const double kPref = 2.0 * kE * kH * kH / (kR * kR * std::sqrt(3.0 * (1.0 - kNu * kNu)));

Body make_body(int along) {
  return Body({kR, kH, kPhi, 2, along}, fem::Material::from_young(kE, kNu, 1160.0));
}

BranchOptions options(double end_volume) {
  BranchOptions o;
  o.p_ref = kPref;
  o.end_volume = end_volume;
  return o;
}

TEST(StaticBranch, PressureWorkEqualsStoredEnergyAndTheExtremaAreOrdered) {
  const Body body = make_body(21);
  double work = 0.0;
  BranchPoint last{body.cavity_volume(body.nodes()), 0.0, 0.0, 0, 0.0};
  auto o = options(-1.0);
  o.progress = [&](const BranchPoint& p) {
    work -= 0.5 * (p.dp + last.dp) * (p.volume - last.volume);
    last = p;
  };
  const auto b = trace_static_branch(body, o);
  ASSERT_TRUE(b.reached_end) << b.stop_reason;
  const double W = body.strain_energy(b.state);
  std::printf("%zu points: work of the pressure %.6e J, strain energy %.6e J (%.3f %%)\n",
              b.points.size(), work, W, 100.0 * (work / W - 1.0));
  std::printf("p_c = %.5f, p_- = %.5f, p_hold = %.5f (over Zoelly's p_c)\n", b.p_c / kPref,
              b.p_minus / kPref, b.p_hold / kPref);
  EXPECT_NEAR(work / W, 1.0, 2e-3);
  EXPECT_GT(b.p_c, b.p_hold);
  EXPECT_GE(b.p_hold, b.p_minus);
  EXPECT_LT(b.v_c, 1.0);
  EXPECT_GT(b.v_c, b.v_minus);
  EXPECT_GT(b.v_minus, b.v_hold);
  EXPECT_TRUE(b.stable);  // the inverted end: the volume falls as the suction rises
}

TEST(StaticBranch, StabilityUnderPressureControlFollowsTheSlopeOfTheBranch) {
  const Body body = make_body(21);
  const auto falling = trace_static_branch(body, options(0.8));  // between p_c and p_-
  ASSERT_TRUE(falling.reached_end) << falling.stop_reason;
  const auto& p = falling.points;
  EXPECT_LT(p.back().dp, p[p.size() - 2].dp);  // dp falls as V falls: dV/dp > 0
  EXPECT_FALSE(falling.stable);
  const auto rising = trace_static_branch(body, options(0.95));  // before buckling
  ASSERT_TRUE(rising.reached_end) << rising.stop_reason;
  EXPECT_TRUE(rising.stable);
}

TEST(StaticBranch, EndsAtTheSuctionAskedOnTheInvertedSegment) {
  const Body body = make_body(21);
  auto o = options(-3.0);
  o.end_dp = 1.4 * kPref;
  const auto b = trace_static_branch(body, o);
  ASSERT_TRUE(b.reached_end) << b.stop_reason;
  EXPECT_NEAR(b.points.back().dp / o.end_dp, 1.0, 1e-9);
  EXPECT_LT(body.cavity_volume(b.state), -body.cavity_volume(body.nodes()) * 0.9);
  EXPECT_TRUE(b.stable);
  EXPECT_NO_THROW(body.check_folds(b.state));
}

// Asked for a suction below the inverted segment's lowest one (p_hold, 0.26 of Zoelly's here),
// the branch holds no inverted equilibrium there: it stops at the segment's foot, just above
// p_hold, and says so, instead of taking an equilibrium of another segment.
TEST(StaticBranch, BelowTheInvertedSegmentItStopsAtItsFoot) {
  const Body body = make_body(21);
  auto o = options(-3.0);
  o.end_dp = 0.1 * kPref;
  const auto b = trace_static_branch(body, o);
  ASSERT_TRUE(b.reached_end) << b.stop_reason;
  EXPECT_TRUE(b.end_above);
  const double dp = b.points.back().dp;
  std::printf("foot at %.5f, p_hold %.5f (over Zoelly's p_c)\n", dp / kPref, b.p_hold / kPref);
  EXPECT_GT(dp, b.p_hold);
  EXPECT_LT(dp, 1.1 * b.p_hold);
  EXPECT_LT(body.cavity_volume(b.state), 0.0);
  // Asked above p_hold, the same branch ends at the suction asked, not at the foot.
  o.end_dp = 0.5 * kPref;
  const auto above = trace_static_branch(body, o);
  EXPECT_FALSE(above.end_above);
  EXPECT_NEAR(above.points.back().dp / o.end_dp, 1.0, 1e-9);
}

// At 1 mm along, the inverted segment rising towards 1.4 p_c creases next to the clamp and turns
// down at a maximum of dp below it: a limit point, where a shell under pressure control snaps.
// Aimed at 1.4 p_c, the branch stops there, or at the last point before it that is stable under
// pressure control: the same branch traced on without an end pressure turns down within the
// next few points, less than 0.1 % above it. Taken through the snap, it comes back to that
// maximum where the branch beyond it folds below it.
TEST(StaticBranch, StopsAtAMaximumOfTheInvertedSegmentBelowTheSuctionAsked) {
  const Body body = make_body(42);
  auto o = options(-1.2);
  o.end_dp = 1.4 * kPref;
  const auto b = trace_static_branch(body, o);
  ASSERT_TRUE(b.snaps_below_end || b.loses_stability_below_end) << b.stop_reason;
  EXPECT_FALSE(b.reached_end);
  EXPECT_TRUE(b.stable);
  const double at = b.points.back().dp, v = b.points.back().volume;
  std::printf("stops at %.5f p_Zoelly, V / V0 = %.4f\n", at / kPref, v / b.V0);
  EXPECT_LT(at, o.end_dp);
  EXPECT_GT(at, b.p_minus);
  EXPECT_LT(v, 0.0);
  auto on = options(-1.2);
  const auto full = trace_static_branch(body, on);
  std::size_t k = 0;  // the same point on the branch traced on
  while (k < full.points.size() && full.points[k].volume != v) ++k;
  ASSERT_LT(k + 4, full.points.size()) << "the branch traced on has no points past it";
  EXPECT_EQ(full.points[k].dp, at);
  EXPECT_GT(at, full.points[k - 1].dp);
  std::size_t top = k;
  while (top + 1 < full.points.size() && full.points[top + 1].dp > full.points[top].dp) ++top;
  EXPECT_LE(top, k + 3);
  EXPECT_LT(full.points[top].dp, 1.001 * at);
  // Through the snaps (BranchOptions::through_snaps) the trace goes on past that maximum. Beyond
  // it this branch folds an element at a lower suction, a state a shell under pressure control
  // snaps over: the trace's state is the one at the maximum passed.
  o.through_snaps = true;
  const auto through = trace_static_branch(body, o);
  ASSERT_EQ(through.passed_maxima.size(), 1u) << through.stop_reason;
  EXPECT_GE(through.passed_maxima[0], at);
  EXPECT_LT(through.passed_maxima[0], 1.001 * at);
  EXPECT_FALSE(through.reached_end);
  EXPECT_TRUE(through.snaps_below_end);
  ASSERT_TRUE(through.fold) << through.stop_reason;
  EXPECT_LT(through.points.back().dp, through.passed_maxima[0]);
  EXPECT_EQ(through.state_dp, through.passed_maxima[0]);
}

// The (25, 2.0) mm cap with every inner corner node a crease's root (MeshSpec::fan_layer), at
// 2 x 35, aimed at 1.0 p_Zoelly: on the inverted segment its smooth surface loses stability
// under pressure control while dp still rises (no maximum: a bifurcation, the surface's
// wrinkling past its Biot instability). The branch stops at the last stable point; traced on a
// little further without an end pressure, the branch's state there is unstable.
TEST(StaticBranch, StopsWhereTheInvertedSegmentLosesStabilityBelowTheSuctionAsked) {
  const double R = 0.025;
  const double pref = 2.0 * kE * kH * kH / (R * R * std::sqrt(3.0 * (1.0 - kNu * kNu)));
  MeshSpec spec{R, kH, kPhi, 2, 35};
  spec.fan_layer = 1;
  const Body body(spec, fem::Material::from_young(kE, kNu, 1160.0));
  BranchOptions o;
  o.p_ref = pref;
  o.end_volume = -9.0;
  o.end_dp = pref;
  const auto b = trace_static_branch(body, o);
  ASSERT_TRUE(b.loses_stability_below_end) << b.stop_reason;
  EXPECT_FALSE(b.snaps_below_end);
  EXPECT_FALSE(b.reached_end);
  EXPECT_TRUE(b.stable);
  const auto& last = b.points.back();
  std::printf("stops at %.5f p_Zoelly, V / V0 = %.4f\n", last.dp / pref, last.volume / b.V0);
  EXPECT_LT(last.dp, o.end_dp);
  EXPECT_LT(last.volume, 0.0);
  EXPECT_GT(last.dp, b.points[b.points.size() - 2].dp);  // still rising
  BranchOptions on;
  on.p_ref = pref;
  on.end_volume = last.volume / b.V0 - 0.01;
  const auto further = trace_static_branch(body, on);
  ASSERT_TRUE(further.reached_end) << further.stop_reason;
  EXPECT_FALSE(further.stable);
}

TEST(StaticBranch, BucklingPressureConvergesAlongTheMeridian) {
  const auto coarse = trace_static_branch(make_body(21), options(0.8));
  const auto fine = trace_static_branch(make_body(42), options(0.8));
  std::printf("p_c: %.6g Pa (2 x 21), %.6g Pa (2 x 42)\n", coarse.p_c, fine.p_c);
  EXPECT_NEAR(coarse.p_c / fine.p_c, 1.0, 5e-3);
}

TEST(StaticBranch, AgreesWithTheThinShellTheory) {
  const auto fe = trace_static_branch(make_body(21), options(0.3));
  const auto st = theory::trace_shell_branch({kR, kH, kPhi, kE, kNu});
  std::printf("p_c: %.5g Pa (solid), %.5g Pa (shell theory); p_-: %.5g Pa, %.5g Pa\n", fe.p_c,
              st.p_c, fe.p_minus, st.p_minus);
  EXPECT_NEAR(fe.p_minus / st.p_minus, 1.0, 0.02);
  EXPECT_NEAR(fe.p_c / st.p_c, 1.0, kH / kR);
}

// A shallow cap (phi = 20 deg) has no buckling maximum: under a suction that only rises it
// turns inside out without a snap. Asked to, the branch stops once the cavity has passed its
// mirror image (V / V0 < -1) with the suction still rising, and says why; a deep cap's branch
// with the same option goes through its maximum to the inverted segment.
TEST(StaticBranch, StopsWhereTheCapTurnsInsideOutWithoutBuckling) {
  auto o = options(-9.0);
  o.end_dp = 0.5 * kPref;
  o.stop_inverted_without_buckling = true;
  const Body shallow({kR, kH, 20.0 * std::numbers::pi / 180.0, 2, 8},
                     fem::Material::from_young(kE, kNu, 1160.0));
  const auto b = trace_static_branch(shallow, o);
  EXPECT_FALSE(b.reached_end);
  EXPECT_TRUE(std::isnan(b.p_c));
  EXPECT_NE(b.stop_reason.find("turned inside out"), std::string::npos) << b.stop_reason;
  EXPECT_LT(b.points.back().volume / b.V0, -1.0);
  EXPECT_GT(b.points[b.points.size() - 2].volume / b.V0, -1.0);
  for (std::size_t i = 1; i < b.points.size(); ++i) {
    EXPECT_GT(b.points[i].dp, b.points[i - 1].dp) << i;
  }
  const auto deep = trace_static_branch(make_body(21), o);
  EXPECT_TRUE(deep.reached_end) << deep.stop_reason;
  EXPECT_NEAR(deep.points.back().dp, 0.5 * kPref, 1e-6 * kPref);
}

TEST(StaticBranch, RefusesUnusableOptions) {
  const Body body = make_body(21);
  auto o = options(-1.0);
  o.p_ref = 0.0;
  EXPECT_THROW(trace_static_branch(body, o), std::invalid_argument);
  o = options(-1.0);
  o.min_step = 2.0 * o.step;
  EXPECT_THROW(trace_static_branch(body, o), std::invalid_argument);
}

}  // namespace
}  // namespace snapjump::axi
