// Every case in examples/ (the paper's five fabricated shells and its Fig. 2(a) popper) through
// `snapjump run` to the apex of the flight, at the coarse and default presets of both models: 24
// runs, hours on two cores (label `long`). A run passes when it ends with an outcome (Jump, Snap,
// No snap, Thrown) or an undetermined one with its reason.
// Each run prints a line for docs/validation.md's table: outcome, r*, F*, H, the prefactors and
// the wall time.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_runner.hpp"

namespace snapjump {
namespace {

namespace fs = std::filesystem;

struct Case {
  const char* file;
  const char* model;   // "3d" | "axisymmetric"
  const char* preset;  // "coarse" | "default"
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.file << ", " << c.model << ", " << c.preset;
}

double quantity(const nlohmann::json& q, const char* key, double scale) {
  if (!q.contains(key) || q[key]["value"].is_null()) return std::nan("");
  return q[key]["value"].get<double>() * scale;
}

class AllCases : public ::testing::TestWithParam<Case> {};

TEST_P(AllCases, RunToTheApexWithAnOutcome) {
  const auto& c = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("snapjump_all_cases_" + std::string(c.model) +
                                                    "_" + c.preset + "_" + c.file);
  fs::remove_all(dir);
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = test_support::run_cli(
      {"run", (fs::path(SNAPJUMP_SOURCE_DIR) / "examples" / c.file).string(), "--model", c.model,
       "--resolution", c.preset, "--output", dir.string(), "--quiet"});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ifstream in(dir / "summary.json");
  ASSERT_TRUE(in) << r.err;
  const auto s = nlohmann::json::parse(in);
  const std::string status = s["status"].get<std::string>();
  const auto& m = s.contains("measured") ? s["measured"] : nlohmann::json::object();
  const std::string outcome = m.contains("outcome") && m["outcome"].is_string()
                                  ? m["outcome"].get<std::string>()
                                  : std::string("-");
  const auto q = m.contains("quantities") && m["quantities"].is_object() ? m["quantities"]
                                                                         : nlohmann::json::object();
  std::printf(
      "| %s | %s | %s | %s | %s | r* %.3g mm | F* %.3g N | H %.3g mm | alpha_r %.3g alpha_e %.3g "
      "alpha_F %.3g alpha_t %.3g | %.0f s |\n",
      c.file, c.model, c.preset, status.substr(0, 60).c_str(), outcome.c_str(),
      quantity(q, "r_star", 1e3), quantity(q, "F_star", 1.0), quantity(q, "H", 1e3),
      quantity(q, "alpha_r", 1.0), quantity(q, "alpha_e", 1.0), quantity(q, "alpha_F", 1.0),
      quantity(q, "alpha_t", 1.0), wall);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(status, "completed (apex of the flight)") << r.err;
  if (outcome == "-") {
    EXPECT_TRUE(m.contains("undetermined") && m["undetermined"].is_string()) << status;
  } else {
    EXPECT_TRUE(outcome == "Jump" || outcome == "Snap" || outcome == "No snap" ||
                outcome == "Thrown")
        << outcome;
  }
}

constexpr const char* kFiles[] = {"default.toml",  "R25_h2.0.toml", "R25_h2.5.toml",
                                  "R30_h1.0.toml", "R30_h1.5.toml", "R30_h2.0.toml"};

std::vector<Case> all_cases() {
  std::vector<Case> v;
  for (const char* model : {"axisymmetric", "3d"}) {
    for (const char* preset : {"coarse", "default"}) {
      for (const char* file : kFiles) v.push_back({file, model, preset});
    }
  }
  return v;
}

INSTANTIATE_TEST_SUITE_P(Examples, AllCases, ::testing::ValuesIn(all_cases()),
                         [](const auto& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.size() - 5);
                           for (auto& ch : name) {
                             if (ch == '.') ch = '_';
                           }
                           return name + "_" + info.param.model + "_" + info.param.preset;
                         });

}  // namespace
}  // namespace snapjump
