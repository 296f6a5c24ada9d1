#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "config/case.hpp"
#include "support/hostile_text.hpp"
#include "sweep/executor.hpp"
#include "sweep/sweep.hpp"

namespace snapjump::sweep {
namespace {

namespace fs = std::filesystem;

// A fresh folder under the system's temporary folder.
fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("snapjump-sweep-test-" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// A table's header and its first three rows (empty where the file has fewer).
struct TableStart {
  std::string header, r0, r1, r2;
};
TableStart table_start(const fs::path& csv) {
  std::istringstream rows(read(csv));
  TableStart t;
  for (auto* line : {&t.header, &t.r0, &t.r1, &t.r2}) std::getline(rows, *line);
  return t;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream f(p);
  f << text;
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const SweepError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SweepSpec, CartesianProductHasTheLastKeyFastestAndZipOutermost) {
  const auto spec = parse_spec(R"(
title = "t"
[zip]
shell.R = ["25 mm", "30 mm"]
shell.h = ["2.5 mm", "2 mm"]
[vary]
popper.net_weight = ["0.48 N", "1 N", "3 N"]
friction.mu = [0.1, 0.5]
)",
                               "/tmp/s.toml");
  ASSERT_EQ(spec.runs.size(), 2u * 3u * 2u);
  ASSERT_EQ(spec.varied_keys,
            (std::vector<std::string>{"shell.R", "shell.h", "popper.net_weight", "friction.mu"}));
  EXPECT_EQ(spec.runs[0].name, "run-0000");
  EXPECT_EQ(spec.runs[11].name, "run-0011");
  // run 1: first zip position, first weight, second mu
  EXPECT_EQ(spec.runs[1].settings[0].text, "25 mm");
  EXPECT_EQ(spec.runs[1].settings[2].text, "0.48 N");
  EXPECT_EQ(spec.runs[1].settings[3].text, "0.5");
  // run 6: second zip position (R and h together), first weight, first mu
  EXPECT_EQ(spec.runs[6].settings[0].text, "30 mm");
  EXPECT_EQ(spec.runs[6].settings[1].text, "2 mm");
  EXPECT_EQ(spec.runs[6].settings[2].text, "0.48 N");
  EXPECT_EQ(spec.runs[6].settings[3].text, "0.1");
  EXPECT_EQ(spec.output, fs::path("runs/sweep-s"));  // like snapjump run: under runs/

  const auto c = make_case(spec, spec.runs[6]);
  EXPECT_DOUBLE_EQ(c.shell.R, 0.030);
  EXPECT_DOUBLE_EQ(c.shell.h, 0.002);
  EXPECT_DOUBLE_EQ(c.popper.net_weight, 0.48);
  EXPECT_DOUBLE_EQ(c.friction.mu, 0.1);
}

TEST(SweepSpec, RangesTakeUnitsAndLogScale) {
  const auto spec = parse_spec(R"(
output = "here"
[set]
numerics.resolution = "coarse"
numerics.end_time = "20 ms"
[vary]
shell.h = { from = "1.5 mm", to = "2.5 mm", count = 3 }
popper.net_weight = { from = "0.1 N", to = "10 N", count = 3, scale = "log" }
)",
                               "/data/s.toml");
  ASSERT_EQ(spec.runs.size(), 9u);
  EXPECT_EQ(spec.output, fs::path("/data/here"));
  const auto c0 = make_case(spec, spec.runs[0]);
  const auto c4 = make_case(spec, spec.runs[4]);  // middle of both ranges
  const auto c8 = make_case(spec, spec.runs[8]);
  EXPECT_NEAR(c0.shell.h, 1.5e-3, 1e-15);
  EXPECT_NEAR(c4.shell.h, 2.0e-3, 1e-15);
  EXPECT_NEAR(c8.shell.h, 2.5e-3, 1e-15);
  EXPECT_NEAR(c0.popper.net_weight, 0.1, 1e-12);
  EXPECT_NEAR(c4.popper.net_weight, 1.0, 1e-12);  // geometric mean of 0.1 and 10
  EXPECT_NEAR(c8.popper.net_weight, 10.0, 1e-12);
  EXPECT_EQ(c4.numerics.resolution, config::Resolution::Coarse);
  ASSERT_TRUE(c4.numerics.end_time.has_value());
  EXPECT_DOUBLE_EQ(*c4.numerics.end_time, 0.020);
}

TEST(SweepSpec, EitherModelCanBeSetOrVaried) {
  const auto spec = parse_spec(R"(
[vary]
numerics.model = ["3d", "axisymmetric"]
)",
                               "/data/s.toml");
  ASSERT_EQ(spec.runs.size(), 2u);
  EXPECT_EQ(make_case(spec, spec.runs[0]).numerics.model, config::Model::ThreeD);
  EXPECT_EQ(make_case(spec, spec.runs[1]).numerics.model, config::Model::Axisymmetric);
  // The case file a run is repeated from carries the model.
  const auto again = config::parse_case(config::to_toml(make_case(spec, spec.runs[1])), "again");
  EXPECT_EQ(again.numerics.model, config::Model::Axisymmetric);
}

