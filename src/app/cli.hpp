// The snapjump command line, as a library function so that tests can run it in-process.
#pragma once

#include <exception>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace snapjump::app {

// Exit codes.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   // the program failed (I/O, numerics)
inline constexpr int kExitBadInput = 2;  // bad command line or case file
// A run that ended in its preparation, before the release: the shell did not invert, or snapped
// back before the release (summary.json's status; its hints say what to try).
inline constexpr int kExitNotPrepared = 3;
// A file could not be written (a full disk, a folder that cannot be written): the message names
// it, no temporary file is left, and a run's summary says "failed: could not write FILE".
inline constexpr int kExitWriteFailed = 4;
// A run stopped by Ctrl-C (or the stop hook), 128 + SIGINT as a shell reports a process ended
// by the signal; past the release it can be resumed.
inline constexpr int kExitInterrupted = 130;

// What a program that embeds the command line (the Python module) can hook into.
struct CliHooks {
  // Asked now and then during a run (a few times a second): true stops it as Ctrl-C does, with a
  // checkpoint when it is past the release (the run can be resumed). Without it, `run` takes
  // SIGINT itself (app::SigintStop).
  std::function<bool()> stop_requested;
};

// What an error that ends a command says: e.what(), except that running out of memory
// (std::bad_alloc, whose what() is a bare "std::bad_alloc") says "out of memory while DOING".
std::string error_text(const std::exception& e, std::string_view doing);

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            const CliHooks& hooks = {});

}  // namespace snapjump::app
