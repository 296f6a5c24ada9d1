#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "config/case.hpp"
#include "fem/body.hpp"
#include "fem/surface_instability.hpp"
#include "popper/material.hpp"
#include "popper/popper.hpp"
#include "support/cases.hpp"
#include "theory/scaling.hpp"

namespace snapjump::popper {
namespace {

using test_support::coarse_axisymmetric_default;

// Each model keeps its own integration of the bulk energy unless the case names one: the 3D
// tetrahedra the paper's full rule, the axisymmetric elements their reduced one.
TEST(Numerics, EachModelHasItsOwnBulkIntegrationUnlessTheCaseSetsOne) {
  auto c = config::default_case();
  EXPECT_FALSE(resolve_numerics(c).reduced_bulk);
  c.numerics.model = config::Model::Axisymmetric;
  EXPECT_TRUE(resolve_numerics(c).reduced_bulk);
  c.numerics.bulk_integration = config::BulkIntegration::Full;
  EXPECT_FALSE(resolve_numerics(c).reduced_bulk);
  c.numerics.model = config::Model::ThreeD;
  c.numerics.bulk_integration = config::BulkIntegration::Reduced;
  EXPECT_TRUE(resolve_numerics(c).reduced_bulk);
}

// A crease fan belongs to the axisymmetric mesh; the 3D model refuses it by name.
TEST(Numerics, ACreaseFanIsTheAxisymmetricModels) {
  auto c = config::default_case();
  c.numerics.crease_fan = 2e-3;
  try {
    (void)resolve_numerics(c);
    FAIL() << "the 3D model took a crease fan";
  } catch (const config::CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("numerics.crease_fan"), std::string::npos) << e.what();
  }
  c.numerics.model = config::Model::Axisymmetric;
  EXPECT_EQ(resolve_numerics(c).axi_crease_fan, 2e-3);
}

// And snapping along the pressure-volume branch, which only that model traces.
TEST(Numerics, InvertedSnapsAlongTheBranchAreTheAxisymmetricModels) {
  auto c = config::default_case();
  c.protocol.inverted_snaps = config::InvertedSnaps::AlongBranch;
  try {
    (void)resolve_numerics(c);
    FAIL() << "the 3D model took snaps along the branch";
  } catch (const config::CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("protocol.inverted_snaps"), std::string::npos) << e.what();
  }
  c.numerics.model = config::Model::Axisymmetric;
  EXPECT_NO_THROW((void)resolve_numerics(c));
}

// A seeded crease too.
TEST(Numerics, ASeededCreaseIsTheAxisymmetricModels) {
  auto c = config::default_case();
  c.numerics.crease_seed = 3e-3;
  c.numerics.crease_seed_depth = 25e-6;
  try {
    (void)resolve_numerics(c);
    FAIL() << "the 3D model took a seeded crease";
  } catch (const config::CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("numerics.crease_seed"), std::string::npos) << e.what();
  }
  c.numerics.model = config::Model::Axisymmetric;
  const auto n = resolve_numerics(c);
  EXPECT_EQ(n.axi_crease_seeds, std::vector<double>{3e-3});
  EXPECT_EQ(n.axi_crease_seed_depth, 25e-6);
  c.numerics.second_crease_seed = 5e-3;
  EXPECT_EQ(resolve_numerics(c).axi_crease_seeds, (std::vector<double>{3e-3, 5e-3}));
}

// A fan layer belongs to the axisymmetric mesh too, and not with a crease fan.
TEST(Numerics, AFanLayerIsTheAxisymmetricModels) {
  auto c = config::default_case();
  c.numerics.fan_layer = 1;
  EXPECT_THROW((void)resolve_numerics(c), config::CaseError);
  c.numerics.model = config::Model::Axisymmetric;
  EXPECT_EQ(resolve_numerics(c).axi_fan_layer, 1);
  c.numerics.crease_fan = 2e-3;
  try {
    (void)resolve_numerics(c);
    FAIL() << "a fan layer was taken with a crease fan";
  } catch (const config::CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("numerics.fan_layer"), std::string::npos) << e.what();
  }
}