TEST(SweepSpec, TheBulkIntegrationCanBeSetOrVaried) {
  const auto spec = parse_spec(R"(
[set]
numerics.model = "axisymmetric"
[vary]
numerics.bulk_integration = ["full", "reduced"]
)",
                               "/data/s.toml");
  ASSERT_EQ(spec.runs.size(), 2u);
  EXPECT_EQ(make_case(spec, spec.runs[0]).numerics.bulk_integration, config::BulkIntegration::Full);
  EXPECT_EQ(make_case(spec, spec.runs[1]).numerics.bulk_integration,
            config::BulkIntegration::Reduced);
  const auto again = config::parse_case(config::to_toml(make_case(spec, spec.runs[0])), "again");
  EXPECT_EQ(again.numerics.bulk_integration, config::BulkIntegration::Full);
}

TEST(SweepFolder, ARunKilledFromOutsideResumesFromItsCheckpoint) {
  const auto dir = fs::temp_directory_path() / "snapjump_sweep_killed_run";
  fs::remove_all(dir);
  const RunPaths p{dir / "cases" / "run-0000.toml", dir / "runs" / "run-0000",
                   dir / "logs" / "run-0000.log", dir / "logs" / "run-0000.failed"};
  fs::create_directories(p.dir);
  fs::create_directories(dir / "logs");
  std::ofstream(p.failed) << "killed by signal 9 (Killed)\n";
  std::ofstream(p.dir / "summary.json") << R"({"status": "running"})";
  EXPECT_FALSE(resumes_after_kill(p));  // no checkpoint yet: starts again
  std::ofstream(p.dir / "checkpoint.bin") << "x";
  EXPECT_EQ(state_of(p), RunState::Failed);
  EXPECT_TRUE(resumes_after_kill(p));
  // A run that recorded its own failure is not resumed: it would fail again.
  std::ofstream(p.dir / "summary.json") << R"({"status": "failed: element 3 is inverted"})";
  EXPECT_FALSE(resumes_after_kill(p));
}

TEST(SweepSpec, ABaseCaseFileIsReadRelativeToTheSweepFile) {
  const auto dir = scratch("base");
  write(dir / "cases" / "thick.toml", R"(
[shell]
R = "25 mm"
h = "2.5 mm"
[material]
E = "1.2 MPa"
[popper]
net_weight = "0.48 N"
)");
  write(dir / "s.toml", "base = \"cases/thick.toml\"\n[vary]\nfriction.mu = [0, 0.2]\n");
  const auto spec = load_spec(dir / "s.toml");
  const auto c = make_case(spec, spec.runs[1]);
  EXPECT_DOUBLE_EQ(c.shell.R, 0.025);
  EXPECT_DOUBLE_EQ(c.friction.mu, 0.2);
}

