#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "config/plausibility.hpp"
#include "support/hostile_text.hpp"

namespace snapjump::config {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A valid minimal case; tests edit one line at a time.
const std::string kMinimal = R"([shell]
R = "30 mm"
h = "2 mm"

[material]
E = "1.2 MPa"

[popper]
net_weight = "0.48 N"
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  if (pos == std::string::npos) throw std::logic_error("test edits a line that is not there");
  return text.replace(pos, from.size(), to);
}

// Expects a CaseError whose message contains every fragment.
void expect_error(const std::string& text, const std::vector<std::string>& fragments,
                  const std::vector<Override>& overrides = {}) {
  try {
    (void)parse_case(text, "case.toml", overrides);
    FAIL() << "expected an error for:\n" << text;
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    for (const auto& f : fragments) {
      EXPECT_NE(msg.find(f), std::string::npos) << "message: " << msg << "\nlacks: " << f;
    }
  }
}

TEST(CaseFile, MinimalCaseInSI) {
  const auto c = parse_case(kMinimal, "case.toml");
  EXPECT_DOUBLE_EQ(c.shell.R, 0.030);
  EXPECT_DOUBLE_EQ(c.shell.h, 0.002);
  EXPECT_DOUBLE_EQ(c.material.E, 1.2e6);
  EXPECT_DOUBLE_EQ(c.popper.net_weight, 0.48);
}

TEST(CaseFile, DefaultsFromTheSimulationGuide) {
  const auto c = parse_case(kMinimal, "case.toml");
  EXPECT_NEAR(c.shell.phi, 80.0 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(c.material.nu, 0.45);
  EXPECT_DOUBLE_EQ(c.material.rho, 1160.0);
  EXPECT_DOUBLE_EQ(c.friction.mu, 0.3);
  EXPECT_NEAR(c.gas.container_volume, 200e-6, 1e-18);
  EXPECT_DOUBLE_EQ(c.gas.p0, 101325.0);
  EXPECT_DOUBLE_EQ(c.gas.alpha_n, 1.0e-3);
  EXPECT_DOUBLE_EQ(c.gas.beta_n, 5.0e-5);
  // The apparatus: a 300 g popper, a counterweight lighter by mg / g = 0.48 / 9.80665 kg, and
  // their sum as the inertia; a rigid wire.
  EXPECT_DOUBLE_EQ(c.popper.mass, 0.300);
  EXPECT_NEAR(c.popper.counterweight(), 0.300 - 0.048946378, 1e-9);
  EXPECT_NEAR(c.popper.moving_mass(), 0.600 - 0.048946378, 1e-9);
  EXPECT_FALSE(c.popper.wire_stiffness.has_value());
  EXPECT_FALSE(c.protocol.delta_p_j.has_value());
  EXPECT_DOUBLE_EQ(c.protocol.delta_p_j_over_pc, 0.5);
  // The program says which defaults it used.
  const auto has = [&](const std::string& s) {
    return std::find(c.defaults_used.begin(), c.defaults_used.end(), s) != c.defaults_used.end();
  };
  EXPECT_TRUE(has("material.nu = 0.45"));
  EXPECT_TRUE(has("shell.phi = 80 deg"));
  EXPECT_TRUE(has("friction.mu = 0.3"));
  EXPECT_TRUE(has("popper.mass = 300 g (net_weight / g when heavier: no counterweight)"));
  EXPECT_FALSE(has("shell.R = "));
}

TEST(CaseFile, EveryTableWithUnits) {
  const std::string text = R"(title = "all keys"
[shell]
R = 0.025
h = "2.5 mm"
phi = "90 deg"
[material]
E = 1200000
nu = 0.49
rho = "1.1 g/cm^3"
[popper]
net_weight = "300 mN"
mass = "60 g"
wire_stiffness = "2 kN/m"
[friction]
mu = 0
[gas]
container_volume = "0.1 L"
p0 = "100 kPa"
alpha_n = "2e-3 Pa^-1 s^-2"
beta_n = "1e-5 Pa^-1 s^-1"
[protocol]
delta_p_j = "4 kPa"
[numerics]
resolution = "coarse"
element_size = "1 mm"
elements_through_thickness = 3
end_time = "0.5 s"
)";
  const auto c = parse_case(text, "all.toml");
  EXPECT_EQ(c.title, "all keys");
  EXPECT_DOUBLE_EQ(c.shell.R, 0.025);
  EXPECT_DOUBLE_EQ(c.shell.h, 0.0025);
  EXPECT_NEAR(c.shell.phi, std::numbers::pi / 2, 1e-15);
  EXPECT_DOUBLE_EQ(c.material.E, 1.2e6);
  EXPECT_DOUBLE_EQ(c.material.nu, 0.49);
  EXPECT_NEAR(c.material.rho, 1100.0, 1e-9);
  EXPECT_NEAR(c.popper.net_weight, 0.3, 1e-15);
  EXPECT_NEAR(c.popper.mass, 0.06, 1e-15);
  EXPECT_NEAR(c.popper.moving_mass(), 0.12 - 0.3 / 9.80665, 1e-15);
  EXPECT_EQ(c.popper.wire_stiffness, 2000.0);
  EXPECT_DOUBLE_EQ(c.friction.mu, 0.0);
  EXPECT_NEAR(c.gas.container_volume, 1e-4, 1e-18);
  EXPECT_DOUBLE_EQ(c.gas.p0, 1e5);
  EXPECT_DOUBLE_EQ(c.gas.alpha_n, 2e-3);
  EXPECT_DOUBLE_EQ(c.gas.beta_n, 1e-5);
  ASSERT_TRUE(c.protocol.delta_p_j.has_value());
  EXPECT_DOUBLE_EQ(*c.protocol.delta_p_j, 4000.0);
  EXPECT_EQ(c.numerics.resolution, Resolution::Coarse);
  EXPECT_DOUBLE_EQ(*c.numerics.element_size, 1e-3);
  EXPECT_EQ(c.numerics.elements_through_thickness.value_or(0), 3);
  EXPECT_DOUBLE_EQ(*c.numerics.end_time, 0.5);
  EXPECT_TRUE(c.defaults_used.empty());
}