// Without numerics.end_time a run goes to the apex of its flight, capped well past the apexes on
// record: the default popper's comes 0.69 s after the release (coarse axisymmetric), and the
// (30, 1.0) mm shell at 0.08 N still rises 1.6 s after it (docs/popper.md). A cap the case sets
// is the cap.
TEST(Numerics, TheDefaultCapLiesWellPastTheApexesOnRecord) {
  auto c = config::default_case();
  EXPECT_GT(resolve_numerics(c).end_time, 2.0 * 0.69);
  auto thin = c;
  thin.shell.h = 1e-3;
  thin.popper.net_weight = 0.08;
  EXPECT_GT(resolve_numerics(thin).end_time, 2.0 * 1.6);
  c.numerics.end_time = 0.3;
  EXPECT_EQ(resolve_numerics(c).end_time, 0.3);
}

// The cap's parts: the refill solves the valve law at delta_p_j for twice the cavity's share of
// the gas; without suction at the release the cap is the longest one.
TEST(Numerics, TheDefaultCapIsRefillsAndRises) {
  const auto c = config::default_case();
  const auto d = default_end(c);
  EXPECT_DOUBLE_EQ(d.cap, kRefillsBeforeTheCap * d.refill + 2.0 * d.rise);
  const double dp = theory::jump_pressure(c);
  const double cavity = theory::cavity_volume(c.shell.R, c.shell.h, c.shell.phi);
  const double t = d.refill;
  EXPECT_NEAR(c.gas.beta_n * dp * t + 0.5 * c.gas.alpha_n * dp * t * t,
              2.0 * cavity / (c.gas.container_volume + cavity), 1e-12);
  EXPECT_NEAR(d.rise * d.rise * c.popper.net_weight / c.popper.moving_mass(), 2.0 * d.height,
              1e-12);
  auto none = c;
  none.protocol.delta_p_j = 0.0;
  EXPECT_EQ(default_end(none).cap, kLongestDefaultEnd);
}

// The presets' grid and axisymmetric elements come from the one table, config::preset.
TEST(Numerics, ThePresetsSetTheGridAndTheAxisymmetricElements) {
  auto c = config::default_case();
  for (const auto r :
       {config::Resolution::Coarse, config::Resolution::Default, config::Resolution::Fine}) {
    c.numerics.resolution = r;
    const auto n = resolve_numerics(c);
    EXPECT_DOUBLE_EQ(
        n.dx, std::min(c.shell.h / config::preset(r).grid_cells_per_thickness, n.cap.element_size));
    EXPECT_EQ(n.axi_through, config::preset(r).axi_through);
    EXPECT_EQ(n.cap.layers, config::preset(r).layers);
  }
  EXPECT_EQ(config::preset(config::Resolution::Default).grid_cells_per_thickness, 4.0);
  EXPECT_EQ(config::preset(config::Resolution::Fine).layers, 2);
}

