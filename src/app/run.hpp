// `snapjump run`: the simulated experiment of one popper, into a new output folder.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "config/case.hpp"

namespace snapjump::app {

struct RunOptions {
  std::string output;  // folder to create; empty: runs/<case name>-<date-time>
  bool quiet = false;  // no progress lines
};

// Runs the protocol (buckle, set, ground, release) and writes series.csv, summary.json,
// snapshots/*.vtu and run.pvd. Returns an exit status; throws config::CaseError for bad input.
int run_simulation(const config::Case& c, const RunOptions& options, std::ostream& out,
                   std::ostream& err);

}  // namespace snapjump::app
