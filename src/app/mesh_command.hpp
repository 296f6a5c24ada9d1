// `snapjump mesh`: the shell the simulator would use, written as a gmsh .msh file to edit and
// name in a case (docs/shells.md).
#pragma once

#include <ostream>
#include <string>

#include "app/case_options.hpp"

namespace CLI {
class App;
}

namespace snapjump::app {

class MeshCommand {
 public:
  explicit MeshCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  // Returns the exit status; bad input throws InputError (the caller prints it).
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* cmd_ = nullptr;
  CaseOptions case_;
  std::string resolution_;
  std::string output_;
};

}  // namespace snapjump::app
