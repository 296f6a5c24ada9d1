// The snapjump command line, as a library function so that tests can run it in-process.
#pragma once

#include <ostream>

namespace snapjump::app {

// Exit codes.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   // the program failed (I/O, numerics)
inline constexpr int kExitBadInput = 2;  // bad command line or case file

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace snapjump::app