TEST(SweepSpec, MistakesNameTheKeyAndTheLine) {
  EXPECT_NE(error_of([] {
              (void)parse_spec("[vary]\nshell.thickness = [1]\n", "s.toml");
            }).find("s.toml:2: unknown case key 'shell.thickness'"),
            std::string::npos);
  EXPECT_NE(error_of([] { (void)parse_spec("title = \"x\"\n", "s.toml"); }).find("nothing to vary"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)parse_spec("[zip]\nshell.R = [\"25 mm\"]\nshell.h = [\"2 mm\", \"3 mm\"]\n",
                               "s.toml");
            }).find("differ in length"),
            std::string::npos);
  // A value in the wrong unit is found before anything runs, with the run and the key.
  const auto unit = error_of(
      [] { (void)parse_spec("[vary]\npopper.net_weight = [\"1 N\", \"2 mm\"]\n", "s.toml"); });
  EXPECT_NE(unit.find("run-0001"), std::string::npos) << unit;
  EXPECT_NE(unit.find("net_weight"), std::string::npos) << unit;
  EXPECT_NE(error_of([] {
              (void)parse_spec("[set]\nfriction.mu = 0.1\n[vary]\nfriction.mu = [0.2]\n", "s.toml");
            }).find("friction.mu"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)parse_spec("[vary]\nshell.h = { from = \"1 mm\", to = \"2 mm\" }\n", "s.toml");
            }).find("count >= 2"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)parse_spec(
                  "[set]\nnumerics.resolution = \"medium\"\n[vary]\nfriction.mu = [0]\n", "s.toml");
            }).find("numerics.resolution"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)parse_spec("[set]\nnumerics.model = \"2d\"\n[vary]\nfriction.mu = [0]\n",
                               "s.toml");
            }).find("numerics.model must be"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)parse_spec(
                  "[set]\nnumerics.bulk_integration = \"half\"\n[vary]\nfriction.mu = [0]\n",
                  "s.toml");
            }).find("numerics.bulk_integration must be \"full\" or \"reduced\""),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)parse_spec("base = \"nowhere.toml\"\n", "/tmp/s.toml");
            }).find("does not exist"),
            std::string::npos);
  EXPECT_NE(error_of([] { (void)parse_spec("[vary\n", "s.toml"); }).find("s.toml:1"),
            std::string::npos);
  // A key in [vary] and in [zip] is refused where it comes the second time.
  EXPECT_NE(error_of([] {
              (void)parse_spec("[vary]\nfriction.mu = [0.1]\n[zip]\nfriction.mu = [0.2, 0.3]\n",
                               "s.toml");
            }).find("s.toml:4: friction.mu is varied twice"),
            std::string::npos);
}

TEST(SweepSpec, AnErrorQuotesAShortEscapedExcerptOfTheFile) {
  using test_support::quotes_only_an_excerpt;
  const auto quoted = test_support::hostile_toml_quoted();
  const auto hostile = test_support::hostile_text();
  const auto error = [](const std::string& text) {
    return error_of([&] { (void)parse_spec(text, "s.toml"); });
  };
  const std::string vary = "[vary]\nfriction.mu = [0]\n";
  EXPECT_TRUE(quotes_only_an_excerpt(error(quoted + " = 1\n" + vary)));          // an unknown key
  EXPECT_TRUE(quotes_only_an_excerpt(error("[vary]\n" + quoted + " = [1]\n")));  // a case key
  EXPECT_TRUE(quotes_only_an_excerpt(error("[vary]\nshell.h = [" + quoted + "]\n")));  // a value
  EXPECT_TRUE(quotes_only_an_excerpt(
      error("[vary]\nshell.h = { from = \"1 mm\", to = \"2 mm\", count = 2, " + quoted +
            " = 1 }\n")));                                                       // a range's key
  EXPECT_TRUE(quotes_only_an_excerpt(error("base = " + quoted + "\n" + vary)));  // a path
  EXPECT_TRUE(quotes_only_an_excerpt(error("output = " + quoted + "\n" + vary)));
  const auto raw = error("title = " + hostile + "\n" + vary);  // not TOML
  EXPECT_TRUE(quotes_only_an_excerpt(raw, false)) << raw;
}

