#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "app/cli.hpp"
#include "config/case.hpp"
#include "io/atomic_file.hpp"
#include "io/folder_lock.hpp"
#include "measure/time_series.hpp"
#include "mesh/cap_mesher.hpp"
#include "mesh/msh_reader.hpp"
#include "plot/gnuplot.hpp"
#include "support/cli_runner.hpp"
#include "support/hostile_text.hpp"
#include "sweep/sweep.hpp"

namespace snapjump::app {
namespace {

using Result = test_support::CliResult;

Result run(std::vector<std::string> args) { return test_support::run_cli(std::move(args)); }

std::string example(const std::string& name) {
  return (std::filesystem::path(SNAPJUMP_SOURCE_DIR) / "examples" / name).string();
}

TEST(Cli, HelpTellsWhatToType) {
  const auto top = run({"--help"});
  EXPECT_EQ(top.code, kExitOk);
  EXPECT_NE(top.out.find("predict"), std::string::npos);
  const auto sub = run({"predict", "--help"});
  EXPECT_EQ(sub.code, kExitOk);
  EXPECT_NE(sub.out.find("--net-weight"), std::string::npos);
  EXPECT_NE(sub.out.find("--format"), std::string::npos);
}

TEST(Cli, NoSubcommandIsAnError) {
  const auto r = run({});
  EXPECT_EQ(r.code, kExitBadInput);
}

TEST(Cli, PredictDefaultCaseTable) {
  const auto r = run({"predict"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("predicted outcome: Jump"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("defaults used"), std::string::npos);
  EXPECT_NE(r.out.find("material.nu = 0.45"), std::string::npos);
  EXPECT_NE(r.out.find("F*  peak plate force"), std::string::npos);
}

TEST(Cli, PredictJsonIsMachineReadableSI) {
  const auto r = run({"predict", "--format", "json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["units"], "SI");
  EXPECT_NEAR(doc["quantities"]["F_c"]["lower"].get<double>(), 0.32, 1e-12);
  EXPECT_EQ(doc["quantities"]["F_c"]["unit"], "N");
  EXPECT_LT(doc["quantities"]["F_star"]["lower"].get<double>(),
            doc["quantities"]["F_star"]["upper"].get<double>());
  EXPECT_EQ(doc["outcome_text"], "Jump");
}

TEST(Cli, PredictCsv) {
  const auto r = run({"predict", "--format", "csv"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(r.out.rfind("quantity,lower,upper,unit\n", 0), 0u);
  EXPECT_NE(r.out.find("\nr_c,0.007745966692,0.007745966692,m\n"), std::string::npos) << r.out;
}

TEST(Cli, FlagsWithUnitsOverrideTheCase) {
  const auto r =
      run({"predict", "--R", "25mm", "--h", "2.5 mm", "--nu", "0.5", "--format", "json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(doc["case"]["R"].get<double>(), 0.025);
  // F_c = 1.2e6 * (2.5e-3)^3 / 0.025 = 0.75 N
  EXPECT_NEAR(doc["quantities"]["F_c"]["lower"].get<double>(), 0.75, 1e-12);
}

TEST(Cli, PredictFromCaseFile) {
  const auto r = run({"predict", example("R30_h1.0.toml"), "--format", "json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(doc["case"]["h"].get<double>(), 0.001);
}

TEST(Cli, BadFlagValueNamesTheFlag) {
  const auto r = run({"predict", "--R", "30kg"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--R"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is a mass, but a length is needed"), std::string::npos) << r.err;
}

TEST(Cli, PredictRefusesACaseItCannotEvaluate) {
  // h = 1e-310 m is positive and smaller than R, but t_c overflows: an error, not "inf".
  const auto r = run({"predict", "--h", "1e-310m", "--allow-implausible"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("non-finite"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
}

TEST(Cli, BareNumbersThatReadAsNoPopperAreRefused) {
  // mm, MPa and N meant; read in SI: a shell of 40 m, 3 m thick, of 0.8 Pa.
  const auto r = run({"predict", "--R", "40", "--h", "3", "--E", "0.8", "--net-weight", "1"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_EQ(r.out.find("predicted outcome"), std::string::npos) << r.out;
  for (const char* part :
       {"error: the case lies outside what a popper can plausibly be",
        "--R: shell.R = 40 is read as 40 m (a number without a unit is in SI), outside 1 mm .. 1 m",
        "e.g. \"40 mm\"", "--h: shell.h = 3 is read as 3 m",
        "--E: material.E = 0.8 is read as 0.8 Pa", "--allow-implausible",
        "warning: --net-weight: popper.net_weight = 1 has no unit and is read in SI, as 1 N"}) {
    EXPECT_NE(r.err.find(part), std::string::npos) << part << "\n" << r.err;
  }
  // A case file's bare number is named by its line; --allow-implausible takes it, warning.
  const auto path = std::filesystem::temp_directory_path() / "snapjump_cli_bare.toml";
  std::ofstream(path) << "[shell]\nR = 30\nh = \"2 mm\"\n[material]\nE = \"1.2 MPa\"\n"
                         "[popper]\nnet_weight = \"0.48 N\"\n";
  const auto file = run({"predict", path.string(), "--no-branch"});
  EXPECT_EQ(file.code, kExitBadInput);
  EXPECT_NE(file.err.find("snapjump_cli_bare.toml:2: shell.R = 30 is read as 30 m"),
            std::string::npos)
      << file.err;
  const auto allowed = run({"predict", path.string(), "--no-branch", "--allow-implausible"});
  EXPECT_EQ(allowed.code, kExitOk) << allowed.err;
  EXPECT_NE(allowed.err.find("warning: " + path.string() + ":2: shell.R = 30 is read as 30 m"),
            std::string::npos)
      << allowed.err;
}

TEST(Cli, ABareNumberIsReadInSIWithAWarningAndAUnitWordJoinsIt) {
  const auto r = run({"predict", "--R", "0.03", "--h", "2", "mm", "--E=1.2", "MPa", "--no-branch",
                      "--format", "json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(doc["case"]["h"].get<double>(), 0.002);
  EXPECT_DOUBLE_EQ(doc["case"]["E"].get<double>(), 1.2e6);
  EXPECT_NE(r.err.find("warning: --R: shell.R = 0.03 has no unit and is read in SI, as 0.03 m"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("shell.h"), std::string::npos) << r.err;
  // A word that is no unit stays the case file.
  const auto file = run({"predict", "--R", "30", "no-such-case.toml"});
  EXPECT_EQ(file.code, kExitBadInput);
  EXPECT_NE(file.err.find("no-such-case.toml"), std::string::npos) << file.err;
}

TEST(Cli, AThickShellGetsWhatCanBeComputedAndAnUnknownOutcome) {
  const auto r = run({"predict", "--h", "6mm", "--no-branch"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.err.find("warning: the predicted outcome is unknown: the indentation at the onset"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("predicted outcome: unknown: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("F*  peak plate force"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  const auto j = run({"predict", "--h", "6mm", "--no-branch", "--format", "json"});
  ASSERT_EQ(j.code, kExitOk) << j.err;
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_TRUE(doc["quantities"]["H_l"]["lower"].is_null());
  EXPECT_GT(doc["quantities"]["H_l"]["upper"].get<double>(), 0.0);
  EXPECT_TRUE(doc["quantities"]["F_star"]["upper"].is_number());
  EXPECT_TRUE(doc["outcome"].empty());
  EXPECT_EQ(doc["outcome_text"].get<std::string>().rfind("unknown: ", 0), 0U);
  EXPECT_TRUE(doc["beyond_range"].is_string());
}

TEST(Cli, UnphysicalFlagIsRejected) {
  const auto r = run({"predict", "--h", "40mm"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("must be smaller than shell.R"), std::string::npos) << r.err;
}

TEST(Cli, BadCaseFileNamesTheLine) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "bad.toml";
  std::ofstream(path) << "[shell]\nR = \"30 mm\"\nh = \"2 mm\"\ncolour = \"red\"\n";
  const auto r = run({"predict", path.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("bad.toml:4"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("unknown key 'colour'"), std::string::npos) << r.err;
}

TEST(Cli, MissingCaseFile) {
  const auto r = run({"predict", "/nonexistent/case.toml"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_FALSE(r.err.empty());
}

TEST(Cli, UnknownFormat) {
  const auto r = run({"predict", "--format", "xml"});
  EXPECT_EQ(r.code, kExitBadInput);
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

TEST(Cli, ContactPrintsTheComputedConstantsAndBounds) {
  const auto path = std::filesystem::temp_directory_path() / "snapjump_cli_curves.csv";
  std::filesystem::remove(path);
  const auto r = run({"contact", "--nu", "0.5", "--format", "json", "--curves", path.string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  // The paper's N+ = 76.94 and, at nu = 1/2, 1.2 < alpha_r < 1.6.
  EXPECT_NEAR(doc["N_plus"]["N"].get<double>(), 76.94, 0.01 * 76.94);
  EXPECT_NEAR(doc["bounds"]["alpha_r"]["lower"].get<double>(), 1.2, 0.05);
  EXPECT_NEAR(doc["bounds"]["alpha_r"]["upper"].get<double>(), 1.6, 0.05);
  std::ifstream csv(path);
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "branch,a,N,e_hat,c1,residual,min_gap");
  int disk = 0, ring = 0;
  for (std::string line; std::getline(csv, line);) {
    if (line.rfind("disk,", 0) == 0) ++disk;
    if (line.rfind("ring,", 0) == 0) ++ring;
  }
  EXPECT_GT(disk, 10);
  EXPECT_GT(ring, 5);
}

TEST(Cli, ContactRejectsBadNu) {
  const auto r = run({"contact", "--nu", "0.7"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--nu"), std::string::npos);
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

TEST(Cli, AnalyzeAMeasuredSeriesWithUnits) {
  const auto path = std::filesystem::temp_directory_path() / "snapjump_cli_series.csv";
  // w crosses 0.03 R = 0.9 mm at t = 20.2 ms (linear between 1.0 mm at 20 ms and 0.5 mm at
  // 21 ms); the force peaks at 2.5 N and is 0 from 24 ms on; z peaks at 22 mm.
  std::ofstream(path) << "t [ms],F [N],z [mm],w [mm]\n"
                         "0,0.48,0,20\n10,0.6,5,10\n20,0.7,10,1.0\n21,2.5,10.5,0.5\n"
                         "22,2.0,11,0.2\n23,0.5,12,0.1\n24,0.0,13,0.5\n30,0.0,20,6\n"
                         "40,0.0,22,8\n50,0.0,18,5\n";
  const auto r = run({"analyze", path.string(), "--R", "30mm", "--format", "json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["outcome"], "Jump");
  EXPECT_NEAR(doc["quantities"]["F_star"]["value"].get<double>(), 2.5, 1e-12);
  EXPECT_NEAR(doc["quantities"]["H"]["value"].get<double>(), 0.022, 1e-12);
  EXPECT_NEAR(doc["quantities"]["H_l"]["value"].get<double>(), 0.0101, 1e-9);
}

TEST(Cli, AnalyzeNamesTheBadCell) {
  const auto path = std::filesystem::temp_directory_path() / "snapjump_cli_bad_series.csv";
  std::ofstream(path) << "t,F\n0,1\n0.1,abc\n";
  const auto r = run({"analyze", path.string(), "--R", "30mm"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(":3"), std::string::npos) << r.err;
}

TEST(Cli, UnknownWordsAreNamedWithASuggestion) {
  const auto r = run({"predict", "--r", "30mm"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("unknown option --r for 'snapjump predict'; did you mean --R?"),
            std::string::npos)
      << r.err;
  const auto sub = run({"analyse", "x.csv"});
  EXPECT_EQ(sub.code, kExitBadInput);
  EXPECT_NE(sub.err.find("unknown subcommand 'analyse'"), std::string::npos) << sub.err;
  EXPECT_NE(sub.err.find("did you mean analyze?"), std::string::npos) << sub.err;
  const auto nested = run({"plot", "seris", "x"});
  EXPECT_NE(nested.err.find("did you mean series?"), std::string::npos) << nested.err;
  const auto far = run({"run", "--zzzzzz"});
  EXPECT_NE(far.err.find("unknown option --zzzzzz"), std::string::npos) << far.err;
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
  EXPECT_EQ(run({"predict", "--format=json"}).code, kExitOk);
}

TEST(Cli, AFlagThatChangesTheCaseSaysSoInTheTitle) {
  const auto r = run({"predict", example("R30_h1.5.toml"), "--h", "2mm", "--format", "json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("[changed: shell.h = 2mm]"), std::string::npos) << r.out.substr(0, 600);
  const auto plain = run({"predict", example("R30_h1.5.toml"), "--format", "json"});
  EXPECT_EQ(plain.out.find("[changed:"), std::string::npos);
}

TEST(Cli, AnalyzeRefusesAHeaderAlone) {
  const auto path = std::filesystem::temp_directory_path() / "snapjump_cli_header_only.csv";
  std::ofstream(path) << "t [ms],F [N]\n";
  const auto r = run({"analyze", path.string(), "--R", "30mm"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("no rows"), std::string::npos) << r.err;
}

TEST(Cli, AnalyzeSaysWhatABareRMeansAndWhyAnOutcomeIsOpen) {
  const auto path = std::filesystem::temp_directory_path() / "snapjump_cli_bare_r.csv";
  // The ring stage only: w is still 5 mm, the suction 1.5 kPa.
  std::ofstream(path) << "t [ms],F [N],w [mm],delta_p [kPa]\n0,0.48,6,2\n10,0.48,5,1.5\n";
  const auto r = run({"analyze", path.string(), "--R", "30"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("not the radius of a popper's shell"), std::string::npos) << r.out;
  const auto mm = run({"analyze", path.string(), "--R", "30mm"});
  EXPECT_NE(mm.out.find("undetermined"), std::string::npos) << mm.out;
  EXPECT_NE(mm.out.find("suction still holding the shell"), std::string::npos) << mm.out;
  const auto complete = run({"analyze", path.string(), "--R", "30mm", "--complete"});
  EXPECT_NE(complete.out.find("No snap"), std::string::npos) << complete.out;
}

TEST(Cli, AnalyzeSeveralLabRecordsIntoOneTable) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto a = dir / "snapjump_cli_lab_a.csv";
  const auto b = dir / "snapjump_cli_lab_b.csv";
  const auto bad = dir / "snapjump_cli_lab_bad.csv";
  // A lab's own spelling: ';' separators, a time in ms named "Zeit", a force in mN by flag.
  const std::string record =
      "Zeit;Kraft;\"w (mm)\"\n0;480;20\n10;600;10\n20;700;1,0\n21;2500;0,5\n22;2000;0,2\n"
      "23;500;0,1\n24;0;0,5\n30;0;6\n40;0;8\n50;0;5\n";
  std::ofstream(a) << record;
  std::ofstream(b) << record;
  std::ofstream(bad) << "Zeit;Kraft\n0;abc\n";
  const auto r =
      run({"analyze", a.string(), b.string(), bad.string(), "--R", "30mm", "--column", "t=Zeit",
           "--column", "F=Kraft", "--unit", "t=ms", "--unit", "F=mN", "--format", "csv"});
  EXPECT_EQ(r.code, kExitBadInput);  // one record failed; the others are in the table
  std::istringstream lines(r.out);
  std::string header, row_a, row_b, row_bad;
  std::getline(lines, header);
  std::getline(lines, row_a);
  std::getline(lines, row_b);
  std::getline(lines, row_bad);
  EXPECT_EQ(header.rfind("file,outcome,t_onset,r_star,e_star,F_star,", 0), 0U) << header;
  EXPECT_NE(row_a.find(",Jump,"), std::string::npos) << row_a;
  EXPECT_NE(row_a.find(",2.5,"), std::string::npos) << row_a;  // F* in N
  EXPECT_EQ(row_a.substr(row_a.find(',')), row_b.substr(row_b.find(','))) << row_b;
  EXPECT_NE(row_bad.find("is not a finite number"), std::string::npos) << row_bad;
  EXPECT_NE(r.err.find("snapjump_cli_lab_bad.csv:2"), std::string::npos) << r.err;
}

// A record compared with a run folder that holds the same series: every difference of a
// quantity the two read alike is zero and within the record's uncertainty; what is not a run
// folder is refused naming what is missing.
TEST(Cli, CompareARecordWithARunFolder) {
  namespace fs = std::filesystem;
  const auto dir = fs::temp_directory_path() / "snapjump_cli_compare";
  fs::remove_all(dir);
  fs::create_directories(dir / "run");
  const std::string series =
      "t [ms],F [mN],w [mm],z [mm]\n0,480,20,0\n10,600,10,5\n20,700,1.0,10\n21,2500,0.5,10\n"
      "22,2000,0.2,10\n23,500,0.1,10\n24,0,0.5,11\n30,0,6,20\n40,0,8,25\n50,0,5,26\n"
      "60,0,5,24\n";
  std::ofstream(dir / "rec.csv") << series;
  std::ofstream(dir / "run" / "series.csv") << series;
  fs::copy_file(example("default.toml"), dir / "run" / "case.toml");
  const auto r = run({"compare", (dir / "rec.csv").string(), (dir / "run").string(), "--format",
                      "json", "--no-figure", "--complete"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["units"], "SI");
  EXPECT_EQ(j["outcomes"]["records"][0], j["outcomes"]["run"]);
  const auto& t = j["quantities"]["t_star"];
  ASSERT_TRUE(t["record"].is_number()) << r.out;
  EXPECT_DOUBLE_EQ(t["difference"].get<double>(), 0.0);
  EXPECT_TRUE(t["within"].get<bool>());
  EXPECT_EQ(t["source"], "t, w, F, z");  // the onset from w; the launch from F, checked by z
  // The run's F* is read through the paper's 170 Hz plate, the record's as recorded.
  EXPECT_EQ(j["quantities"]["F_star"]["run_key"], "F_star_plate");
  const auto table = run(
      {"compare", (dir / "rec.csv").string(), (dir / "run").string(), "--no-figure", "--complete"});
  ASSERT_EQ(table.code, kExitOk) << table.err;
  EXPECT_NE(table.out.find("t_star"), std::string::npos) << table.out;

  const auto not_dir = run({"compare", (dir / "rec.csv").string(), (dir / "rec.csv").string()});
  EXPECT_EQ(not_dir.code, kExitBadInput);
  EXPECT_NE(not_dir.err.find("is not a folder"), std::string::npos) << not_dir.err;
  fs::remove(dir / "run" / "case.toml");
  const auto no_case = run({"compare", (dir / "rec.csv").string(), (dir / "run").string()});
  EXPECT_EQ(no_case.code, kExitBadInput);
  EXPECT_NE(no_case.err.find("no case.toml"), std::string::npos) << no_case.err;
  fs::remove_all(dir);
}

// Every design `snapjump design` lists meets its target when its R, h and net weight are fed
// back to `snapjump predict`; an infeasible target names what binds; a bad constraint names the
// flag.
TEST(Cli, DesignsMeetTheirTargetsThroughPredict) {
  const auto r = run({"design", "--jump-height", "50mm", "--net-weight", "1N", "--E", "1.2MPa",
                      "--footprint", "80mm", "--count", "3", "--no-branch", "--format", "json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_FALSE(j["designs"].empty());
  for (const auto& d : j["designs"]) {
    const auto p = run({"predict", "--R", fmt::format("{}m", d["R"].get<double>()), "--h",
                        fmt::format("{}m", d["h"].get<double>()), "--net-weight", "1N", "--E",
                        "1.2MPa", "--no-branch", "--format", "json"});
    ASSERT_EQ(p.code, kExitOk) << p.err;
    const auto q = nlohmann::json::parse(p.out);
    EXPECT_GE(q["quantities"]["H"]["lower"].get<double>(), 0.050);
    EXPECT_EQ(q["outcome_text"], "Jump");
    EXPECT_LE(d["footprint"].get<double>(), 0.080 + 1e-12);
  }
  const auto energy =
      run({"design", "--energy", "5mJ", "--count", "2", "--no-branch", "--format", "json"});
  ASSERT_EQ(energy.code, kExitOk) << energy.err;
  for (const auto& d : nlohmann::json::parse(energy.out)["designs"]) {
    EXPECT_GE(d["stored_energy"].get<double>(), 5e-3);
  }
  const auto none = run({"design", "--jump-height", "100m", "--no-branch"});
  EXPECT_EQ(none.code, kExitBadInput);
  EXPECT_NE(none.err.find("misses by"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("H's lower bound"), std::string::npos) << none.err;
  const auto bad = run({"design", "--footprint", "-1mm"});
  EXPECT_EQ(bad.code, kExitBadInput);
  EXPECT_NE(bad.err.find("--footprint"), std::string::npos) << bad.err;
  const auto unit = run({"design", "--jump-height", "50N"});
  EXPECT_EQ(unit.code, kExitBadInput);
  EXPECT_NE(unit.err.find("--jump-height"), std::string::npos) << unit.err;
}

TEST(Cli, AnalyzeRejectsAWrongUnitOnAFlag) {
  const auto path = std::filesystem::temp_directory_path() / "snapjump_cli_series2.csv";
  std::ofstream(path) << "t,F\n0,1\n0.1,0\n";
  const auto r = run({"analyze", path.string(), "--R", "30 N"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--R"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

TEST(Cli, AReciprocalOrShiftedUnitIsRefusedNamingTheKey) {
  // UDUNITS converts a unit to its reciprocal (0.5 m^-1 to 2 m) and reads '@' as an offset.
  const std::vector<std::vector<std::string>> flags{
      {"--R", "0.5 m^-1", "shell.R", "length"},
      {"--R", "30 mm^-1", "shell.R", "length"},
      {"--E", "1 Pa^-1", "material.E", "pressure"},
      {"--end-time", "1 Hz", "numerics.end_time", "time"},
      {"--R", "30 mm @ 5", "shell.R", "'@'"},
      {"--R", "30 mm^99999999999999999999", "shell.R", "from -4 to 4"}};
  for (const auto& f : flags) {
    const auto r = run({"predict", f[0], f[1]});
    EXPECT_EQ(r.code, kExitBadInput) << f[1] << ": " << r.out;
    EXPECT_NE(r.err.find(f[0] + ": " + f[2]), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(f[3]), std::string::npos) << r.err;
  }
  // A record's header: t in Hz would invert the times, F in 1/N the forces.
  const auto dir = std::filesystem::temp_directory_path() /
                   fmt::format("snapjump_cli_reciprocal_{}", ::getpid());
  std::filesystem::create_directories(dir);
  for (const auto& header : {"t [Hz],F [N]", "t [s],F [N^-1]"}) {
    const auto path = dir / "record.csv";
    std::ofstream(path) << header << "\n1,0.5\n2,0.4\n4,0.0\n";
    const auto r = run({"analyze", path.string(), "--R", "30mm"});
    EXPECT_EQ(r.code, kExitBadInput) << header << ": " << r.out;
    EXPECT_NE(r.err.find("is the reciprocal of a"), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

TEST(Cli, InputsThatAskForUnboundedMemoryAreRefusedCheaply) {
  const auto dir =
      std::filesystem::temp_directory_path() / fmt::format("snapjump_cli_unbounded_{}", ::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto start = std::chrono::steady_clock::now();
  // A range of 1e11 values: refused by the sweep's cap before one value is made.
  std::ofstream(dir / "big.toml") << "title = \"big\"\n[vary]\n"
                                     "friction.mu = {from = 0, to = 0.6, count = 100000000000}\n";
  const auto sweep = run({"sweep", (dir / "big.toml").string(), "--dry-run"});
  EXPECT_EQ(sweep.code, kExitBadInput) << sweep.out;
  EXPECT_NE(sweep.err.find("friction.mu: count = 100000000000 is more runs than a sweep holds "
                           "(100000)"),
            std::string::npos)
      << sweep.err;
  // Two ranges of 1e5 each: 1e10 runs, refused as the product grows.
  std::ofstream(dir / "product.toml")
      << "[vary]\nfriction.mu = {from = 0, to = 0.6, count = 100000}\n"
         "shell.h = {from = \"1 mm\", to = \"2 mm\", count = 100000}\n";
  const auto product = run({"sweep", (dir / "product.toml").string(), "--dry-run"});
  EXPECT_EQ(product.code, kExitBadInput);
  EXPECT_NE(product.err.find("more than a sweep holds (100000)"), std::string::npos) << product.err;
  // A header of 2e7 separators (20 MB).
  std::ofstream(dir / "wide.csv") << "t,F" << std::string(20'000'000, ',') << "\n0,1\n";
  const auto wide = run({"analyze", (dir / "wide.csv").string(), "--R", "30 mm"});
  EXPECT_EQ(wide.code, kExitBadInput);
  EXPECT_NE(wide.err.find("wide.csv:1: more than 1000 cells on one line"), std::string::npos)
      << wide.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  std::filesystem::remove_all(dir);
}

// Running out of memory ends a command with a message that says so and status 1: the command
// runs in a child process whose address space is held to 32 MB more than it had, and reads a
// record of 64 MB.
TEST(Cli, RunningOutOfMemoryIsNamedNotABareBadAlloc) {
  const auto dir = std::filesystem::temp_directory_path() /
                   fmt::format("snapjump_cli_out_of_memory_{}", ::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto record = dir / "huge.csv";
  {
    std::ofstream csv(record);
    csv << "t,F\n";
    const std::string row = "0.001,0.5\n";
    for (std::size_t n = 0; n < 64u * 1024 * 1024 / row.size(); ++n) csv << row;
  }
  const auto err_file = dir / "err.txt";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::ifstream statm("/proc/self/statm");
    std::size_t pages = 0;
    statm >> pages;
    const auto limit =
        static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) + (32u << 20);
    const rlimit r{limit, limit};
    if (::setrlimit(RLIMIT_AS, &r) != 0) ::_exit(100);
    const auto result = run({"analyze", record.string(), "--R", "30 mm"});
    { std::ofstream(err_file) << result.err; }
    ::_exit(result.code);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), kExitFailure);
  std::ifstream in(err_file);
  std::stringstream err;
  err << in.rdbuf();
  EXPECT_NE(err.str().find("error: out of memory while running snapjump analyze"),
            std::string::npos)
      << err.str();
  EXPECT_EQ(err.str().find("std::bad_alloc"), std::string::npos) << err.str();
  std::filesystem::remove_all(dir);
}

TEST(Cli, AnErrorQuotesAShortEscapedExcerptOfTheFile) {
  const auto dir =
      std::filesystem::temp_directory_path() / fmt::format("snapjump_cli_excerpt_{}", ::getpid());
  std::filesystem::create_directories(dir);
  // A file that is not a record: its first line is not echoed whole.
  const std::string secret = "root:$6$saltsalt$" + std::string(80, 'H') + ":19000:0:99999:7:::";
  std::ofstream(dir / "shadow") << secret << "\nbin:*:19000\n";
  const auto r = run({"analyze", (dir / "shadow").string(), "--R", "30 mm"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(secret.substr(0, 20)), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(secret.substr(0, 41)), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("19000"), std::string::npos) << r.err;
  // Control characters in a header or a cell reach the terminal escaped, and a forged line
  // cannot start.
  std::ofstream(dir / "esc.csv") << "t,\"F\x1b[31m\nerror: forged\"\n0,1\n1,abc\x1b[2J\n";
  const auto e = run({"analyze", (dir / "esc.csv").string(), "--R", "30 mm"});
  EXPECT_EQ(e.code, kExitBadInput);
  EXPECT_EQ(e.err.find('\x1b'), std::string::npos) << e.err;
  EXPECT_EQ(e.err.find("\nerror: forged"), std::string::npos) << e.err;
  EXPECT_NE(e.err.find("\\x1B"), std::string::npos) << e.err;
  // A title with an escape sequence and a line break is printed escaped.
  std::ifstream default_case(example("default.toml"));
  std::stringstream with_title;
  for (std::string line; std::getline(default_case, line);) {
    with_title << (line.starts_with("title") ? "title = \"pop\\u001b[2J\\nerror: forged\"" : line)
               << "\n";
  }
  std::ofstream(dir / "title.toml") << with_title.str();
  const auto t = run({"predict", (dir / "title.toml").string()});
  EXPECT_EQ(t.code, kExitOk) << t.err;
  EXPECT_EQ(t.out.find('\x1b'), std::string::npos);
  EXPECT_NE(t.out.find("snapjump predict: pop\\x1B[2J\\nerror: forged"), std::string::npos)
      << t.out.substr(0, 300);
  std::filesystem::remove_all(dir);
}

TEST(Cli, AWriteThatFailsNamesTheFileAndLeavesNoTemporary) {
  // Every write to /dev/full fails with ENOSPC, as on a full disk: the temporary file is made a
  // link to it.
  const auto dir =
      std::filesystem::temp_directory_path() / fmt::format("snapjump_cli_disk_full_{}", ::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto target = dir / "summary.json";
  std::ofstream(target) << "old\n";
  std::filesystem::create_symlink("/dev/full", dir / "summary.json.tmp");
  try {
    io::write_file_atomically(target, std::string(1 << 20, 'x'));
    ADD_FAILURE() << "a write to a full disk succeeded";
  } catch (const io::WriteFailed& e) {
    EXPECT_EQ(e.path(), target);
    EXPECT_NE(std::string(e.what()).find("could not write " + target.string()), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(std::strerror(ENOSPC)), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(dir / "summary.json.tmp")));
  std::ifstream in(target);
  std::string kept;
  std::getline(in, kept);
  EXPECT_EQ(kept, "old");
  std::filesystem::remove_all(dir);
}

TEST(Cli, RunNeverOverwritesAnOutputFolder) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_existing_run";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "series.csv") << "t,F\n";
  const auto r = run({"run", "--output", dir.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("never overwrites"), std::string::npos) << r.err;
  // the file that was there is untouched
  std::ifstream in(dir / "series.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,F");
}

TEST(Cli, ARunThatFailsAfterItsFolderIsMadeSaysSoInItsSummary) {
  // A popper lighter than its own shell is found only when the shell is built, after the folder
  // and its summary exist: the summary must not stay at "running".
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_failed_run";
  std::filesystem::remove_all(dir);
  const auto r = run({"run", "--model", "axisymmetric", "--net-weight", "0.05N", "--popper-mass",
                      "10g", "--output", dir.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  std::ifstream in(dir / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("\"status\": \"failed: popper.mass"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\"case\""), std::string::npos);  // what it held is kept
}

TEST(Cli, TheGroundedShellsInnerSurfaceIsPrintedAndKeptInTheSummary) {
  // The coarse axisymmetric default popper's inner surface, 2.49 to 1 about 1.9 mm from the rim:
  // past the incompressible neo-Hookean crease threshold (2.4), short of its law's Biot
  // instability (2.95 at nu = 0.45); both thresholds come from src/fem/surface_instability.
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_inner_surface";
  std::filesystem::remove_all(dir);
  const auto r = run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--end-time",
                      "1ms", "--output", dir.string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("past the crease threshold and short of Biot's"), std::string::npos)
      << r.out;
  std::ifstream in(dir / "summary.json");
  const auto s = nlohmann::json::parse(in)["preparation"]["inner_surface"];
  const double ratio = s["ratio"].get<double>(), biot = s["biot_ratio"].get<double>();
  EXPECT_GT(ratio, s["crease_ratio"].get<double>());
  EXPECT_LT(ratio, biot);
  EXPECT_NEAR(biot, 2.954, 0.005);
  EXPECT_TRUE(s["past_crease_threshold"].get<bool>());
  EXPECT_FALSE(s["past_biot"].get<bool>());
  EXPECT_EQ(s["closed_creases"].get<int>(), 0);
  EXPECT_GT(s["from_rim"].get<double>(), 0.0);
  EXPECT_LT(s["from_rim"].get<double>(), 5e-3);
}

TEST(Cli, AClosedCreaseIsReportedAsSuch) {
  // The (25, 2.5) mm cap on square 1.25 mm elements, a crease seeded 3.55 mm from the rim, held
  // at 0.4 p_c: on its branch the crease starts at the notch and closes, and the grounded shell's
  // inner surface touches itself there, whatever its stretch ratio says of a smooth surface.
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_closed_crease";
  std::filesystem::remove_all(dir);
  const auto r =
      run({"run", example("R25_h2.5.toml"), "--model", "axisymmetric", "--resolution", "coarse",
           "--element-size", "1.25mm", "--crease-seed", "3.26mm", "--crease-seed-depth", "50um",
           "--delta-p-j-over-pc", "0.4", "--end-time", "1ms", "--output", dir.string(), "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("it touches itself in one place: creased"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("stays smooth"), std::string::npos) << r.out;
  std::ifstream in(dir / "summary.json");
  const auto s = nlohmann::json::parse(in)["preparation"]["inner_surface"];
  EXPECT_EQ(s["closed_creases"].get<int>(), 1);
  EXPECT_NEAR(s["from_rim"].get<double>(), 3.55e-3, 0.01e-3);
}

TEST(Cli, ACreaseFanIsPrintedAndKeptInTheSummaryAndRefusedByThe3DModel) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_crease_fan";
  std::filesystem::remove_all(dir);
  const auto r = run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--crease-fan",
                      "2mm", "--end-time", "1ms", "--output", dir.string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("crease fan  a crease's root at the inner surface's node"),
            std::string::npos)
      << r.out;
  std::ifstream in(dir / "summary.json");
  const auto n = nlohmann::json::parse(in)["numerics"];
  // The coarse (30, 2.0) mm cap's inner corner nodes are 29 mm x 80 deg / 21 = 1.93 mm apart:
  // the one nearest 2 mm is the first.
  EXPECT_NEAR(n["crease_fan_from_rim"].get<double>(), 29e-3 * 80.0 / 180.0 * 3.14159265 / 21, 1e-6);
  const auto three_d =
      run({"run", "--crease-fan", "2mm", "--end-time", "1ms", "--output", (dir / "3d").string()});
  EXPECT_EQ(three_d.code, kExitBadInput);
  EXPECT_NE(three_d.err.find("numerics.crease_fan"), std::string::npos) << three_d.err;
}

TEST(Cli, AFanLayerIsPrintedAndKeptInTheSummaryAndRefusedByThe3DModel) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_fan_layer";
  std::filesystem::remove_all(dir);
  const auto r = run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--fan-layer",
                      "1", "--end-time", "1ms", "--output", dir.string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("fan layer   the first 1 layer through h"), std::string::npos) << r.out;
  std::ifstream in(dir / "summary.json");
  const auto n = nlohmann::json::parse(in)["numerics"];
  EXPECT_EQ(n["fan_layer"].get<int>(), 1);
  // The coarse cap's 2 x 21 elements, and per column two more less the axis's diamond.
  EXPECT_EQ(n["elements"].get<int>(), 2 * 21 + 2 * 21 - 1);
  const auto deep = run({"run", "--model", "axisymmetric", "--fan-layer", "3", "--end-time", "1ms",
                         "--output", (dir / "deep").string()});
  EXPECT_EQ(deep.code, kExitBadInput);
  const auto three_d =
      run({"run", "--fan-layer", "1", "--end-time", "1ms", "--output", (dir / "3d").string()});
  EXPECT_EQ(three_d.code, kExitBadInput);
  EXPECT_NE(three_d.err.find("numerics.fan_layer"), std::string::npos) << three_d.err;
}

TEST(Cli, ASeededCreaseIsPrintedAndKeptInTheSummaryAndRefusedWhereTheMeshCannotTakeIt) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_crease_seed";
  std::filesystem::remove_all(dir);
  // Elements of 1 mm along and through (the coarse preset's two through h).
  const auto r = run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--element-size",
                      "1mm", "--crease-seed", "3mm", "--crease-seed-depth", "25um", "--end-time",
                      "1ms", "--output", dir.string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("seeded      a crease's root at the inner surface's node"),
            std::string::npos)
      << r.out;
  std::ifstream in(dir / "summary.json");
  const auto n = nlohmann::json::parse(in)["numerics"];
  // 42 elements along 29 mm x 80 deg: the inner corner node nearest 3 mm is the third.
  const double element = 29e-3 * 80.0 / 180.0 * 3.14159265 / 42;
  ASSERT_EQ(n["crease_seeds_from_rim"].size(), 1U);
  EXPECT_NEAR(n["crease_seeds_from_rim"][0].get<double>(), 3 * element, 1e-6);
  EXPECT_DOUBLE_EQ(n["crease_seed_depth"].get<double>(), 25e-6);
  EXPECT_EQ(n["elements"].get<int>(), 2 * 42 + 4);
  // A second rosette, given before the first in arc length: the summary lists them from the rim.
  const auto two =
      run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--element-size", "1mm",
           "--crease-seed", "7mm", "--second-crease-seed", "3mm", "--crease-seed-depth", "25um",
           "--end-time", "1ms", "--output", (dir / "two").string()});
  ASSERT_EQ(two.code, kExitOk) << two.err;
  EXPECT_NE(two.out.find("creases' roots at the inner surface's nodes"), std::string::npos)
      << two.out;
  std::ifstream in_two(dir / "two" / "summary.json");
  const auto n2 = nlohmann::json::parse(in_two)["numerics"];
  ASSERT_EQ(n2["crease_seeds_from_rim"].size(), 2U);
  EXPECT_NEAR(n2["crease_seeds_from_rim"][0].get<double>(), 3 * element, 1e-6);
  EXPECT_NEAR(n2["crease_seeds_from_rim"][1].get<double>(), 7 * element, 1e-6);
  EXPECT_EQ(n2["elements"].get<int>(), 2 * 42 + 8);
  const auto alone = run({"run", "--model", "axisymmetric", "--resolution", "coarse",
                          "--element-size", "1mm", "--second-crease-seed", "3mm", "--end-time",
                          "1ms", "--output", (dir / "alone").string()});
  EXPECT_EQ(alone.code, kExitBadInput);
  EXPECT_NE(alone.err.find("numerics.second_crease_seed"), std::string::npos) << alone.err;
  // The coarse preset's own elements are twice as long as deep.
  const auto flat =
      run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--crease-seed", "3mm",
           "--end-time", "1ms", "--output", (dir / "flat").string()});
  EXPECT_NE(flat.code, kExitOk);
  EXPECT_NE(flat.err.find("no longer than deep"), std::string::npos) << flat.err;
  const auto three_d =
      run({"run", "--crease-seed", "3mm", "--end-time", "1ms", "--output", (dir / "3d").string()});
  EXPECT_EQ(three_d.code, kExitBadInput);
  EXPECT_NE(three_d.err.find("numerics.crease_seed"), std::string::npos) << three_d.err;
}

TEST(Cli, RunSaysWhereALinkedOutputFolderReallyIs) {
  const auto base = std::filesystem::temp_directory_path() / "snapjump_cli_linked_output";
  std::filesystem::remove_all(base);
  std::filesystem::create_directories(base / "real");
  std::filesystem::create_directory_symlink(base / "real", base / "link");
  const auto r = run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--end-time",
                      "1ms", "--quiet", "--output", (base / "link" / "x").string()});
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(
      r.out.find("(that is " + (std::filesystem::canonical(base / "real") / "x").string() + ")"),
      std::string::npos)
      << r.out;
  EXPECT_TRUE(std::filesystem::exists(base / "real" / "x" / "summary.json"));
}

TEST(Cli, TwoProcessesNeverShareARunOrASweepFolder) {
  const auto base = std::filesystem::temp_directory_path() / "snapjump_cli_locks";
  std::filesystem::remove_all(base);
  // A run folder in use (a resume going on) cannot be resumed a second time.
  const auto run_dir = base / "run";
  std::filesystem::create_directories(run_dir);
  std::ofstream(run_dir / "case.toml") << config::to_toml(config::default_case());
  {
    const io::FolderLock held(run_dir, "run.lock", "the run folder");
    const auto r = run({"run", "--resume", run_dir.string()});
    EXPECT_NE(r.code, kExitOk);
    EXPECT_NE(r.err.find("in use by another process"), std::string::npos) << r.err;
  }
  // A sweep folder in use by another sweep: refused before anything is written or started.
  const auto sweep_dir = base / "sweep";
  std::filesystem::create_directories(sweep_dir);
  const auto file = base / "s.toml";
  std::ofstream(file) << "output = \"sweep\"\n[vary]\nfriction.mu = [0.1, 0.2]\n";
  {
    const io::FolderLock held(sweep_dir, "sweep.lock", "the sweep folder");
    const auto r = run({"sweep", file.string()});
    EXPECT_NE(r.code, kExitOk);
    EXPECT_NE(r.err.find("in use by another process (pid"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(sweep_dir / "plan.csv"));
  }
}

TEST(Cli, RunRefusesAnIncompressibleMaterialBeforeWritingAnything) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_nu_half";
  std::filesystem::remove_all(dir);
  const auto r = run({"run", "--nu", "0.5", "--output", dir.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("nu < 0.5"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

// A designer's mesh with a defect is refused before anything is written, naming what is wrong.
TEST(Cli, ADesignersMeshWithADefectIsNamedBeforeTheRunStarts) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_user_mesh";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  auto cap = mesh::make_cap_mesh(
      {.R = 0.03, .h = 0.002, .phi = 1.396, .element_size = 0.008, .layers = 1});
  const auto case_with = [&](const std::string& msh) {
    const auto path = dir / (msh + ".toml");
    std::ofstream(path) << "[shell]\nmesh = \"" << msh << "\"\nR = \"30 mm\"\nh = \"2 mm\"\n"
                        << "[material]\nE = \"1.2 MPa\"\n[popper]\nnet_weight = \"0.48 N\"\n";
    return path.string();
  };
  const auto refused = [&](const std::string& msh, const std::string& why) {
    const auto out = dir / ("run-" + msh);
    const auto r = run({"run", case_with(msh), "--resolution", "coarse", "--output", out.string()});
    EXPECT_EQ(r.code, kExitBadInput) << msh;
    EXPECT_NE(r.err.find(why), std::string::npos) << msh << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << msh;
  };
  // Upside down (turned about the x axis): the rim below the apex.
  auto turned = cap;
  for (std::size_t a = 0; a < turned.nodes.size(); ++a) {
    turned.nodes.y[a] = -turned.nodes.y[a];
    turned.nodes.z[a] = -turned.nodes.z[a];
  }
  mesh::write_msh(turned, dir / "turned.msh");
  refused("turned.msh", "must open upward");
  // Mirrored in z: every element turned inside out.
  auto mirrored = cap;
  for (auto& z : mirrored.nodes.z) z = -z;
  mesh::write_msh(mirrored, dir / "mirrored.msh");
  refused("mirrored.msh", "element");
  // Not a mesh; a missing file.
  std::ofstream(dir / "text.msh") << "hello\n";
  refused("text.msh", "not a gmsh .msh file");
  const auto missing = run({"run", case_with("absent.msh"), "--output", (dir / "x").string()});
  EXPECT_EQ(missing.code, kExitBadInput);
  EXPECT_NE(missing.err.find("shell.mesh"), std::string::npos) << missing.err;
  // The axisymmetric model meshes its own cap.
  mesh::write_msh(cap, dir / "cap.msh");
  const auto axi = run(
      {"run", case_with("cap.msh"), "--model", "axisymmetric", "--output", (dir / "axi").string()});
  EXPECT_EQ(axi.code, kExitBadInput);
  EXPECT_NE(axi.err.find("3D shape"), std::string::npos) << axi.err;
  // `snapjump mesh` writes .msh files only.
  const auto wrong = run({"mesh", "--output", (dir / "cap.vtk").string()});
  EXPECT_EQ(wrong.code, kExitBadInput);
}

TEST(Cli, ResumeNeedsARunFolder) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_not_a_run";
  std::filesystem::create_directories(dir);
  const auto r = run({"run", "--resume", dir.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("not a snapjump run folder"), std::string::npos) << r.err;
}

TEST(Cli, ResumeTakesNoNewCase) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_not_a_run";
  std::filesystem::create_directories(dir);
  const auto r = run({"run", "--resume", dir.string(), "--R", "20mm"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("give no case file"), std::string::npos) << r.err;
}

// A finished run's folder with a stale summary: the series is a jump of the default popper, whose
// force peaks at `peak` [N].
std::filesystem::path stale_run(const std::string& name, bool finished, double peak = 2.0) {
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "case.toml") << config::to_toml(config::default_case());
  {
    std::ofstream csv(dir / "series.csv");
    csv << "t,z,r,w,e,F,contact\n";
    for (int i = 0; i <= 600; ++i) {
      const double t = 1e-4 * i;
      const double w = std::max(0.01 - 0.5 * t, 0.0);  // below 0.03 R = 0.9 mm from 18.2 ms
      double F = 0.48;
      if (t >= 0.019)
        F = std::max(0.0, peak * (1.0 - (t - 0.019) / 0.004));
      else if (t >= 0.018)
        F = 0.48 + (peak - 0.48) * (t - 0.018) / 0.001;
      const double z = t <= 0.023 ? t : 0.023 + (t - 0.023) - 4.9 * (t - 0.023) * (t - 0.023);
      csv << t << ',' << z << ',' << 0.015 << ',' << w << ',' << 0.004 << ',' << F << ','
          << (w > 0.0 ? "ring" : "disk") << '\n';
    }
  }
  nlohmann::json summary = {{"status", finished ? "completed" : "running"}, {"wall_time", 12.5}};
  if (finished) summary["measured"] = {{"outcome", "No snap"}};
  std::ofstream(dir / "summary.json") << summary.dump(2);
  return dir;
}

TEST(Cli, ReanalyzeRewritesTheSummaryOfAFinishedRun) {
  const auto dir = stale_run("snapjump_cli_reanalyze", true);
  const auto r = run({"run", "--reanalyze", dir.string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("Jump (theory: Jump)"), std::string::npos) << r.out;
  std::ifstream in(dir / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["measured"]["outcome"], "Jump");
  EXPECT_EQ(summary["comparison"]["outcome"]["simulated"], "Jump");
  EXPECT_TRUE(summary["theory"].contains("quantities"));
  EXPECT_EQ(summary["status"], "completed");  // what the run itself wrote stays
  EXPECT_DOUBLE_EQ(summary["wall_time"].get<double>(), 12.5);
}

TEST(Cli, APrefactorFarFromItsBoundsIsNamedWithItsLikelyCause) {
  // F* = 6 N against F_c = 0.32 N: alpha_F = 18.75, beyond 1.5 times the upper bound 8.04.
  const auto dir = stale_run("snapjump_cli_far_from_bounds", true, 6.0);
  const auto r = run({"run", "--reanalyze", dir.string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(
      r.out.find("  warning     alpha_F = 18.8 lies a factor 2.33 above its upper bound 8.04: "),
      std::string::npos)
      << r.out;
  std::ifstream in(dir / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  const auto& far = summary["comparison"]["alpha_F"]["far_from_bounds"];
  EXPECT_NEAR(far["factor"].get<double>(), 18.75 / 8.04, 0.01);
  EXPECT_TRUE(far["above"].get<bool>());
  EXPECT_FALSE(far["likely_cause"].get<std::string>().empty());
  ASSERT_FALSE(summary["comparison"]["warnings"].empty());
  EXPECT_NE(summary["comparison"]["warnings"][0].get<std::string>().find("alpha"),
            std::string::npos);
  // Inside the bounds (alpha_F = 6.25), no such warning.
  const auto inside = stale_run("snapjump_cli_inside_bounds", true);
  const auto ok = run({"run", "--reanalyze", inside.string()});
  EXPECT_EQ(ok.out.find("alpha_F = "), std::string::npos) << ok.out;
}

TEST(Cli, ARunThatDoesNotInvertSaysWhatToTryAndExitsThree) {
  // A shallow cap (phi = 20 deg): its branch turns it inside out without a buckling maximum.
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_cli_not_inverted";
  std::filesystem::remove_all(dir);
  const auto r = run({"run", "--phi", "20deg", "--model", "axisymmetric", "--resolution", "coarse",
                      "--output", dir.string(), "--quiet"});
  EXPECT_EQ(r.code, kExitNotPrepared) << r.out << r.err;
  for (const char* part :
       {"result      did not invert", "try         Zoelly's p_c of the case",
        "axisymmetric quasi-static branch", "--resolution default", "--model 3d"}) {
    EXPECT_NE(r.out.find(part), std::string::npos) << part << "\n" << r.out;
  }
  std::ifstream in(dir / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["status"], "did not invert");
  EXPECT_EQ(summary["hints"].size(), 4U);
}

TEST(Cli, ReanalyzeRefusesARunWithoutResults) {
  const auto dir = stale_run("snapjump_cli_reanalyze_running", false);
  const auto r = run({"run", "--reanalyze", dir.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("no results yet"), std::string::npos) << r.err;
  const auto m = run({"run", "--reanalyze", dir.string(), "--mu", "0.1"});
  EXPECT_EQ(m.code, kExitBadInput);
  EXPECT_NE(m.err.find("--reanalyze reads"), std::string::npos) << m.err;
}

TEST(Cli, PauseAtNeedsATime) {
  const auto r = run({"run", "--pause-at", "3 mm"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--pause-at"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

// Every error that bad input causes has one base, which the command line maps to status 2.
static_assert(std::is_base_of_v<InputError, config::CaseError>);
static_assert(std::is_base_of_v<InputError, units::UnitError>);
static_assert(std::is_base_of_v<InputError, measure::SeriesError>);
static_assert(std::is_base_of_v<InputError, mesh::MeshError>);
static_assert(std::is_base_of_v<InputError, sweep::SweepError>);
static_assert(std::is_base_of_v<InputError, plot::PlotInputError>);

TEST(Cli, AnInputErrorOfEachKindIsStatusTwo) {
  // A bad unit (units), a bad case key (config), a bad record (measure), a bad mesh (mesh).
  EXPECT_EQ(run({"predict", "--R", "3 N"}).code, kExitBadInput);
  EXPECT_EQ(run({"predict", "--nu", "abc"}).code, kExitBadInput);
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "snapjump_cli_kind.csv") << "t,F\n0,x\n";
  EXPECT_EQ(run({"analyze", (dir / "snapjump_cli_kind.csv").string()}).code, kExitBadInput);
  EXPECT_EQ(run({"mesh", "--h", "0 mm", "--output", (dir / "k.msh").string()}).code, kExitBadInput);
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

namespace fs = std::filesystem;

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A folder of this test process's own (another process may run the same tests at once).
fs::path own_folder(const std::string& name) {
  const auto dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A sweep run in-process starts its runs as this test program: should a folder check fail to
// stop one, its runs run no tests (instead of the whole suite, as "run ..." arguments would).
class NoTestsInChildren {
 public:
  NoTestsInChildren() {
    if (const char* f = std::getenv("GTEST_FILTER")) saved_ = f;
    ::setenv("GTEST_FILTER", "-*", 1);
  }
  ~NoTestsInChildren() {
    if (saved_.empty()) {
      ::unsetenv("GTEST_FILTER");
    } else {
      ::setenv("GTEST_FILTER", saved_.c_str(), 1);
    }
  }
  NoTestsInChildren(const NoTestsInChildren&) = delete;
  NoTestsInChildren& operator=(const NoTestsInChildren&) = delete;

 private:
  std::string saved_;
};

// A lock file of a sweep or a run that is a symbolic link is refused, never followed: the file
// it points to keeps its bytes, for a sweep as for a resumed run.
TEST(Cli, ALockFileThatIsALinkIsRefusedAndItsTargetUntouched) {
  const NoTestsInChildren guard;
  const auto base = own_folder("snapjump_cli_lock_links");
  fs::create_directories(base / "ud3");
  std::ofstream(base / "victim.txt") << "precious\n";
  fs::create_symlink("../victim.txt", base / "ud3" / "sweep.lock");
  std::ofstream(base / "s.toml") << "output = \"ud3\"\n[vary]\nfriction.mu = [0.1, 0.2]\n";
  const auto sweep = run({"sweep", (base / "s.toml").string()});
  EXPECT_EQ(sweep.code, kExitBadInput) << sweep.err;
  EXPECT_NE(sweep.err.find((base / "ud3" / "sweep.lock").string() + " is a symbolic link"),
            std::string::npos)
      << sweep.err;
  EXPECT_FALSE(fs::exists(base / "ud3" / "plan.csv"));
  EXPECT_EQ(text_of(base / "victim.txt"), "precious\n");

  const auto rl = base / "rl";
  fs::create_directories(rl);
  std::ofstream(rl / "case.toml") << config::to_toml(config::default_case());
  fs::create_symlink("../victim.txt", rl / "run.lock");
  const auto resume = run({"run", "--resume", rl.string()});
  EXPECT_EQ(resume.code, kExitBadInput) << resume.err;
  EXPECT_NE(resume.err.find((rl / "run.lock").string() + " is a symbolic link"), std::string::npos)
      << resume.err;
  EXPECT_FALSE(fs::exists(rl / "summary.json"));
  EXPECT_EQ(text_of(base / "victim.txt"), "precious\n");
  fs::remove_all(base);
}

// A file of the user's that happens to be called sweep.lock keeps its bytes: in a folder the
// sweep refuses, and when a lock takes it as it is. A lock's own file, left by a killed process,
// is taken over and says who holds it now.
TEST(Cli, ALockNeverRewritesAFileThatIsNotALocks) {
  const NoTestsInChildren guard;
  const auto base = own_folder("snapjump_cli_lock_own_file");
  fs::create_directories(base / "own");
  std::ofstream(base / "own" / "sweep.lock") << "my notes\n";
  std::ofstream(base / "own" / "data.csv") << "1,2\n";
  std::ofstream(base / "s.toml") << "output = \"own\"\n[vary]\nfriction.mu = [0.1, 0.2]\n";
  const auto r = run({"sweep", (base / "s.toml").string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("not a sweep folder"), std::string::npos) << r.err;
  EXPECT_EQ(text_of(base / "own" / "sweep.lock"), "my notes\n");
  {
    const io::FolderLock held(base / "own", "sweep.lock", "the sweep folder");
    EXPECT_EQ(text_of(base / "own" / "sweep.lock"), "my notes\n");
    EXPECT_THROW(io::FolderLock(base / "own", "sweep.lock", "the sweep folder"), io::FolderBusy);
  }
  EXPECT_EQ(text_of(base / "own" / "sweep.lock"), "my notes\n");
  // A stale lock (a process id, its process gone) is taken over.
  std::ofstream(base / "own" / "run.lock") << "999999999\n";
  const io::FolderLock stale(base / "own", "run.lock", "the run folder");
  EXPECT_EQ(text_of(base / "own" / "run.lock"), std::to_string(::getpid()) + "\n");
  fs::remove_all(base);
}

// A sweep refused for its folder ("/", "..": folders that hold other things) leaves no lock
// file there.
TEST(Cli, ASweepRefusedForItsFolderLeavesNoLockFile) {
  const NoTestsInChildren guard;
  const auto base = own_folder("snapjump_cli_lock_refused");
  fs::create_directories(base / "a" / "b");
  std::ofstream(base / "a" / "b" / "s.toml")
      << "output = \"..\"\n[vary]\nfriction.mu = [0.1, 0.2]\n";
  const auto up = run({"sweep", (base / "a" / "b" / "s.toml").string()});
  EXPECT_EQ(up.code, kExitBadInput);
  EXPECT_NE(up.err.find("not a sweep folder"), std::string::npos) << up.err;
  EXPECT_FALSE(fs::exists(base / "a" / "sweep.lock"));
  const bool had_one = fs::exists(fs::symlink_status("/sweep.lock"));
  const auto root = run({"sweep", (base / "a" / "b" / "s.toml").string(), "--output", "/"});
  EXPECT_EQ(root.code, kExitBadInput);
  EXPECT_NE(root.err.find("not a sweep folder"), std::string::npos) << root.err;
  if (!had_one) {
    EXPECT_FALSE(fs::exists(fs::symlink_status("/sweep.lock")));
  }
  fs::remove_all(base);
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

nlohmann::json summary_of(const std::filesystem::path& dir) {
  return nlohmann::json::parse(text_of(dir / "summary.json"));
}

// The coarse axisymmetric default popper, in the ring stage: ends made short for tests.
std::vector<std::string> short_run(const std::filesystem::path& dir, const std::string& end) {
  return {"run",        "--model", "axisymmetric", "--resolution", "coarse", "--quiet",
          "--end-time", end,       "--output",     dir.string()};
}

// One run straight to 60 ms, for the runs below to be compared with (made once).
const std::filesystem::path& straight_60ms() {
  static const std::filesystem::path dir = [] {
    const auto d = own_folder("snapjump_cli_end_straight");
    const auto r = run(short_run(d, "60ms"));
    EXPECT_EQ(r.code, kExitOk) << r.err;
    return d;
  }();
  return dir;
}

// A run stopped by its cap says so and gives its heights as lower bounds; a resume with a later
// cap goes on from there, and the series is the one a run straight to that cap writes.
TEST(RunEnd, ACappedRunSaysSoAndALaterCapContinuesIt) {
  const auto& straight = straight_60ms();
  const auto dir = own_folder("snapjump_cli_end_capped");
  const auto capped = run(short_run(dir, "30ms"));
  ASSERT_EQ(capped.code, kExitOk) << capped.err;
  EXPECT_NE(capped.out.find("status      capped at 0.03 s before the apex of the flight"),
            std::string::npos)
      << capped.out;
  EXPECT_NE(capped.out.find("H and H_s are lower bounds"), std::string::npos) << capped.out;
  const auto at = capped.out.find("H   jump height");
  ASSERT_NE(at, std::string::npos) << capped.out;
  const auto h_line = capped.out.substr(at, capped.out.find('\n', at) - at);
  EXPECT_NE(h_line.find(">= "), std::string::npos) << h_line;
  auto summary = summary_of(dir);
  EXPECT_EQ(summary["status"].get<std::string>().rfind("capped at 0.03 s", 0), 0U);
  EXPECT_EQ(summary["measured"]["quantities"]["H"]["lower_bound"], true);
  EXPECT_EQ(summary["measured"]["quantities"]["H_s"]["lower_bound"], true);
  EXPECT_NE(summary["measured"]["warnings"].dump().find("lower bounds"), std::string::npos);

  // Nothing to continue to without a later cap; the run stays as it was.
  const auto same = run({"run", "--resume", dir.string(), "--quiet"});
  EXPECT_EQ(same.code, kExitBadInput);
  EXPECT_NE(same.err.find("--end-time"), std::string::npos) << same.err;
  const auto earlier = run({"run", "--resume", dir.string(), "--quiet", "--end-time", "20ms"});
  EXPECT_EQ(earlier.code, kExitBadInput);
  EXPECT_NE(earlier.err.find("has reached t = 0.03"), std::string::npos) << earlier.err;
  EXPECT_EQ(summary_of(dir)["status"], summary["status"]);

  const auto later = run({"run", "--resume", dir.string(), "--quiet", "--end-time", "60ms"});
  ASSERT_EQ(later.code, kExitOk) << later.err;
  EXPECT_EQ(summary_of(dir)["status"].get<std::string>().rfind("capped at 0.06 s", 0), 0U);
  EXPECT_EQ(text_of(dir / "series.csv"), text_of(straight / "series.csv"));
  EXPECT_EQ(text_of(dir / "run.pvd"), text_of(straight / "run.pvd"));
  // The new cap is the run's own now: a later resume goes to it.
  const auto kept = config::load_case_file(dir / "case.toml");
  ASSERT_TRUE(kept.numerics.end_time.has_value());
  EXPECT_DOUBLE_EQ(*kept.numerics.end_time, 0.06);
}

// A paused run resumed keeps in its summary where its case came from, which values were the
// defaults, and the wall time of its first part (the folder's case.toml, which the resume reads,
// has every value written out and is not where the case came from).
TEST(RunEnd, AResumedRunKeepsItsCasesOriginAndItsWholeWallTime) {
  const auto dir = own_folder("snapjump_cli_resume_summary");
  auto args = short_run(dir, "30ms");
  args.insert(args.end(), {"--pause-at", "10ms"});
  const auto first = run(args);
  ASSERT_EQ(first.code, kExitOk) << first.err;
  const auto before = summary_of(dir);
  ASSERT_FALSE(before["case"]["defaults_used"].empty());
  ASSERT_TRUE(before["wall_time"].is_number());
  const auto resumed = run({"run", "--resume", dir.string(), "--quiet"});
  ASSERT_EQ(resumed.code, kExitOk) << resumed.err;
  const auto after = summary_of(dir);
  EXPECT_EQ(after["case"]["source"], before["case"]["source"]);
  EXPECT_EQ(after["case"]["defaults_used"], before["case"]["defaults_used"]);
  EXPECT_GT(after["wall_time"].get<double>(), before["wall_time"].get<double>());
  // Each part's wall time, the first as the first part's summary gave it; wall_time their sum.
  ASSERT_EQ(before["wall_time_parts"].size(), 1u);
  ASSERT_EQ(after["wall_time_parts"].size(), 2u);
  EXPECT_DOUBLE_EQ(after["wall_time_parts"][0].get<double>(), before["wall_time"].get<double>());
  EXPECT_NEAR(after["wall_time"].get<double>(),
              after["wall_time_parts"][0].get<double>() + after["wall_time_parts"][1].get<double>(),
              1e-9);
  // A third part, from a summary that a killed run left with only its wall_time so far.
  auto edited = after;
  edited.erase("wall_time_parts");
  edited["status"] = "running";
  std::ofstream(dir / "summary.json") << edited.dump(2);
  const auto again = run({"run", "--resume", dir.string(), "--end-time", "40ms", "--quiet"});
  ASSERT_EQ(again.code, kExitOk) << again.err;
  const auto third = summary_of(dir);
  ASSERT_EQ(third["wall_time_parts"].size(), 2u);
  EXPECT_DOUBLE_EQ(third["wall_time_parts"][0].get<double>(), after["wall_time"].get<double>());
  EXPECT_EQ(third["case"]["defaults_used"], before["case"]["defaults_used"]);
}

// Starts the command line `words` (the binary first) in a child process with SIGINT at its
// default, its output into `log`; -1 when fork fails.
pid_t spawn(std::vector<std::string> words, const std::filesystem::path& log) {
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {  // only async-signal-safe calls up to the exec
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::signal(SIGINT, SIG_DFL);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

// Ctrl-C while the axisymmetric preparation follows its pressure-volume branch (a minute and
// more at the fine preset) stops the run at the branch's next point, not at the branch's end.
TEST(RunEnd, SigintStopsTheBranchAtItsNextPoint) {
  const auto exe = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "snapjump";
  ASSERT_TRUE(std::filesystem::exists(exe)) << exe << ": build the snapjump target";
  const auto base = own_folder("snapjump_cli_branch_sigint");
  const auto dir = base / "run", log = base / "log.txt";
  const pid_t pid = spawn({exe.string(), "run", "--model", "axisymmetric", "--resolution", "fine",
                           "--quiet", "--output", dir.string()},
                          log);
  ASSERT_GE(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, SIGINT);
  const auto sent = std::chrono::steady_clock::now();
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  ASSERT_TRUE(WIFEXITED(status)) << text_of(log);
  EXPECT_EQ(WEXITSTATUS(status), kExitInterrupted) << text_of(log);
  EXPECT_NE(text_of(log).find("in the preparation (buckle (branch)"), std::string::npos)
      << text_of(log);
  EXPECT_LT(waited, 20.0);  // the fine branch alone takes 40-70 s on two cores here
}

// Ctrl-C: SIGINT to a `snapjump run` past its release leaves a checkpoint and the status
// "interrupted" with the command that resumes it, and the process ends with 130. The run, given
// no end time, states the cap it has from the case; resumed with a cap of its own, its series is
// the one a run straight to that cap writes.
TEST(RunEnd, SigintLeavesAnInterruptedRunThatResumes) {
  const auto& straight = straight_60ms();
  // The command line's binary, built beside this one.
  const auto exe = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "snapjump";
  ASSERT_TRUE(std::filesystem::exists(exe)) << exe << ": build the snapjump target";
  const auto base = own_folder("snapjump_cli_end_sigint");
  const auto dir = base / "run", log = base / "log.txt";
  std::vector<std::string> words = {exe.string(),   "run",          "--model",
                                    "axisymmetric", "--resolution", "coarse",
                                    "--quiet",      "--output",     dir.string()};
  const pid_t pid = spawn(words, log);
  ASSERT_GE(pid, 0);
  // The release has come when the series exists.
  const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!std::filesystem::exists(dir / "series.csv") && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << text_of(log);
  EXPECT_EQ(WEXITSTATUS(status), kExitInterrupted) << text_of(log);
  const auto summary = summary_of(dir);
  const auto said = summary["status"].get<std::string>();
  EXPECT_EQ(said.rfind("interrupted at t = ", 0), 0U) << said;
  EXPECT_NE(said.find("continue with snapjump run --resume " + dir.string()), std::string::npos)
      << said;
  EXPECT_NE(text_of(log).find("resume      snapjump run --resume " + dir.string()),
            std::string::npos)
      << text_of(log);
  EXPECT_TRUE(std::filesystem::exists(dir / "checkpoint.bin"));
  EXPECT_NE(text_of(log).find("end         the apex of the flight, at most"), std::string::npos)
      << text_of(log);
  // The default popper's apex comes 0.69 s after the release (docs/popper.md).
  EXPECT_GT(summary["numerics"]["end_time"].get<double>(), 2.0 * 0.69) << summary.dump(2);
  EXPECT_EQ(summary["end"]["cap_from"], "default");

  const auto resumed = run({"run", "--resume", dir.string(), "--quiet", "--end-time", "60ms"});
  ASSERT_EQ(resumed.code, kExitOk) << resumed.err;
  EXPECT_EQ(text_of(dir / "series.csv"), text_of(straight / "series.csv"));
}

// A full disk, made without privileges: the command line `words` runs in a child process whose
// files may not grow beyond `bytes` (RLIMIT_FSIZE) with SIGXFSZ ignored, so that a write past
// the limit fails with EFBIG as one on a full disk fails with ENOSPC. Its output goes to `log`
// (held to the same limit); returns its exit status, or -1 when it did not exit.
int run_with_file_limit(std::vector<std::string> words, const fs::path& log, rlim_t bytes) {
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {  // only async-signal-safe calls up to the exec
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::signal(SIGXFSZ, SIG_IGN);  // kept ignored across the exec
    const rlimit r{bytes, bytes};
    if (::setrlimit(RLIMIT_FSIZE, &r) != 0) ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

// The files under dir whose names end in ".tmp".
std::vector<std::string> temporaries_under(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().extension() == ".tmp") out.push_back(e.path().string());
  }
  return out;
}

// Every snapshot a run left is whole: no empty or cut .vtu file.
void expect_whole_snapshots(const fs::path& dir) {
  if (!fs::exists(dir / "snapshots")) return;
  for (const auto& e : fs::directory_iterator(dir / "snapshots")) {
    const auto text = text_of(e.path());
    EXPECT_TRUE(text.ends_with("</VTKFile>\n")) << e.path() << " holds " << text.size() << " bytes";
  }
}

// A disk that fills during a run: every write that would grow a file past 16 KB fails (the
// first snapshot of the release is larger). The run ends with status 4 naming the file, leaves
// no temporary file and no cut snapshot, and its summary says it failed and why.
TEST(RunEnd, AFullDiskEndsTheRunAsAWriteFailure) {
  const auto exe = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "snapjump";
  ASSERT_TRUE(std::filesystem::exists(exe)) << exe << ": build the snapjump target";
  const auto base = own_folder("snapjump_cli_disk_full_run");
  const auto dir = base / "run", log = base / "log.txt";
  const int code =
      run_with_file_limit({exe.string(), "run", "--model", "axisymmetric", "--resolution", "coarse",
                           "--end-time", "20ms", "--quiet", "--output", dir.string()},
                          log, 16 << 10);
  EXPECT_EQ(code, kExitWriteFailed) << text_of(log);
  EXPECT_NE(text_of(log).find("error: could not write " + dir.string() + "/"), std::string::npos)
      << text_of(log);
  EXPECT_NE(text_of(log).find(std::strerror(EFBIG)), std::string::npos) << text_of(log);
  EXPECT_EQ(temporaries_under(dir), std::vector<std::string>{});
  expect_whole_snapshots(dir);
  const auto status = summary_of(dir)["status"].get<std::string>();
  EXPECT_EQ(status.rfind("failed: could not write " + dir.string() + "/", 0), 0u) << status;
}

// A resume whose writes fail (here its rewrite of the series, past 4 KB) ends with status 4, not
// as bad input: series.csv and summary.json stay as they were, no series.csv.tmp is left, and the
// run resumes once the disk has room.
TEST(RunEnd, AResumeOnAFullDiskEndsAsAWriteFailureAndResumesLater) {
  const auto exe = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "snapjump";
  ASSERT_TRUE(std::filesystem::exists(exe)) << exe << ": build the snapjump target";
  const auto base = own_folder("snapjump_cli_disk_full_resume");
  const auto dir = base / "run", log = base / "log.txt";
  const auto first = run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--end-time",
                          "5ms", "--quiet", "--output", dir.string()});
  ASSERT_EQ(first.code, kExitOk) << first.err;
  const auto series = text_of(dir / "series.csv"), summary = text_of(dir / "summary.json");
  ASSERT_GT(series.size(), 4u << 10);
  ASSERT_GT(summary.size(), 4u << 10);
  const int code = run_with_file_limit(
      {exe.string(), "run", "--resume", dir.string(), "--end-time", "15ms", "--quiet"}, log,
      4 << 10);
  EXPECT_EQ(code, kExitWriteFailed) << text_of(log);
  EXPECT_NE(text_of(log).find("error: could not write " + (dir / "series.csv.tmp").string()),
            std::string::npos)
      << text_of(log);
  EXPECT_EQ(temporaries_under(dir), std::vector<std::string>{});
  EXPECT_EQ(text_of(dir / "series.csv"), series);
  // The summary, larger than the disk's room, says what it said (capped, to be continued).
  EXPECT_EQ(text_of(dir / "summary.json"), summary);
  const auto later = run({"run", "--resume", dir.string(), "--end-time", "15ms", "--quiet"});
  EXPECT_EQ(later.code, kExitOk) << later.err;
}

// A lock file that is a link is named with where it points, an excerpt of the link's text.
TEST(Cli, ALockFileLinkIsNamedWithAShortEscapedExcerptOfItsTarget) {
  const auto base = own_folder("snapjump_cli_lock_link_text");
  fs::create_symlink(test_support::hostile_text(), base / "run.lock");
  try {
    const io::FolderLock lock(base, "run.lock", "the run folder");
    ADD_FAILURE() << "a lock through a link was taken";
  } catch (const io::LockFileRefused& e) {
    EXPECT_TRUE(test_support::quotes_only_an_excerpt(e.what()));
  }
}

}  // namespace
}  // namespace snapjump::app