TEST(CaseFile, OverridesWinOverTheFile) {
  const std::vector<Override> o = {{"shell.h", "1.5mm", "--h"}, {"friction.mu", "0.1", "--mu"}};
  const auto c = parse_case(kMinimal, "case.toml", o);
  EXPECT_DOUBLE_EQ(c.shell.h, 0.0015);
  EXPECT_DOUBLE_EQ(c.friction.mu, 0.1);
}

TEST(CaseFile, ErrorsNameKeyAndLine) {
  // unknown key, with the file's line
  expect_error(replace(kMinimal, "h = \"2 mm\"", "thickness = \"2 mm\""),
               {"case.toml:3", "unknown key 'thickness' in [shell]", "R, h, phi"});
  // unknown table
  expect_error(kMinimal + "[plate]\nmu = 0.3\n", {"case.toml:10", "unknown table 'plate'"});
  // wrong dimension
  expect_error(replace(kMinimal, "R = \"30 mm\"", "R = \"30 kg\""),
               {"case.toml:2", "shell.R", "'kg' is a mass, but a length is needed"});
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2 N\""),
               {"case.toml:6", "material.E", "is a force, but a pressure is needed"});
  // unknown unit
  expect_error(replace(kMinimal, "net_weight = \"0.48 N\"", "net_weight = \"0.48 Nm2x\""),
               {"case.toml:9", "popper.net_weight", "unknown unit"});
  // wrong TOML type
  expect_error(replace(kMinimal, "R = \"30 mm\"", "R = true"),
               {"case.toml:2", "shell.R must be a number or a string with a unit"});
  // TOML syntax error
  expect_error(replace(kMinimal, "R = \"30 mm\"", "R = \"30 mm"),
               {"case.toml:2", "not valid TOML"});
}