Spec small_spec(const fs::path& dir) {
  write(dir / "s.toml", "output = \"out\"\n[vary]\nfriction.mu = [0, 0.1, 0.2]\n");
  return load_spec(dir / "s.toml");
}

TEST(SweepFolder, CaseFilesRepeatTheRunsAndADifferentSweepIsRefused) {
  const auto dir = scratch("folder");
  const auto spec = small_spec(dir);
  prepare_folder(spec);
  prepare_folder(spec);  // again: the same sweep is fine
  const auto p = paths_of(spec, spec.runs[2]);
  ASSERT_TRUE(fs::exists(p.case_file));
  EXPECT_DOUBLE_EQ(config::load_case_file(p.case_file).friction.mu, 0.2);
  EXPECT_EQ(state_of(p), RunState::New);

  write(dir / "t.toml", "output = \"out\"\n[vary]\nfriction.mu = [0, 0.5]\n");
  const auto other = load_spec(dir / "t.toml");
  EXPECT_NE(error_of([&] { prepare_folder(other); }).find("holds a different sweep"),
            std::string::npos);
}

TEST(SweepFolder, StatesFollowTheRunsFiles) {
  const auto dir = scratch("states");
  const auto spec = small_spec(dir);
  prepare_folder(spec);
  const auto p0 = paths_of(spec, spec.runs[0]);
  const auto p1 = paths_of(spec, spec.runs[1]);
  const auto p2 = paths_of(spec, spec.runs[2]);
  write(p0.dir / "summary.json", R"j({"status": "completed (apex of the flight)"})j");
  write(p1.dir / "summary.json", R"({"status": "running"})");
  write(p1.dir / "checkpoint.bin", "x");
  write(p2.dir / "summary.json", R"({"status": "running"})");
  EXPECT_EQ(state_of(p0), RunState::Done);
  EXPECT_EQ(state_of(p1), RunState::Resumable);
  EXPECT_EQ(state_of(p2), RunState::Interrupted);
  write(p2.failed, "exit status 1");
  EXPECT_EQ(state_of(p2), RunState::Failed);
  EXPECT_EQ(runs_to_do(spec, false), (std::vector<std::size_t>{1}));
  EXPECT_EQ(runs_to_do(spec, true), (std::vector<std::size_t>{1, 2}));
}

// A stand-in for `snapjump run`: records its arguments, and finishes the run unless the case
// says mu = 0.1 (then it fails with exit status 3, as a crashing run would).
fs::path fake_program(const fs::path& dir) {
  const fs::path exe = dir / "fake-snapjump";
  write(exe, R"(#!/bin/sh
echo "$@" >> ")" +
                 (dir / "calls.txt").string() + R"("
if [ "$2" = "--resume" ]; then out="$3"; else out="$4"; fi
if grep -q "^mu = 0.1" "$2" 2>/dev/null; then echo "error: simulated failure"; exit 3; fi
mkdir -p "$out"
echo "threads=$OMP_NUM_THREADS"
printf '{"status": "completed", "wall_time": 1.5, "measured": {"outcome": "Jump", "quantities": {"F_star": {"value": 0.9}}}}' > "$out/summary.json"
)");
  fs::permissions(exe, fs::perms::owner_all);
  return exe;
}

