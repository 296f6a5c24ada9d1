// The status a run writes into its summary.json ("status"): words a person reads, and the one
// place where a program (the run's exit status, a sweep's bookkeeping) reads them back.
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>

namespace snapjump::io::run_status {

inline constexpr std::string_view kRunning = "running";
// Reached its end time without an end rule to say more: the status of runs made before the cap
// existed; read as capped.
inline constexpr std::string_view kCompleted = "completed";
inline constexpr std::string_view kCompletedAtApex = "completed (apex of the flight)";
inline constexpr std::string_view kCapped = "capped";  // "capped at T s before the apex ..."
inline constexpr std::string_view kSnappedBack = "snapped back before release";
inline constexpr std::string_view kDidNotInvert = "did not invert";
inline constexpr std::string_view kFailed = "failed";  // "failed: why"
inline constexpr std::string_view kPaused = "paused";  // "paused at t = ...; continue with ..."
// "interrupted at t = ...; continue with ..." (Ctrl-C), or "interrupted in the preparation ...".
inline constexpr std::string_view kInterrupted = "interrupted";

inline std::string failure(std::string_view why) {
  return std::string(kFailed) + ": " + std::string(why);
}
// A run stopped by its cap on simulated time (end_time [s]) before the flight's apex.
inline std::string capped_at(double end_time) {
  return fmt::format("{} at {:.6g} s before the apex of the flight (H and H_s are lower bounds)",
                     kCapped, end_time);
}
[[nodiscard]] inline bool failed(std::string_view status) { return status.starts_with(kFailed); }
// The record ends at the cap, before the apex: its H and H_s are lower bounds.
[[nodiscard]] inline bool capped(std::string_view status) {
  return status.starts_with(kCapped) || status == kCompleted;
}
[[nodiscard]] inline bool interrupted(std::string_view status) {
  return status.starts_with(kInterrupted);
}
// A run that has its result: it went to its end (the apex or the cap), or the preparation told
// the outcome.
[[nodiscard]] inline bool finished(std::string_view status) {
  return status.starts_with(kCompleted) || capped(status) || status == kSnappedBack ||
         status == kDidNotInvert;
}

}  // namespace snapjump::io::run_status