// The onset rule on a made-up record sampled every millisecond: the suction rises at 10 kPa/s and
// the volume shrinks at 1e-6 m^3/s, then, from the sample at 900 Pa on, at 1e-4 m^3/s. The window
// (300, 600) Pa sees the slow rate; the first sample whose interval shrank more than 5 times
// faster is the next one, at 910 Pa.
TEST(SnapOnset, FirstSampleFasterThanTheWindowsRate) {
  SnapOnset onset(300.0, 600.0, 5.0);
  double V = 1e-3;
  for (int k = 0; k <= 120; ++k) {
    const double t = 1e-3 * k, p = 1e4 * t;
    onset.sample(t, V, p);
    if (k <= 90) {
      EXPECT_FALSE(onset.pressure()) << p;
    }
    V -= (k < 90 ? 1e-6 : 1e-4) * 1e-3;
  }
  ASSERT_TRUE(onset.pressure());
  EXPECT_NEAR(*onset.pressure(), 910.0, 1e-9);
  // A record that never enters the window has no reference: no onset, however fast the snap.
  // A sample no later than the one before is ignored (no division by a zero interval).
  SnapOnset same_time(300.0, 600.0, 5.0);
  same_time.sample(0.0, 1e-3, 400.0);
  same_time.sample(0.0, 0.9e-3, 400.0);
  same_time.sample(1e-3, 0.999e-3, 500.0);
  same_time.sample(2e-3, 0.5e-3, 700.0);
  ASSERT_TRUE(same_time.pressure());
  EXPECT_EQ(*same_time.pressure(), 700.0);
  SnapOnset late(300.0, 600.0, 5.0);
  late.sample(0.0, 1e-3, 700.0);
  late.sample(1e-3, 0.5e-3, 800.0);
  EXPECT_FALSE(late.pressure());
}

// The buckling phase alone (the protocol's one buckling driver): the cheap axisymmetric coarse
// popper inverts, its buckling pressure is read, and a popper is prepared only once.
TEST(Protocol, BucklePhaseAloneThenNoSecondPreparation) {
  auto c = coarse_axisymmetric_default();
  Popper pop(c, resolve_numerics(c));
  const auto prep = pop.buckle();
  EXPECT_TRUE(prep.inverted) << prep.message;
  ASSERT_TRUE(prep.buckling_pressure) << prep.message;
  EXPECT_GT(*prep.buckling_pressure, 0.0);
  EXPECT_FALSE(prep.held);  // the phase that sets delta_p_j has not run
  EXPECT_GT(pop.model().apex_z(), pop.model().outer_rim_z());
  EXPECT_THROW((void)pop.prepare(), std::logic_error);
  EXPECT_THROW((void)pop.buckle(), std::logic_error);
  EXPECT_THROW(pop.release(), std::logic_error);
}

// Below the branch's p_- (0.20 p_c for this cap) no buckled state is left: the cap that is still
// inverted in the air after phase 2 snaps back once the plate and its weight touch it, and its
// apex stands on the plate before the release. That is a preparation that did not hold the shell,
// not a release whose snap comes at t = 0. (At the protocol's 0.5 p_c, above p_hold = 0.26 p_c,
// the same cap is held: ExamplePreparation.)
TEST(Protocol, ACapThatSnapsBackAsItIsGroundedIsNotHeld) {
  auto c = coarse_axisymmetric_default();
  c.protocol.delta_p_j_over_pc = 0.1;
  Popper low(c, resolve_numerics(c));
  const auto prep = low.prepare();
  EXPECT_TRUE(prep.inverted) << prep.message;
  EXPECT_FALSE(prep.held) << prep.message;
  EXPECT_NE(prep.message.find("snapped back as it was grounded"), std::string::npos)
      << prep.message;
  EXPECT_LT(low.model().apex_z(), 0.03 * c.shell.R);
  EXPECT_THROW(low.release(), std::logic_error);
}

// The (25, 2.5) mm cap at 4 x 56: its inverted segment stops being stable at 0.358 p_c, below
// delta_p_j, and the shell snaps from there in phase 2 into a crease that folds an element
// (docs/axisymmetric.md, "The converged popper"). The fold's error carries what phase 1 found.
TEST(Protocol, AFoldAfterTheBuckleSaysWhatTheBuckleFound) {
  auto c = config::load_case_file(std::filesystem::path(SNAPJUMP_SOURCE_DIR) / "examples" /
                                  "R25_h2.5.toml");
  c.numerics.model = config::Model::Axisymmetric;
  c.numerics.element_size = 0.625e-3;
  Popper pop(c, resolve_numerics(c));
  try {
    (void)pop.prepare();
    ADD_FAILURE() << "no fold";
  } catch (const fem::FoldedElement& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("after the shell inverted along the quasi-static pressure-volume branch "
                        "to the last state stable under pressure control"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("folded through itself"), std::string::npos) << what;
  }
}