TEST(SweepExecute, RunsWhatIsLeftRecordsFailuresAndResumesInterruptedRuns) {
  const auto dir = scratch("execute");
  auto spec = small_spec(dir);
  prepare_folder(spec);
  // run-0002 was interrupted after a checkpoint: it must be resumed, not started again.
  const auto p2 = paths_of(spec, spec.runs[2]);
  write(p2.dir / "summary.json", R"({"status": "running"})");
  write(p2.dir / "checkpoint.bin", "x");

  ExecOptions o;
  o.executable = fake_program(dir);
  o.jobs = 2;
  o.threads = 3;
  std::ostringstream log;
  auto todo = runs_to_do(spec, false);
  ASSERT_EQ(todo.size(), 3u);
  std::size_t k = 0;
  const auto report = execute(
      spec, todo, [&] { return std::optional(k++); }, o, log);
  EXPECT_EQ(report.finished, 2);
  EXPECT_EQ(report.failed, 1);
  const auto calls = read(dir / "calls.txt");
  EXPECT_NE(calls.find("run --resume " + p2.dir.string() + " --quiet"), std::string::npos);
  EXPECT_NE(read(paths_of(spec, spec.runs[0]).log).find("threads=3"), std::string::npos);
  const auto p1 = paths_of(spec, spec.runs[1]);
  EXPECT_EQ(state_of(p1), RunState::Failed);
  EXPECT_NE(read(p1.failed).find("exit status 3"), std::string::npos);
  EXPECT_NE(read(p1.failed).find("simulated failure"), std::string::npos);
  EXPECT_NE(log.str().find("run-0001 FAILED"), std::string::npos);

  // Started again: nothing left but the failed run, which is retried only on request.
  EXPECT_TRUE(runs_to_do(spec, false).empty());
  EXPECT_EQ(runs_to_do(spec, true), (std::vector<std::size_t>{1}));

  // The table: one row per run, the measured values of finished runs, the failure's reason.
  const auto csv = dir / "out" / "sweep.csv";
  EXPECT_EQ(write_table(spec, csv), 2);
  const auto [header, r0, r1, r2] = table_start(csv);
  EXPECT_EQ(header.rfind("run,status,outcome,predicted_outcome,friction.mu [1],R [m]", 0), 0u);
  EXPECT_NE(header.find("F_star [N]"), std::string::npos);
  EXPECT_NE(header.find("alpha_F_lo [1]"), std::string::npos);
  EXPECT_EQ(r0.rfind("run-0000,completed,Jump,", 0), 0u) << r0;
  EXPECT_NE(r0.find(",0.9,"), std::string::npos);
  EXPECT_EQ(r1.rfind("run-0001,failed,undetermined,", 0), 0u) << r1;
  EXPECT_NE(r1.find("not analysed (failed)"), std::string::npos) << r1;
  EXPECT_NE(r1.find("exit status 3"), std::string::npos);
}

// A stand-in for a run that goes on until SIGINT, then leaves a checkpoint and the status of an
// interrupted run, as `snapjump run` does, and exits with 130.
fs::path patient_program(const fs::path& dir) {
  const fs::path exe = dir / "patient-snapjump";
  write(exe, R"(#!/bin/sh
echo "$@" >> ")" +
                 (dir / "calls.txt").string() + R"("
if [ "$2" = "--resume" ]; then out="$3"; else out="$4"; fi
mkdir -p "$out"
printf '{"status": "running"}' > "$out/summary.json"
trap 'printf x > "$out/checkpoint.bin"; printf "{\"status\": \"interrupted at t = 0.1 s\"}" > "$out/summary.json"; exit 130' INT
sleep 60 &
wait $!
)");
  fs::permissions(exe, fs::perms::owner_all);
  return exe;
}