// The message of the CaseError that parsing `text` throws.
std::string error_of(const std::string& text) {
  try {
    (void)parse_case(text, "case.toml");
  } catch (const CaseError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an error for:\n" << text;
  return {};
}

TEST(CaseFile, AnErrorQuotesAShortEscapedExcerptOfTheFile) {
  using test_support::quotes_only_an_excerpt;
  const auto quoted = test_support::hostile_toml_quoted();
  const auto hostile = test_support::hostile_text();
  // An unknown table or key, at the top and in a table.
  EXPECT_TRUE(quotes_only_an_excerpt(error_of(kMinimal + quoted + " = 1\n")));
  EXPECT_TRUE(quotes_only_an_excerpt(error_of(replace(kMinimal, "h = ", quoted + " = "))));
  // A value and its unit, a mesh path.
  EXPECT_TRUE(quotes_only_an_excerpt(error_of(replace(kMinimal, "\"30 mm\"", quoted))));
  EXPECT_TRUE(quotes_only_an_excerpt(
      error_of(replace(kMinimal, "h = \"2 mm\"", "h = \"2 mm\"\nmesh = " + quoted))));
  // Text that is not TOML: toml++'s message is passed on escaped.
  const auto raw = error_of(replace(kMinimal, "h = \"2 mm\"", "h = " + hostile));
  EXPECT_TRUE(quotes_only_an_excerpt(raw, false)) << raw;
}

TEST(CaseFile, MissingRequiredValues) {
  expect_error(replace(kMinimal, "R = \"30 mm\"\n", ""),
               {"case.toml", "missing required value shell.R", "length", "[shell]"});
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"\n", ""),
               {"missing required value material.E", "pressure"});
  expect_error(replace(kMinimal, "net_weight = \"0.48 N\"\n", ""),
               {"missing required value popper.net_weight", "force"});
}

TEST(CaseFile, UnphysicalValues) {
  expect_error(replace(kMinimal, "h = \"2 mm\"", "h = \"30 mm\""),
               {"case.toml:3", "shell.h", "must be smaller than shell.R"});
  expect_error(replace(kMinimal, "h = \"2 mm\"", "h = \"-2 mm\""),
               {"case.toml:3", "shell.h", "must be positive"});
  expect_error(kMinimal + "", {"--nu", "material.nu", "(-1, 0.5]"},
               {{"material.nu", "0.51", "--nu"}});
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2 MPa\"\nnu = -1.2"),
               {"case.toml:7", "material.nu", "(-1, 0.5]"});
  expect_error(replace(kMinimal, "h = \"2 mm\"", "h = \"2 mm\"\nphi = \"180 deg\""),
               {"case.toml:4", "shell.phi", "between 0 and 180 deg"});
  expect_error(replace(kMinimal, "h = \"2 mm\"", "h = \"2 mm\"\nphi = 80"),
               {"case.toml:4", "shell.phi", "radians"});
  expect_error(replace(kMinimal, "h = \"2 mm\"", "h = \"2 mm\"\nphi = \"0 deg\""),
               {"shell.phi", "between 0 and 180 deg"});
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"", "E = 0"),
               {"case.toml:6", "material.E", "must be positive"});
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2 MPa\"\nrho = \"-1 kg/m^3\""),
               {"case.toml:7", "material.rho", "must be positive"});
  expect_error(replace(kMinimal, "net_weight = \"0.48 N\"", "net_weight = \"0 N\""),
               {"case.toml:9", "popper.net_weight", "must be positive"});
  expect_error(kMinimal + "mass = \"-1 g\"\n", {"popper.mass", "must be positive"});
  expect_error(kMinimal + "mass = \"10 g\"\n", {"popper.mass", "at least net_weight / g"});
  expect_error(kMinimal + "wire_stiffness = \"1 N\"\n", {"popper.wire_stiffness", "stiffness"});
  expect_error(kMinimal + "wire_stiffness = \"-1 N/m\"\n",
               {"popper.wire_stiffness", "must be positive"});
  expect_error(kMinimal + "[friction]\nmu = -0.1\n", {"case.toml:11", "friction.mu", "negative"});
  expect_error(kMinimal + "[protocol]\ndelta_p_j = \"2 kPa\"\ndelta_p_j_over_pc = 0.5\n",
               {"not both"});
  expect_error(kMinimal + "[protocol]\ndelta_p_j = \"200 kPa\"\n",
               {"protocol.delta_p_j", "[0, p0)"});
  expect_error(kMinimal + "[numerics]\nresolution = \"ultra\"\n",
               {"case.toml:11", "numerics.resolution"});
  expect_error(kMinimal + "[numerics]\nmodel = \"2d\"\n",
               {"case.toml:11", "numerics.model", "\"3d\" or \"axisymmetric\""});
  expect_error(kMinimal + "[numerics]\nelements_through_thickness = 0\n",
               {"case.toml:11", "elements_through_thickness"});
  expect_error(kMinimal + "[gas]\ncontainer_volume = \"0 mL\"\n",
               {"gas.container_volume", "must be positive"});
}

