// `snapjump run`: the simulated experiment of one popper, into a new output folder.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "config/case.hpp"

namespace snapjump::app {

struct RunOptions {
  std::string output;  // folder to create; empty: runs/<case name>-<date-time>
  bool quiet = false;  // no progress lines
  // Stop at this simulated time after the release, leaving a checkpoint to resume from.
  std::optional<double> pause_at;
  // Continue the run in this folder from its checkpoint (the case comes from its case.toml).
  std::string resume;
  // For tests of crash safety: on resume, fail (throw) after rewriting this many rows of the
  // series, as a run killed in the middle of the rewrite would stop.
  std::optional<std::size_t> fault_after_rewritten_rows;
  // Asked a few times a second: true stops the run (after the release with a checkpoint and the
  // status "paused", to resume; during the preparation with an error).
  std::function<bool()> stop_requested;
};

// Runs the protocol (buckle, set, ground, release) and writes series.csv, summary.json,
// snapshots/*.vtu and run.pvd. Returns an exit status; throws config::CaseError for bad input.
int run_simulation(const config::Case& c, const RunOptions& options, std::ostream& out,
                   std::ostream& err);

// Analyses a finished run's series.csv again (with this build's analysis and theory) and
// rewrites the measured quantities, the theory and the comparison in its summary.json; the time
// series and snapshots are left as they are. Throws config::CaseError for a folder that is not a
// finished run.
int reanalyze_run(const std::filesystem::path& dir, std::ostream& out);

}  // namespace snapjump::app
