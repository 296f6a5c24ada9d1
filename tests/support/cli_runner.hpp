// Runs the snapjump command line in-process for tests: exit status and what it printed.
#pragma once
#include <sstream>
#include <string>
#include <vector>

#include "app/cli.hpp"

namespace snapjump::test_support {

struct CliResult {
  int code = -1;
  std::string out;
  std::string err;
};

// run_cli({"predict", "--format", "json"}) runs `snapjump predict --format json`.
inline CliResult run_cli(std::vector<std::string> args) {
  args.insert(args.begin(), "snapjump");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  CliResult r;
  r.code = app::run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

}  // namespace snapjump::test_support