TEST(CaseFile, NonFiniteNumbersAreRejected) {
  expect_error(replace(kMinimal, "R = \"30 mm\"", "R = nan"), {"case.toml:2", "not a finite"});
  expect_error(replace(kMinimal, "R = \"30 mm\"", "R = inf"), {"case.toml:2", "not a finite"});
}

TEST(CaseFile, BulkIntegrationIsFullOrReduced) {
  EXPECT_EQ(parse_case(kMinimal + "[numerics]\nbulk_integration = \"reduced\"\n", "case.toml")
                .numerics.bulk_integration,
            BulkIntegration::Reduced);
  expect_error(kMinimal + "[numerics]\nbulk_integration = \"selective\"\n",
               {"case.toml:", "numerics.bulk_integration must be \"full\" or \"reduced\""});
  expect_error(kMinimal + "[numerics]\nbulk = \"full\"\n", {"bulk_integration"});
}

TEST(CaseFile, InvertedSnapsAreTakenInTimeOrAlongTheBranch) {
  EXPECT_EQ(parse_case(kMinimal, "case.toml").protocol.inverted_snaps, InvertedSnaps::InTime);
  EXPECT_EQ(
      parse_case(kMinimal + "[protocol]\ninverted_snaps = \"along the branch\"\n", "case.toml")
          .protocol.inverted_snaps,
      InvertedSnaps::AlongBranch);
  expect_error(
      kMinimal + "[protocol]\ninverted_snaps = \"quasi-static\"\n",
      {"case.toml:", "protocol.inverted_snaps must be \"in time\" or \"along the branch\""});
}

TEST(CaseFile, ACreaseFanIsALengthOfTheAxisymmetricMesh) {
  const auto c = parse_case(
      kMinimal + "[numerics]\nmodel = \"axisymmetric\"\ncrease_fan = \"2.15 mm\"\n", "case.toml");
  ASSERT_TRUE(c.numerics.crease_fan.has_value());
  EXPECT_DOUBLE_EQ(*c.numerics.crease_fan, 2.15e-3);
  expect_error(kMinimal + "[numerics]\nmodel = \"axisymmetric\"\ncrease_fan = \"2 kg\"\n",
               {"numerics.crease_fan"});
  expect_error(kMinimal + "[numerics]\nmodel = \"axisymmetric\"\ncrease_fan = \"-1 mm\"\n",
               {"numerics.crease_fan"});
  expect_error(kMinimal + "[numerics]\nmodel = \"axisymmetric\"\ncrease_fan_band = \"1 mm\"\n",
               {"numerics.crease_fan_band", "give both"});
}

