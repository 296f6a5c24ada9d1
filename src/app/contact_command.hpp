// `snapjump contact`: the shell-plane contact problem (contact/contact.hpp): N+, n(2), N-, the
// mirror-buckling energy and the prefactor bounds at a Poisson ratio, and its branches as CSV.
#pragma once

#include <ostream>
#include <string>

namespace CLI {
class App;
}

namespace snapjump::app {

class ContactCommand {
 public:
  explicit ContactCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  // Returns the exit status: 2 for a Poisson ratio outside (-1, 0.5], 1 when --curves cannot be
  // written (errors printed to err).
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* cmd_ = nullptr;
  double nu_ = 0.5;
  std::string format_ = "table";
  std::string curves_;
};

}  // namespace snapjump::app
