// A run paused half-way and resumed from its checkpoint ends with the same time series as the
// run that went straight through. About two minutes on two cores (two preparations).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "app/checkpoint.hpp"
#include "app/cli.hpp"
#include "app/run.hpp"

namespace snapjump::app {
namespace {

int run(std::vector<std::string> args) {
  args.insert(args.begin(), "snapjump");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int code = run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
  if (code != 0) ADD_FAILURE() << err.str();
  return code;
}

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// --resume of the run in dir, which must fail: its messages.
std::string refused_resume(const std::filesystem::path& dir) {
  std::vector<std::string> args = {"snapjump", "run", "--resume", dir.string(), "--quiet"};
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  EXPECT_NE(run_cli(static_cast<int>(argv.size()), argv.data(), out, err), 0);
  return err.str();
}

TEST(RunResume, PausedAndResumedRunMatchesAStraightOne) {
  const auto base = std::filesystem::temp_directory_path() / "snapjump_resume_test";
  std::filesystem::remove_all(base);
  const auto straight = base / "straight", paused = base / "paused";
  ASSERT_EQ(run({"run", "--resolution", "coarse", "--end-time", "4ms", "--quiet", "--output",
                 straight.string()}),
            0);
  ASSERT_EQ(run({"run", "--resolution", "coarse", "--end-time", "4ms", "--pause-at", "2ms",
                 "--quiet", "--output", paused.string()}),
            0);
  EXPECT_TRUE(std::filesystem::exists(paused / "checkpoint.bin"));
  EXPECT_NE(read(paused / "series.csv"), read(straight / "series.csv"));  // really stopped early
  {
    // A checkpoint whose particles follow another numbering of the mesh's nodes (a build before
    // the curve order, say) is refused, even with a valid checksum.
    const auto other = base / "other";
    std::filesystem::copy(paused, other, std::filesystem::copy_options::recursive);
    std::string bytes = read(paused / "checkpoint.bin");
    constexpr std::size_t kFingerprint = sizeof("snapjump-popper-state-3");
    constexpr std::size_t kTrailer = sizeof("snapjump-checksum-1") + sizeof(std::uint64_t);
    ASSERT_GT(bytes.size(), kFingerprint + kTrailer);
    bytes[kFingerprint] = static_cast<char>(bytes[kFingerprint] ^ 1);
    const std::uint64_t sum = fnv1a64(std::string_view(bytes).substr(0, bytes.size() - kTrailer));
    std::memcpy(bytes.data() + bytes.size() - sizeof sum, &sum, sizeof sum);
    std::ofstream(other / "checkpoint.bin", std::ios::binary) << bytes;
    const auto err = refused_resume(other);
    EXPECT_NE(err.find("another numbering of its nodes"), std::string::npos) << err;
  }
  ASSERT_EQ(run({"run", "--resume", paused.string(), "--quiet"}), 0);
  EXPECT_EQ(read(paused / "series.csv"), read(straight / "series.csv"));
  EXPECT_EQ(read(paused / "run.pvd"), read(straight / "run.pvd"));
}

// An axisymmetric coarse run of the default popper to 60 ms, straight and paused at pause_at,
// in base/straight and base/paused.
struct PausedAndStraight {
  std::filesystem::path straight, paused;
};
PausedAndStraight axisymmetric_runs(const std::string& name, const std::string& pause_at) {
  const auto base = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(base);
  const PausedAndStraight r{base / "straight", base / "paused"};
  const std::vector<std::string> common = {"run",    "--model", "axisymmetric", "--resolution",
                                           "coarse", "--quiet", "--end-time",   "60ms"};
  auto a = common, b = common;
  a.insert(a.end(), {"--output", r.straight.string()});
  b.insert(b.end(), {"--pause-at", pause_at, "--output", r.paused.string()});
  EXPECT_EQ(run(a), 0);
  EXPECT_EQ(run(b), 0);
  return r;
}

TEST(RunResume, AxisymmetricRunResumesExactly) {
  // The same through the axisymmetric model, paused in the ring stage.
  const auto [straight, paused] = axisymmetric_runs("snapjump_resume_axi_test", "25ms");
  EXPECT_NE(read(paused / "series.csv"), read(straight / "series.csv"));
  ASSERT_EQ(run({"run", "--resume", paused.string(), "--quiet"}), 0);
  EXPECT_EQ(read(paused / "series.csv"), read(straight / "series.csv"));
  EXPECT_EQ(read(paused / "run.pvd"), read(straight / "run.pvd"));
  EXPECT_EQ(read(paused / "snapshots" / "frame_00010.vtu"),
            read(straight / "snapshots" / "frame_00010.vtu"));
}

TEST(RunResume, AResumeKilledWhileRewritingTheSeriesCanBeResumedAgain) {
  // The resume rewrites series.csv up to its checkpoint; a run stopped in the middle of that
  // rewrite (here by an injected fault) must leave a folder that resumes. It did not when the
  // series was truncated in place.
  const auto [straight, paused] = axisymmetric_runs("snapjump_resume_fault_test", "45ms");
  RunOptions faulty;
  faulty.resume = paused.string();
  faulty.quiet = true;
  faulty.fault_after_rewritten_rows = 100;
  std::ostringstream out, err;
  EXPECT_THROW((void)run_simulation(config::Case{}, faulty, out, err), std::runtime_error);
  ASSERT_EQ(run({"run", "--resume", paused.string(), "--quiet"}), 0);
  EXPECT_EQ(read(paused / "series.csv"), read(straight / "series.csv"));
}

// An axisymmetric coarse run paused at 2 ms, in the fresh folder dir.
void pause_a_run(const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  ASSERT_EQ(run({"run", "--model", "axisymmetric", "--resolution", "coarse", "--quiet",
                 "--end-time", "10ms", "--pause-at", "2ms", "--output", dir.string()}),
            0);
}

// Adds a line under [numerics] of the run's case.toml.
void add_to_numerics(const std::filesystem::path& dir, const std::string& line) {
  auto text = read(dir / "case.toml");
  const auto at = text.find("[numerics]\n");
  ASSERT_NE(at, std::string::npos) << text;
  text.insert(at + 11, line + "\n");
  std::ofstream(dir / "case.toml") << text;
}

TEST(RunResume, ARunIsNotContinuedWithOtherNumerics) {
  // A run paused, then its case changed so that the discretisation differs (as a snapjump with
  // new defaults would see it): the resume names what differs and refuses.
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_resume_numerics_test";
  ASSERT_NO_FATAL_FAILURE(pause_a_run(dir));
  const auto summary = read(dir / "summary.json");
  ASSERT_NO_FATAL_FAILURE(add_to_numerics(dir, "elements_through_thickness = 3"));
  const auto err = refused_resume(dir);
  EXPECT_NE(err.find("other numerics than it started with"), std::string::npos) << err;
  EXPECT_NE(err.find("when it started"), std::string::npos) << err;
  EXPECT_EQ(read(dir / "summary.json"), summary);  // still paused, not failed
}

TEST(RunResume, ARunMadeBeforeTheBulkKeyIsNotContinuedWithAnotherRule) {
  // Summaries written before the bulk_integration key existed have none; such a run used its
  // model's rule then (axisymmetric: reduced). Given "full" in its case.toml, the resume refuses
  // and names it.
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_resume_bulk_test";
  ASSERT_NO_FATAL_FAILURE(pause_a_run(dir));
  auto summary = nlohmann::json::parse(read(dir / "summary.json"));
  ASSERT_EQ(summary["numerics"]["bulk_integration"], "reduced");
  summary["numerics"].erase("bulk_integration");
  std::ofstream(dir / "summary.json") << summary.dump(2);
  ASSERT_NO_FATAL_FAILURE(add_to_numerics(dir, "bulk_integration = \"full\""));
  const auto err = refused_resume(dir);
  EXPECT_NE(err.find("bulk_integration: \"reduced\" when it started, \"full\" now"),
            std::string::npos)
      << err;
}

}  // namespace
}  // namespace snapjump::app