TEST(Protocol, TheGroundedShellsInnerSurfaceIsMeasuredWhereTheModelResolvesIt) {
  // The axisymmetric popper's fold next to the clamp compresses its inner surface most there
  // (docs/axisymmetric.md, "The crease at the clamp"), less than Biot's instability of its law,
  // past which no smooth surface is stable; the 3D mesh (one element through h) reports nothing.
  auto c = coarse_axisymmetric_default();
  Popper axi(c, resolve_numerics(c));
  const auto prep = axi.prepare();
  ASSERT_TRUE(prep.held) << prep.message;
  ASSERT_TRUE(prep.surface_ratio.has_value());
  EXPECT_GT(*prep.surface_ratio, 1.5);
  EXPECT_LT(*prep.surface_ratio, fem::biot_instability(body_material(c.material)).ratio);
  const double meridian = (c.shell.R - 0.5 * c.shell.h) * c.shell.phi;
  EXPECT_LT(prep.surface_from_rim, 0.15 * meridian);
  c.numerics.model = config::Model::ThreeD;
  Popper three_d(c, resolve_numerics(c));
  EXPECT_FALSE(three_d.model().inner_surface_compression().has_value());
}

TEST(Protocol, SettingsThatCannotRunAreRefused) {
  auto c = coarse_axisymmetric_default();
  const auto n = resolve_numerics(c);
  for (const auto broken : {+[](PreparationSettings& s) { s.ramp = 0.0; },
                            +[](PreparationSettings& s) { s.buckle_factor = -1.0; },
                            +[](PreparationSettings& s) { s.onset_factor = 1.0; },
                            +[](PreparationSettings& s) {
                              s.reference_window = {0.6, 0.3};
                            },
                            // a window the suction never leaves: no onset could be seen
                            +[](PreparationSettings& s) {
                              s.reference_window = {0.3, 1.4};
                            },
                            +[](PreparationSettings& s) { s.fast_to = 1.4; },
                            +[](PreparationSettings& s) { s.fast_ramp = 0.02; },
                            +[](PreparationSettings& s) { s.progress_every = 0; }}) {
    PreparationSettings s;
    broken(s);
    EXPECT_THROW(Popper(c, n, s), std::invalid_argument);
  }
}

// The buckling ramp: one even ramp by default, or a fast first leg then an even one.
TEST(Protocol, BucklingRampWithAndWithoutAFastLeg) {
  auto c = coarse_axisymmetric_default();
  const auto n = resolve_numerics(c);
  const double pc = 1000.0;
  const Popper even(c, n);
  EXPECT_EQ(even.buckling_suction(0.0, pc), 0.0);
  EXPECT_DOUBLE_EQ(even.buckling_suction(0.01, pc), 700.0);  // 1.4 p_c over 20 ms
  EXPECT_DOUBLE_EQ(even.buckling_suction(0.05, pc), 1400.0);
  PreparationSettings s;
  s.buckle_factor = 1.3;
  s.fast_to = 0.6;
  s.fast_ramp = 0.01;
  s.ramp = 0.15;
  const Popper two_legs(c, n, s);
  EXPECT_DOUBLE_EQ(two_legs.buckling_suction(0.005, pc), 300.0);
  EXPECT_DOUBLE_EQ(two_legs.buckling_suction(0.01, pc), 600.0);
  EXPECT_DOUBLE_EQ(two_legs.buckling_suction(0.08, pc), 950.0);  // 5 p_c per second
  EXPECT_DOUBLE_EQ(two_legs.buckling_suction(0.2, pc), 1300.0);
}

}  // namespace
}  // namespace snapjump::popper
