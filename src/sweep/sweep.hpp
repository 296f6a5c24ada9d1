// Sweeps: many popper runs that differ in a few case values, described by one sweep file.
//
// A sweep file (TOML) names a base case and the values to vary:
//
//   title = "net weight and thickness"
//   base = "../default.toml"              # optional; the built-in default case without it
//   output = "runs/sweep-weight"          # optional; relative to the sweep file's folder
//   [set]                                 # the same for every run
//   numerics.resolution = "coarse"
//   [vary]                                # Cartesian product of these
//   popper.net_weight = ["0.48 N", "1 N", "3 N"]
//   shell.h = { from = "1.5 mm", to = "2.5 mm", count = 3 }   # also: scale = "log"
//   [zip]                                 # lists of one length, taken position by position
//   shell.R = ["25 mm", "30 mm"]
//   material.E = ["1.2 MPa", "1.0 MPa"]
//
// Runs are numbered run-0000, run-0001, ... in the order of the product (the last [vary] key
// changes fastest; the zip position is the outermost). Each run has its own case file, folder
// and log under the sweep's output folder, so a sweep killed half-way and started again skips
// what has finished and resumes what was interrupted.
#pragma once
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "config/case.hpp"
#include "config/input_error.hpp"

namespace snapjump::sweep {

// Bad sweep file or output folder; what() names the file, the key and what was expected.
class SweepError : public InputError {
 public:
  using InputError::InputError;
};

// One case value: key "popper.net_weight", text "0.48 N" (a bare number is SI), origin for
// messages ("sweep.toml:7").
struct Setting {
  std::string key;
  std::string text;
  std::string origin;
};

struct RunPlan {
  std::string name;               // run-0003
  std::vector<Setting> settings;  // the varied values of this run, in the order of varied_keys
};

struct Spec {
  std::filesystem::path file;  // the sweep file
  std::string title;
  std::optional<std::filesystem::path> base;  // the base case file; the built-in case if absent
  std::vector<Setting> fixed;                 // [set]
  std::vector<std::string> varied_keys;       // [zip] keys, then [vary] keys
  std::vector<RunPlan> runs;
  std::filesystem::path output;  // the sweep's folder
};

// Reads a sweep file. Checks every key against the case format and builds every run's case
// once, so that a bad value is reported before anything runs. Throws SweepError.
Spec load_spec(const std::filesystem::path& file);
Spec parse_spec(std::string_view toml_text, const std::filesystem::path& file);

// The case of one run: the base case, then [set], then the run's values.
config::Case make_case(const Spec& spec, const RunPlan& run);

// Where a run's files live inside the sweep folder.
struct RunPaths {
  std::filesystem::path case_file;  // cases/run-0003.toml
  std::filesystem::path dir;        // runs/run-0003
  std::filesystem::path log;        // logs/run-0003.log
  std::filesystem::path failed;     // logs/run-0003.failed: why the run failed
};
RunPaths paths_of(const Spec& spec, const RunPlan& run);

enum class RunState {
  New,          // nothing yet
  Done,         // a summary with a final status (completed, snapped back, did not invert)
  Failed,       // the run failed: its summary says so, or the sweep recorded why
  Resumable,    // interrupted after a checkpoint
  Interrupted,  // interrupted before its first checkpoint: starts again
};
std::string_view to_string(RunState s);
RunState state_of(const RunPaths& p);
// A failed run that did not record a failure itself (its summary is not "failed: ...": it was
// killed from outside, as the OOM killer does) and has a checkpoint: a retry resumes it from
// there instead of starting it again.
bool resumes_after_kill(const RunPaths& p);

// Refuses, with a SweepError, an output folder that holds a different sweep (its plan.csv
// differs) or something else than a sweep (no plan.csv, and more than a sweep.lock or nothing).
// Writes nothing: it comes before the sweep takes its lock in the folder.
void check_folder(const Spec& spec);

// Prepares the sweep folder: plan.csv (after check_folder, again) and one case file per run.
// Safe to call again on the same sweep.
void prepare_folder(const Spec& spec);

// One row per run, in run order: the case, the theory's bounds and the measured quantities
// (columns documented in docs/sweeps.md). Returns the number of runs with a result.
int write_table(const Spec& spec, const std::filesystem::path& csv);

}  // namespace snapjump::sweep
