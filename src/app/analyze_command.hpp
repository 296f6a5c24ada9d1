// `snapjump analyze RECORD...`: the characteristic quantities of time series, simulated or
// measured on a force plate (measure/analysis.hpp, docs/analysis.md), as a table, JSON or CSV.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace snapjump::app {

class AnalyzeCommand {
 public:
  explicit AnalyzeCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  // Returns the exit status (2 when a record of several could not be read: the others are still
  // analysed); bad input throws InputError (the caller prints it).
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* cmd_ = nullptr;
  std::vector<std::string> records_;
  std::string case_file_;
  std::string R_;
  std::string force_threshold_;
  std::string force_offset_;
  std::string settle_time_;
  bool complete_ = false;
  std::vector<std::string> columns_;  // NAME=HEADER
  std::vector<std::string> units_;    // NAME=UNIT
  std::string format_ = "table";
};

}  // namespace snapjump::app
