// `snapjump sweep sweep.toml`: many runs from one sweep file, on one machine or over MPI.
#pragma once
#include <ostream>
#include <string>

namespace CLI {
class App;
}

namespace snapjump::app {

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
