// theory::design: every returned design, fed back to predict on its own case, meets its targets
// with the prefactors' lower bounds; rankings are in order; an infeasible target names what binds.
#include <gtest/gtest.h>

#include <cmath>

#include "config/case.hpp"
#include "theory/design.hpp"
#include "theory/prefactors.hpp"

namespace snapjump::theory {
namespace {

config::Case base() {
  return config::parse_case(
      "[shell]\nR = \"30 mm\"\nh = \"2 mm\"\n[material]\nE = \"1.2 MPa\"\n[popper]\nnet_weight = "
      "\"1 N\"\n",
      "base.toml");
}

DesignSpace space(double mg) {
  DesignSpace s;
  s.net_weight_lo = s.net_weight_hi = mg;
  s.grid = 80;
  return s;
}

void expect_meets(const Design& d, const config::Case& b, const DesignTargets& t,
                  const DesignSpace& s) {
  const auto p = predict(design_case(b, d.R, d.h, d.net_weight), contact_constants());
  EXPECT_TRUE(p.beyond_range.empty());
  EXPECT_TRUE(p.outcome.jump && p.outcome.certain()) << p.outcome_text();
  EXPECT_GE(p.jump_margin.lo, t.margin);
  if (t.H) {
    EXPECT_GE(p.H.lo, t.H->lo);
    if (t.H->hi) {
      EXPECT_LE(p.H.hi, *t.H->hi);
    }
  }
  EXPECT_LE(2.0 * p.rim_radius, s.max_footprint * (1 + 1e-12));
  EXPECT_GE(d.h, s.min_h * (1 - 1e-12));
  EXPECT_NEAR(d.footprint, 2.0 * d.R * std::sin(b.shell.phi), 1e-12);
}

TEST(Design, AFiftyMillimetreJumpAtOneNewtonIsMetWithTheLowerBounds) {
  const auto b = base();
  DesignTargets t;
  t.H = Target{0.050, std::nullopt};
  const auto s = space(1.0);
  const auto r = design(b, t, s, Rank::Smallest, 5);
  ASSERT_FALSE(r.designs.empty()) << r.infeasible;
  for (const auto& d : r.designs) expect_meets(d, b, t, s);
  for (std::size_t i = 1; i < r.designs.size(); ++i) {
    EXPECT_LE(r.designs[i - 1].footprint, r.designs[i].footprint);
  }
  // The Pareto front: a larger footprint buys a higher lower bound of H, step by step.
  ASSERT_FALSE(r.pareto.empty());
  for (std::size_t i = 1; i < r.pareto.size(); ++i) {
    EXPECT_GT(r.pareto[i].footprint, r.pareto[i - 1].footprint);
    EXPECT_GT(r.pareto[i].prediction.H.lo, r.pareto[i - 1].prediction.H.lo);
  }
  EXPECT_GT(r.evaluated, 1000);
}

TEST(Design, RankingsAndARangeTarget) {
  const auto b = base();
  DesignTargets t;
  t.H = Target{0.030, 0.090};
  t.margin = 1.5;
  const auto s = space(0.5);
  const auto light = design(b, t, s, Rank::Lightest, 4);
  ASSERT_GE(light.designs.size(), 2U) << light.infeasible;
  for (const auto& d : light.designs) expect_meets(d, b, t, s);
  for (std::size_t i = 1; i < light.designs.size(); ++i) {
    EXPECT_LE(light.designs[i - 1].prediction.shell_mass, light.designs[i].prediction.shell_mass);
  }
  const auto margin = design(b, t, s, Rank::Margin, 3);
  ASSERT_FALSE(margin.designs.empty());
  EXPECT_GE(margin.designs[0].prediction.jump_margin.lo,
            light.designs[0].prediction.jump_margin.lo);
  const auto high = design(b, t, s, Rank::Highest, 3);
  ASSERT_FALSE(high.designs.empty());
  EXPECT_GE(high.designs[0].prediction.H.lo, light.designs[0].prediction.H.lo);
  for (const auto& d : high.designs) expect_meets(d, b, t, s);
}

TEST(Design, AnInfeasibleTargetSaysWhatBindsAndByHowMuch) {
  const auto b = base();
  DesignTargets t;
  t.H = Target{100.0, std::nullopt};  // 100 m within a 100 mm footprint
  const auto r = design(b, t, space(1.0), Rank::Smallest, 3);
  EXPECT_TRUE(r.designs.empty());
  ASSERT_TRUE(r.closest);
  EXPECT_LT(r.closest->slack, 0.0);
  EXPECT_NE(r.infeasible.find("H's lower bound"), std::string::npos) << r.infeasible;
  EXPECT_NE(r.infeasible.find("misses by"), std::string::npos) << r.infeasible;
  // The pump's suction as the constraint that binds: a thick shell needs more than 1 Pa.
  DesignTargets any;
  auto weak_pump = space(1.0);
  weak_pump.max_suction = 1.0;
  const auto p = design(b, any, weak_pump, Rank::Smallest, 3);
  EXPECT_TRUE(p.designs.empty());
  EXPECT_NE(p.infeasible.find("pump"), std::string::npos) << p.infeasible;
}

TEST(Design, ASearchSpaceThatMakesNoSenseIsRefused) {
  const auto b = base();
  auto s = space(1.0);
  s.max_footprint = -1.0;
  EXPECT_THROW(design(b, {}, s, Rank::Smallest, 3), config::CaseError);
  s = space(1.0);
  s.min_h = 0.05;  // a 50 mm wall
  EXPECT_THROW(design(b, {}, s, Rank::Smallest, 3), config::CaseError);
  s = space(1.0);
  s.net_weight_hi = 0.5;  // below the lower end
  EXPECT_THROW(design(b, {}, s, Rank::Smallest, 3), config::CaseError);
}

// A payload range: the search takes the net weight as a third dimension; every design's weight
// lies in it.
TEST(Design, ANetWeightRangeIsSearched) {
  const auto b = base();
  DesignTargets t;
  t.H = Target{0.040, std::nullopt};
  auto s = space(0.5);
  s.net_weight_hi = 5.0;
  const auto r = design(b, t, s, Rank::Margin, 3);
  ASSERT_FALSE(r.designs.empty()) << r.infeasible;
  for (const auto& d : r.designs) {
    EXPECT_GE(d.net_weight, 0.5 * (1 - 1e-12));
    EXPECT_LE(d.net_weight, 5.0 * (1 + 1e-12));
    expect_meets(d, b, t, s);
  }
}

}  // namespace
}  // namespace snapjump::theory
