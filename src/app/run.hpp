// `snapjump run`: the simulated experiment of one popper, into a new output folder.
#pragma once

#include <signal.h>

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
  // With resume: the run's new cap on simulated time [s] (--end-time), written into its
  // case.toml; a run that went to its cap goes on from there to this one or to the apex.
  std::optional<double> end_time;
  // For tests of crash safety: on resume, fail (throw) after rewriting this many rows of the
  // series, as a run killed in the middle of the rewrite would stop.
  std::optional<std::size_t> fault_after_rewritten_rows;
  // Asked a few times a second: true stops the run with the status "interrupted" and the exit
  // status kExitInterrupted (after the release with a checkpoint, to resume; during the
  // preparation with nothing to resume).
  std::function<bool()> stop_requested;
};

// Ctrl-C for a run: while one lives, SIGINT only sets a flag that requested() reads, which the
// run's stop_requested asks; the handler before it comes back when it is destroyed. A second
// SIGINT ends the process as the default action does (the handler is reset once it has run).
class SigintStop {
 public:
  SigintStop();
  ~SigintStop();
  SigintStop(const SigintStop&) = delete;
  SigintStop& operator=(const SigintStop&) = delete;
  [[nodiscard]] bool requested() const;

 private:
  struct sigaction previous_ {};
  bool installed_ = false;
};

// Runs the protocol (buckle, set, ground, release) and writes series.csv, summary.json,
// snapshots/*.vtu and run.pvd. Returns an exit status (kExitNotPrepared when the preparation
// ended the run, with what to try); throws config::CaseError for bad input.
int run_simulation(const config::Case& c, const RunOptions& options, std::ostream& out,
                   std::ostream& err);

// Analyses a finished run's series.csv again (with this build's analysis and theory) and
// rewrites the measured quantities, the theory and the comparison in its summary.json; the time
// series and snapshots are left as they are. Throws config::CaseError for a folder that is not a
// finished run.
int reanalyze_run(const std::filesystem::path& dir, std::ostream& out);

}  // namespace snapjump::app
