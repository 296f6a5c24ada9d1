// The status a run writes into its summary.json ("status"): words a person reads, and the one
// place where a program (the run's exit status, a sweep's bookkeeping) reads them back.
#pragma once

#include <string>
#include <string_view>

namespace snapjump::io::run_status {

inline constexpr std::string_view kRunning = "running";
inline constexpr std::string_view kCompleted = "completed";  // reached the end time
inline constexpr std::string_view kCompletedAtApex = "completed (apex of the flight)";
inline constexpr std::string_view kSnappedBack = "snapped back before release";
inline constexpr std::string_view kDidNotInvert = "did not invert";
inline constexpr std::string_view kFailed = "failed";  // "failed: why"
inline constexpr std::string_view kPaused = "paused";  // "paused at t = ...; continue with ..."

inline std::string failure(std::string_view why) {
  return std::string(kFailed) + ": " + std::string(why);
}
[[nodiscard]] inline bool failed(std::string_view status) { return status.starts_with(kFailed); }
// A run that has its result: it went to its end, or the preparation told the outcome.
[[nodiscard]] inline bool finished(std::string_view status) {
  return status.starts_with(kCompleted) || status == kSnappedBack || status == kDidNotInvert;
}

}  // namespace snapjump::io::run_status
