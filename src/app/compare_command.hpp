// `snapjump compare RECORD... RUN_DIR`: measured records beside a simulated run and the theory's
// bounds, in one table (measure/comparison.hpp), with the overlay figure beside it.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace snapjump::app {

class CompareCommand {
 public:
  explicit CompareCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  // Returns the exit status; bad input throws InputError (the caller prints it).
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* cmd_ = nullptr;
  std::vector<std::string> inputs_;  // the records, then the run's folder
  std::vector<std::string> columns_, units_;
  std::string force_offset_, settle_time_, force_resolution_ = "12 mN", ring_width_,
                                           length_resolution_;
  bool complete_ = false;
  std::string format_ = "table";
  std::string figure_;
  bool no_figure_ = false;
};

}  // namespace snapjump::app
