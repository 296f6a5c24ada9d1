// `snapjump predict`: the closed-form theory for one popper, and the buckling and reverse-snap
// suctions from the axisymmetric model's pressure-volume branch.
#pragma once

#include <ostream>
#include <string>

#include "app/case_options.hpp"

namespace CLI {
class App;
}

namespace snapjump::app {

class PredictCommand {
 public:
  explicit PredictCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  // Returns the exit status; bad input throws InputError (the caller prints it).
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* cmd_ = nullptr;
  CaseOptions case_;
  std::string format_ = "table";
  bool no_branch_ = false;
};

}  // namespace snapjump::app
