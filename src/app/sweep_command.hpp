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