TEST(CaseFile, ASeededCreaseIsALengthAndANotchOfTheAxisymmetricMesh) {
  const auto c = parse_case(kMinimal +
                                "[numerics]\nmodel = \"axisymmetric\"\ncrease_seed = \"3.35 mm\"\n"
                                "crease_seed_depth = \"25 um\"\nsecond_crease_seed = \"2.1 mm\"\n",
                            "case.toml");
  ASSERT_TRUE(c.numerics.crease_seed && c.numerics.crease_seed_depth &&
              c.numerics.second_crease_seed);
  EXPECT_DOUBLE_EQ(*c.numerics.crease_seed, 3.35e-3);
  EXPECT_DOUBLE_EQ(*c.numerics.second_crease_seed, 2.1e-3);
  EXPECT_DOUBLE_EQ(*c.numerics.crease_seed_depth, 25e-6);
  // Written and read back.
  const auto r = parse_case(to_toml(c), "written.toml");
  EXPECT_EQ(r.numerics.crease_seed, c.numerics.crease_seed);
  EXPECT_EQ(r.numerics.crease_seed_depth, c.numerics.crease_seed_depth);
  EXPECT_EQ(r.numerics.second_crease_seed, c.numerics.second_crease_seed);
  expect_error(kMinimal + "[numerics]\nsecond_crease_seed = \"2 mm\"\n",
               {"numerics.second_crease_seed", "give both"});
  expect_error(kMinimal + "[numerics]\ncrease_seed = \"3 mm\"\nsecond_crease_seed = \"0 mm\"\n",
               {"numerics.second_crease_seed"});
  expect_error(kMinimal + "[numerics]\ncrease_seed = \"3 s\"\n", {"numerics.crease_seed"});
  expect_error(kMinimal + "[numerics]\ncrease_seed = \"-3 mm\"\n", {"numerics.crease_seed"});
  expect_error(kMinimal + "[numerics]\ncrease_seed_depth = \"25 um\"\n",
               {"numerics.crease_seed_depth", "give both"});
  expect_error(kMinimal + "[numerics]\ncrease_seed = \"3 mm\"\ncrease_seed_depth = \"-1 um\"\n",
               {"numerics.crease_seed_depth"});
  expect_error(kMinimal + "[numerics]\ncrease_seed = \"3 mm\"\ncrease_fan = \"2 mm\"\n",
               {"numerics.crease_seed", "numerics.crease_fan"});
  expect_error(kMinimal + "[numerics]\ncrease_seed = \"3 mm\"\nfan_layer = 1\n",
               {"numerics.crease_seed", "numerics.fan_layer"});
}

TEST(CaseFile, AFanLayerIsZeroOneOrTwoLayersOfTheAxisymmetricMesh) {
  const auto c =
      parse_case(kMinimal + "[numerics]\nmodel = \"axisymmetric\"\nfan_layer = 2\n", "case.toml");
  ASSERT_TRUE(c.numerics.fan_layer.has_value());
  EXPECT_EQ(*c.numerics.fan_layer, 2);
  EXPECT_FALSE(parse_case(kMinimal, "case.toml").numerics.fan_layer.has_value());
  for (const auto* bad : {"3", "-1", "true", "\"2\"", "1.5"}) {
    expect_error(kMinimal + "[numerics]\nfan_layer = " + bad + "\n",
                 {"numerics.fan_layer must be 0, 1 or 2"});
  }
  expect_error(kMinimal + "[numerics]\nfan_layer = 1\ncrease_fan = \"2 mm\"\n",
               {"numerics.fan_layer", "numerics.crease_fan"});
}

TEST(CaseFile, TheLawIsNeoHookeanUnlessGentWithItsLockingValue) {
  EXPECT_EQ(parse_case(kMinimal, "case.toml").material.law, Law::NeoHookean);
  const auto gent =
      replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2 MPa\"\nlaw = \"Gent\"\ngent_jm = 20");
  const auto c = parse_case(gent, "case.toml");
  EXPECT_EQ(c.material.law, Law::Gent);
  EXPECT_EQ(c.material.gent_jm, 20.0);
  // Written and read back: the law and its parameter survive.
  const auto r = parse_case(to_toml(c), "written.toml");
  EXPECT_EQ(r.material.law, Law::Gent);
  EXPECT_EQ(r.material.gent_jm, 20.0);
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2 MPa\"\nlaw = \"Gent\""),
               {"material.law = \"Gent\" needs material.gent_jm"});
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2 MPa\"\ngent_jm = 20"),
               {"material.gent_jm", "Gent's law"});
  expect_error(replace(gent, "gent_jm = 20", "gent_jm = -1"), {"material.gent_jm", "positive"});
  expect_error(replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2 MPa\"\nlaw = \"Mooney\""),
               {"case.toml:", "material.law must be \"neo-Hookean\" or \"Gent\""});
}

TEST(CaseFile, BadOverrideNamesTheFlag) {
  expect_error(kMinimal, {"--R", "shell.R", "is a mass"}, {{"shell.R", "30 g", "--R"}});
}