// A stop request (Ctrl-C on the sweep): no run is started after it, the running ones get SIGINT
// passed on when it did not reach them, and are waited for; they are interrupted, not failed, and
// the next sweep resumes them.
TEST(SweepExecute, AStopRequestStopsTheRunsAndLeavesThemToResume) {
  const auto dir = scratch("stop");
  auto spec = small_spec(dir);
  prepare_folder(spec);
  ExecOptions o;
  o.executable = patient_program(dir);
  o.jobs = 2;
  const auto t0 = std::chrono::steady_clock::now();
  o.stop_requested = [&] {
    return std::chrono::steady_clock::now() - t0 > std::chrono::milliseconds(500);
  };
  std::ostringstream log;
  const auto todo = runs_to_do(spec, false);
  ASSERT_EQ(todo.size(), 3u);
  std::size_t k = 0;
  const auto report = execute(
      spec, todo, [&] { return std::optional(k++); }, o, log);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(report.stopped);
  EXPECT_EQ(report.interrupted, 2);
  EXPECT_EQ(report.failed, 0);
  EXPECT_LT(took, 30.0);           // the runs would have gone on for a minute
  EXPECT_GT(took, kForwardAfter);  // SIGINT passed on only after the grace period
  for (int i : {0, 1}) {
    const auto p = paths_of(spec, spec.runs[static_cast<std::size_t>(i)]);
    EXPECT_EQ(state_of(p), RunState::Resumable) << i;
    EXPECT_FALSE(fs::exists(p.failed)) << i;
  }
  EXPECT_EQ(state_of(paths_of(spec, spec.runs[2])), RunState::New);  // never started
  EXPECT_NE(log.str().find("run-0000 interrupted"), std::string::npos) << log.str();
  EXPECT_EQ(runs_to_do(spec, false), (std::vector<std::size_t>{0, 1, 2}));
}

TEST(SweepTable, AnOutcomeIsNeverBlankAndAnUndeterminedOneCarriesItsReason) {
  const auto dir = scratch("table-outcomes");
  const auto spec = small_spec(dir);
  prepare_folder(spec);
  // An analysis without an outcome, one written before the reason was recorded, a thrown run.
  write(paths_of(spec, spec.runs[0]).dir / "summary.json",
        R"({"status": "completed", "measured": {"outcome": null, "undetermined": "the record )"
        R"(ends 45.8 ms after the force peak"}})");
  write(paths_of(spec, spec.runs[1]).dir / "summary.json",
        R"({"status": "completed", "measured": {"outcome": null}})");
  write(paths_of(spec, spec.runs[2]).dir / "summary.json",
        R"({"status": "completed", "measured": {"outcome": "Thrown", "undetermined": null}})");
  const auto csv = dir / "out" / "sweep.csv";
  EXPECT_EQ(write_table(spec, csv), 1);
  const auto [header, r0, r1, r2] = table_start(csv);
  EXPECT_NE(header.find(",wall_time [s],undetermined,error"), std::string::npos) << header;
  EXPECT_EQ(r0.rfind("run-0000,completed,undetermined,", 0), 0u) << r0;
  EXPECT_NE(r0.find(",the record ends 45.8 ms after the force peak,"), std::string::npos) << r0;
  EXPECT_EQ(r1.rfind("run-0001,completed,undetermined,", 0), 0u) << r1;
  EXPECT_NE(r1.find("no reason recorded"), std::string::npos) << r1;
  EXPECT_EQ(r2.rfind("run-0002,completed,Thrown,", 0), 0u) << r2;
}

// Every sweep under examples/sweeps/ loads (load_spec builds every run's case, so a bad key or
// value in any run fails here), with the runs its comment announces for the lift sweeps.
TEST(SweepSpec, TheExampleSweepsLoad) {
  const auto dir = std::filesystem::path(SNAPJUMP_SOURCE_DIR) / "examples" / "sweeps";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    Spec spec;
    EXPECT_NO_THROW(spec = load_spec(entry.path()));
    EXPECT_FALSE(spec.runs.empty());
    if (entry.path().filename() == "lift-axi.toml") {
      EXPECT_EQ(spec.runs.size(), 10u);
      EXPECT_EQ(make_case(spec, spec.runs.front()).numerics.model, config::Model::Axisymmetric);
    }
    ++count;
  }
  EXPECT_GE(count, 6);
}

}  // namespace
}  // namespace snapjump::sweep
