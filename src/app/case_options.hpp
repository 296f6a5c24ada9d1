// The case flags that the subcommands reading a case share (--R, --E, ..., the case file), and
// what the case's reader noticed, said before a command works on it.
#pragma once

#include <map>
#include <ostream>
#include <string>

#include "config/case.hpp"

namespace CLI {
class App;
}

namespace snapjump::app {

// What the case's reader noticed (config::Case::bare_numbers, implausible), said before a command
// works on the case: a bare number as a warning; a value outside what a popper can plausibly be
// refused, or with `allow` a warning too.
void say_readings(const config::Case& c, bool allow, std::ostream& err);

// Flags that set case keys, shared by the subcommands that read a case.
struct CaseOptions {
  std::string case_file;
  std::map<std::string, std::string> values;  // case key -> text
  bool allow_implausible = false;

  // Registers the case file (positional) and one flag per quantity key of the case format.
  void add_to(CLI::App& cmd);
  // The case, its bare numbers said on err; throws config::CaseError for an implausible one.
  [[nodiscard]] config::Case load(std::ostream& err) const;
};

}  // namespace snapjump::app