TEST(CaseFile, WrittenInSIAndReadBackTheSame) {
  const std::vector<Override> o = {{"protocol.delta_p_j", "2.5 kPa", "--delta-p-j"}};
  auto c = parse_case(kMinimal, "case.toml", o);
  c.numerics.resolution = Resolution::Coarse;
  c.numerics.model = Model::Axisymmetric;
  c.numerics.end_time = 0.3;
  c.numerics.bulk_integration = BulkIntegration::Full;
  c.protocol.inverted_snaps = InvertedSnaps::AlongBranch;
  const auto r = parse_case(to_toml(c), "written.toml");
  EXPECT_EQ(r.protocol.inverted_snaps, InvertedSnaps::AlongBranch);
  EXPECT_EQ(r.numerics.model, Model::Axisymmetric);
  EXPECT_EQ(r.numerics.bulk_integration, BulkIntegration::Full);
  EXPECT_FALSE(parse_case(to_toml(parse_case(kMinimal, "case.toml")), "again.toml")
                   .numerics.bulk_integration)
      << "absent stays absent: each model keeps its own default";
  EXPECT_EQ(r.title, c.title);
  EXPECT_EQ(r.shell.R, c.shell.R);
  EXPECT_EQ(r.shell.h, c.shell.h);
  EXPECT_EQ(r.shell.phi, c.shell.phi);
  EXPECT_EQ(r.material.E, c.material.E);
  EXPECT_EQ(r.material.nu, c.material.nu);
  EXPECT_EQ(r.material.rho, c.material.rho);
  EXPECT_EQ(r.popper.net_weight, c.popper.net_weight);
  EXPECT_EQ(r.popper.mass, c.popper.mass);
  EXPECT_EQ(r.popper.wire_stiffness, c.popper.wire_stiffness);
  EXPECT_EQ(r.friction.mu, c.friction.mu);
  EXPECT_EQ(r.gas.container_volume, c.gas.container_volume);
  EXPECT_EQ(r.gas.alpha_n, c.gas.alpha_n);
  EXPECT_EQ(r.gas.beta_n, c.gas.beta_n);
  EXPECT_EQ(r.protocol.delta_p_j, c.protocol.delta_p_j);
  EXPECT_EQ(r.numerics.resolution, Resolution::Coarse);
  EXPECT_EQ(r.numerics.end_time, c.numerics.end_time);
}

// Any title and any source file name survive the round trip: the case file a
// run writes back must read again, or the run cannot be resumed and a sweep's runs all fail.
TEST(CaseFile, HostileStringsSurviveTheRoundTrip) {
  std::string every;
  for (int ch = 1; ch < 128; ++ch) every += static_cast<char>(ch);
  const std::vector<std::string> titles = {"it's \"quoted\"",
                                           "two\nlines\r\n[shell]\nR = 1",
                                           "back\\slash \\u0041 \\n",
                                           "tab\there",
                                           "\"\"\"triple\"\"\"",
                                           "'''literal'''",
                                           "# not a comment",
                                           "ünïcödé – δp ≥ 0",
                                           every,
                                           ""};
  for (const auto& title : titles) {
    auto c = parse_case(kMinimal, "case.toml");
    c.title = title;
    c.source = "dir\nwith \"odd\" name/" + title + ".toml";
    c.gas.p0 = 98765.4321;
    c.numerics.element_size = 1.0 / 3.0 * 1e-3;
    c.numerics.elements_through_thickness = 2;
    c.numerics.end_time = 0.1 + 0.2;  // not a short decimal
    const auto text = to_toml(c);
    Case r;
    ASSERT_NO_THROW(r = parse_case(text, "written.toml")) << text;
    EXPECT_EQ(r.title, title);
    EXPECT_EQ(r.gas.p0, c.gas.p0);
    EXPECT_EQ(r.numerics.element_size, c.numerics.element_size);
    EXPECT_EQ(r.numerics.elements_through_thickness, 2);
    EXPECT_EQ(r.numerics.end_time, c.numerics.end_time);
    const auto body = [](const std::string& t) { return t.substr(t.find('\n')); };  // no comment
    EXPECT_EQ(body(to_toml(r)), body(text)) << "written twice, the same values";
  }
}