namespace snapjump::app {
namespace {

// The numbers of a series.csv, row by row (comment lines and the contact column left out).
std::vector<std::vector<double>> numbers(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::vector<std::vector<double>> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) {
      try {
        row.push_back(std::stod(cell));
      } catch (const std::exception&) {  // the contact state
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

// The cap that `snapjump mesh` writes, named in a case as [shell] mesh, runs as the cap the
// simulator generates itself (the .msh text rounds the coordinates: equal to 1e-9). The run
// folder keeps its own copy of the mesh, which case.toml names.
TEST(UserMesh, TheWrittenCapReadBackRunsAsTheGeneratedOne) {
  const auto base = std::filesystem::temp_directory_path() / "snapjump_user_mesh_test";
  std::filesystem::remove_all(base);
  std::filesystem::create_directories(base);
  ASSERT_EQ(run({"mesh", "--resolution", "coarse", "--output", (base / "cap.msh").string()}), 0);
  {
    std::ifstream in(std::filesystem::path(SNAPJUMP_SOURCE_DIR) / "examples" / "default.toml");
    std::ofstream out(base / "case.toml");
    for (std::string line; std::getline(in, line);) {
      out << line << '\n';
      if (line == "[shell]") out << "mesh = \"cap.msh\"\n";
    }
  }
  const auto mine = base / "mine", generated = base / "generated";
  ASSERT_EQ(run({"run", (base / "case.toml").string(), "--resolution", "coarse", "--end-time",
                 "1ms", "--quiet", "--output", mine.string()}),
            0);
  ASSERT_EQ(run({"run", "--resolution", "coarse", "--end-time", "1ms", "--quiet", "--output",
                 generated.string()}),
            0);
  const auto a = numbers(mine / "series.csv"), b = numbers(generated / "series.csv");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 5U);
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].size(), b[i].size());
    for (std::size_t k = 0; k < a[i].size(); ++k) {
      EXPECT_NEAR(a[i][k], b[i][k], 1e-9 * (1.0 + std::abs(b[i][k])))
          << "row " << i << " col " << k;
    }
  }
  EXPECT_TRUE(std::filesystem::exists(mine / "shell.msh"));
  EXPECT_NE(read(mine / "case.toml").find("mesh = \"shell.msh\""), std::string::npos);
}

}  // namespace
}  // namespace snapjump::app
