// `snapjump run`'s command line: a new run from a case, --resume of a run's folder, or
// --reanalyze of a finished one (the run itself: app/run.hpp).
#pragma once

#include <map>
#include <ostream>
#include <string>

#include "app/case_options.hpp"
#include "app/cli.hpp"
#include "app/run.hpp"

namespace CLI {
class App;
}

namespace snapjump::app {

class RunCommand {
 public:
  explicit RunCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  // Returns the exit status; bad input throws InputError (the caller prints it). Without
  // hooks.stop_requested, Ctrl-C stops the run with a checkpoint (SigintStop).
  int run(std::ostream& out, std::ostream& err, const CliHooks& hooks) const;

 private:
  // Whether the command line sets up a new run, which --resume and --reanalyze take from the
  // run's folder instead (`values` are the case values it gives).
  [[nodiscard]] bool sets_up_a_run(const std::map<std::string, std::string>& values) const;
  int resume(RunOptions options, std::ostream& out, std::ostream& err) const;

  CLI::App* cmd_ = nullptr;
  CaseOptions case_;
  RunOptions options_;
  std::string resolution_, model_, bulk_;
  int fan_layer_ = -1;
  std::string snaps_;  // --inverted-snaps
  std::string pause_at_;
  std::string reanalyze_;
};

}  // namespace snapjump::app