TEST(CaseFile, BareNumbersAndImplausibleValuesAreNoted) {
  const auto units = parse_case(kMinimal, "case.toml");
  EXPECT_TRUE(units.bare_numbers.empty());
  EXPECT_TRUE(units.implausible.empty());
  // A bare number that reads as a plausible value, in the file and by a flag.
  const auto bare = parse_case(replace(kMinimal, "R = \"30 mm\"", "R = 0.03"), "case.toml",
                               std::vector<Override>{{"shell.h", "0.002", "--h"}});
  ASSERT_EQ(bare.bare_numbers.size(), 2U);
  EXPECT_NE(bare.bare_numbers[0].find("case.toml:2: shell.R = 0.03 has no unit and is read in "
                                      "SI, as 0.03 m"),
            std::string::npos)
      << bare.bare_numbers[0];
  EXPECT_NE(bare.bare_numbers[1].find("--h: shell.h = 0.002"), std::string::npos);
  EXPECT_TRUE(bare.implausible.empty());
  // A bare number that reads as no popper's: implausible (and not also bare), naming the range.
  const auto metres = parse_case(replace(kMinimal, "E = \"1.2 MPa\"", "E = \"1.2\""), "case.toml");
  ASSERT_EQ(metres.implausible.size(), 1U);
  EXPECT_TRUE(metres.bare_numbers.empty());
  for (const char* part :
       {"case.toml:6: material.E = \"1.2\" is read as 1.2 Pa", "1 kPa .. 10 GPa", "\"1.2 MPa\""}) {
    EXPECT_NE(metres.implausible[0].find(part), std::string::npos) << metres.implausible[0];
  }
  // The case a run writes carries units: read back, it has no bare numbers.
  auto c = units;
  c.numerics.end_time = 0.5;
  const auto text = to_toml(c);
  EXPECT_NE(text.find("R = \"0.03 m\""), std::string::npos) << text;
  EXPECT_TRUE(parse_case(text, "written.toml").bare_numbers.empty());
}

TEST(CaseFile, PlausibleRangesBoundKnownKeysAndHoldThePapersPoppers) {
  const auto c = default_case();
  for (const auto& r : plausible_ranges()) {
    const auto* k = find_quantity_key(r.key);
    ASSERT_NE(k, nullptr) << r.key;
    EXPECT_LT(r.lo, r.hi) << r.key;
    EXPECT_FALSE(r.why.empty()) << r.key;
    auto copy = c;
    const double v = k->field ? *k->field(copy) : 0.0;
    EXPECT_TRUE(r.holds(v)) << r.key << " = " << v;
  }
  EXPECT_EQ(plausible_range("material.nu"), nullptr);
}

TEST(CaseFile, MissingFile) {
  EXPECT_THROW((void)load_case_file("/nonexistent/case.toml"), CaseError);
}

TEST(CaseFile, DefaultCaseIsThePapersFig2aPopper) {
  const auto c = default_case();
  EXPECT_DOUBLE_EQ(c.shell.R, 0.030);
  EXPECT_DOUBLE_EQ(c.shell.h, 0.002);
  EXPECT_DOUBLE_EQ(c.material.E, 1.2e6);
  EXPECT_DOUBLE_EQ(c.popper.net_weight, 0.48);
}

TEST(CaseFile, ExamplesLoadAndDefaultMatchesItsExample) {
  const std::filesystem::path dir = std::filesystem::path(SNAPJUMP_SOURCE_DIR) / "examples";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    if (entry.path().filename().string().rfind("sweep", 0) == 0) continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW((void)load_case_file(entry.path()));
    ++count;
  }
  EXPECT_GE(count, 5);
  const auto file = load_case_file(dir / "default.toml");
  const auto builtin = default_case();
  EXPECT_DOUBLE_EQ(file.shell.R, builtin.shell.R);
  EXPECT_DOUBLE_EQ(file.shell.h, builtin.shell.h);
  EXPECT_DOUBLE_EQ(file.shell.phi, builtin.shell.phi);
  EXPECT_DOUBLE_EQ(file.material.E, builtin.material.E);
  EXPECT_DOUBLE_EQ(file.popper.net_weight, builtin.popper.net_weight);
}

}  // namespace
}  // namespace snapjump::config
