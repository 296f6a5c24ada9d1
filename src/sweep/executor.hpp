// Runs the runs of a sweep as child processes (`snapjump run`), a few at a time.
//
// Each run is its own process: a run that crashes or runs out of memory takes nothing else
// with it, gmsh (which keeps global state) never sees two runs at once, and each run's
// OpenMP threads are set through its environment. The next run to start comes from a
// WorkSource: a counter on one machine, or a counter shared by all MPI processes.
#pragma once
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "sweep/sweep.hpp"

namespace snapjump::sweep {

struct ExecOptions {
  std::filesystem::path executable;  // the snapjump program that runs each case
  int jobs = 1;                      // runs at the same time (in this process)
  int threads = 1;                   // OpenMP threads per run
  bool retry_failed = false;         // run again what failed before
  std::string label;                 // prefix of progress lines ("rank 1: "), may be empty
  // Asked a few times a second: true stops the sweep. No run is started after it; the running
  // ones stop as a Ctrl-C stops them (a terminal's Ctrl-C reaches them too; a stop that did not
  // is passed on to them as SIGINT after kForwardAfter) and are waited for.
  std::function<bool()> stop_requested;
};

// How long a stopped sweep waits before it passes SIGINT on to its runs itself [s].
inline constexpr double kForwardAfter = 2.0;

// Hands out positions in the to-do list; nullopt when there are none left.
using WorkSource = std::function<std::optional<std::size_t>()>;

struct ExecReport {
  int finished = 0;      // ran to a final status here
  int failed = 0;        // failed here
  int interrupted = 0;   // stopped by the stop request, to be resumed by the next sweep
  bool stopped = false;  // the stop request came
};

// The runs that still need work (not done; failed ones only with retry_failed).
std::vector<std::size_t> runs_to_do(const Spec& spec, bool retry_failed);

// Runs todo[k] for each k the source gives, `jobs` at a time; `idle` is called about five times
// a second while waiting (MPI progress). Progress lines go to `log`.
ExecReport execute(const Spec& spec, const std::vector<std::size_t>& todo, const WorkSource& next,
                   const ExecOptions& options, std::ostream& log,
                   const std::function<void()>& idle = {});

// The running program, for starting the runs (/proc/self/exe).
std::filesystem::path self_executable();

}  // namespace snapjump::sweep
