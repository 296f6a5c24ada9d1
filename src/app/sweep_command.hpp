// `snapjump sweep sweep.toml`: many runs from one sweep file, on one machine or over MPI.
#pragma once
#include <ostream>
#include <string>

#include "sweep/executor.hpp"
#include "sweep/sweep.hpp"

namespace CLI {
class App;
}

namespace snapjump::app {

// Runs the sweep's runs that are still to do (all but the finished, and the failed unless
// retry_failed) in this process, `jobs` at a time (0: the cores over the threads per run), and
// writes its table; the caller holds the folder's lock. Returns the exit status.
int run_here(const sweep::Spec& spec, sweep::ExecOptions options, int jobs, bool retry_failed,
             std::ostream& out);

class SweepCommand {
 public:
  explicit SweepCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  int run(std::ostream& out, std::ostream& err) const;

 private:
  // --dry-run: the runs and their states.
  void list_runs(const sweep::Spec& spec, std::ostream& out) const;
  // The sweep shared among the processes of mpirun (rank 0 prepares the folder and writes the
  // table); the exit status.
  int run_over_mpi(const sweep::Spec& spec, sweep::ExecOptions options, std::ostream& out,
                   std::ostream& err) const;
  // The sweep (or with --table-only its table) in this process alone; the exit status.
  int run_in_this_process(const sweep::Spec& spec, const sweep::ExecOptions& options,
                          std::ostream& out, std::ostream& err) const;

  CLI::App* cmd_ = nullptr;
  std::string file_;
  std::string output_;
  int jobs_ = 0;     // 0: from the cores
  int threads_ = 1;  // per run
  bool retry_failed_ = false;
  bool dry_run_ = false;
  bool table_only_ = false;
};

}  // namespace snapjump::app
