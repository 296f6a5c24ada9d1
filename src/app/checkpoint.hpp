// Checkpoints of a run: the popper's state and the release loop's, in one file that is replaced
// atomically and read back only after it has been checked (a checksum over its bytes, then every
// field: lengths against the model, times finite, snapshot names of the run's own form).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "popper/popper.hpp"
#include "popper/state_io.hpp"

namespace snapjump::app {

// What the release loop needs besides the popper, saved in checkpoints with it.
struct LoopState {
  double next_sample = 0.0, next_snapshot = 0.0, next_checkpoint = 0.0;
  // Where the flight stands (its airborne_since is saved; R and snapped follow from the case and
  // the series).
  popper::FlightWatch flight;
  std::uint64_t rows = 0;  // rows of series.csv that belong to this state
  std::vector<std::pair<double, std::string>> frames;  // (time, snapshots/frame_NNNNN.vtu)
};

// A checkpoint that cannot be used. what() says why.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using popper::fnv1a64;

// The checkpoint's bytes: the popper's state, the loop's, then a trailer with the checksum of
// everything before it.
std::string encode_checkpoint(const popper::Popper& pop, const LoopState& loop);
// Restores the popper from the bytes and returns the loop's state; `what` names the file in
// messages. A checkpoint written before the trailer existed (no checksum) is read with the same
// field checks. Throws CheckpointError.
LoopState decode_checkpoint(std::string_view bytes, popper::Popper& pop, std::string_view what);

// dir/checkpoint.bin, replaced atomically (written to a temporary file, then renamed).
void write_checkpoint(const std::filesystem::path& dir, const popper::Popper& pop,
                      const LoopState& loop);
// Reads dir/checkpoint.bin into pop. Throws CheckpointError (config::CaseError when there is none).
LoopState read_checkpoint(const std::filesystem::path& dir, popper::Popper& pop);

}  // namespace snapjump::app
