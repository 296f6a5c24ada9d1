#include "app/checkpoint.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

#include "config/case.hpp"
#include "config/files.hpp"
#include "io/atomic_file.hpp"
#include "popper/state_io.hpp"

namespace snapjump::app {
namespace fs = std::filesystem;
namespace {

constexpr char kLoopMagic[] = "snapjump-run-loop-1";
constexpr char kTrailerMagic[] = "snapjump-checksum-1";
constexpr std::size_t kTrailer = sizeof kTrailerMagic + sizeof(std::uint64_t);
// Bounds far above any run's, below anything that would exhaust memory.
constexpr std::uint64_t kMaxFrames = 10'000'000, kMaxName = 4096;
constexpr std::uintmax_t kMaxFile = std::uintmax_t{16} << 30;

using popper::get;
using popper::put;

}  // namespace

std::string encode_checkpoint(const popper::Popper& pop, const LoopState& s) {
  std::ostringstream f(std::ios::binary);
  pop.save_state(f);
  f.write(kLoopMagic, sizeof kLoopMagic);
  for (double d : {s.next_sample, s.next_snapshot, s.next_checkpoint, s.flight.airborne_since})
    put(f, d);
  put(f, s.rows);
  put(f, static_cast<std::uint64_t>(s.frames.size()));
  for (const auto& [t, name] : s.frames) {
    put(f, t);
    put(f, static_cast<std::uint64_t>(name.size()));
    f.write(name.data(), static_cast<std::streamsize>(name.size()));
  }
  std::string bytes = std::move(f).str();
  const std::uint64_t sum = fnv1a64(bytes);
  bytes.append(kTrailerMagic, sizeof kTrailerMagic);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  return bytes;
}

LoopState decode_checkpoint(std::string_view bytes, popper::Popper& pop, std::string_view what) {
  const auto fail = [&](const std::string& why) {
    return CheckpointError(fmt::format("{}: {}", what, why));
  };
  // No trailer, no resume: a file cut short (or cut and re-sealed by hand) could otherwise drop
  // the rows recorded before it without a word.
  if (bytes.size() < kTrailer || std::memcmp(bytes.data() + bytes.size() - kTrailer, kTrailerMagic,
                                             sizeof kTrailerMagic) != 0) {
    throw fail("it ends without its checksum: the file is truncated or was not written whole");
  }
  const std::string_view body = bytes.substr(0, bytes.size() - kTrailer);
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + bytes.size() - sizeof sum, sizeof sum);
  if (sum != fnv1a64(body)) {
    throw fail("the checksum does not match its contents: the file is damaged");
  }
  std::istringstream f{std::string(body), std::ios::binary};
  try {
    pop.load_state(f);
  } catch (const std::exception& e) {
    throw fail(e.what());
  }
  char magic[sizeof kLoopMagic] = {};
  f.read(magic, sizeof magic);
  if (!f || std::memcmp(magic, kLoopMagic, sizeof kLoopMagic) != 0) {
    throw fail("the release loop's state is missing or damaged");
  }
  LoopState s;
  std::uint64_t n = 0;
  get(f, s.next_sample);
  get(f, s.next_snapshot);
  get(f, s.next_checkpoint);
  get(f, s.flight.airborne_since);
  get(f, s.rows);
  get(f, n);
  if (!f) throw fail("truncated in the release loop's state");
  for (const double t : {s.next_sample, s.next_snapshot, s.next_checkpoint}) {
    if (!std::isfinite(t) || t < 0.0) {
      throw fail(fmt::format("a next sample, snapshot or checkpoint time of {} s", t));
    }
  }
  if (!std::isfinite(s.flight.airborne_since) || s.flight.airborne_since < -1.0) {
    throw fail(fmt::format("a flight start of {} s", s.flight.airborne_since));
  }
  if (n > kMaxFrames) throw fail(fmt::format("{} snapshots listed", n));
  const std::regex frame_name(R"(snapshots/frame_[0-9]{5,9}\.vtu)");
  for (std::uint64_t k = 0; k < n; ++k) {
    double t = 0.0;
    std::uint64_t len = 0;
    get(f, t);
    get(f, len);
    if (!f) throw fail("truncated in the list of snapshots");
    if (len > kMaxName) throw fail(fmt::format("a snapshot name of {} bytes", len));
    std::string name(len, '\0');
    f.read(name.data(), static_cast<std::streamsize>(len));
    if (!f) throw fail("truncated in the list of snapshots");
    if (!std::isfinite(t) || t < 0.0) throw fail(fmt::format("a snapshot at t = {} s", t));
    if (!std::regex_match(name, frame_name)) {
      throw fail("a snapshot name that is not one of the run's own (snapshots/frame_NNNNN.vtu)");
    }
    s.frames.emplace_back(t, std::move(name));
  }
  f.peek();
  if (!f.eof()) throw fail("bytes after the end of the state");
  return s;
}

void write_checkpoint(const fs::path& dir, const popper::Popper& pop, const LoopState& loop) {
  io::write_file_atomically(dir / "checkpoint.bin", encode_checkpoint(pop, loop), true);
}

LoopState read_checkpoint(const fs::path& dir, popper::Popper& pop) {
  const fs::path path = dir / "checkpoint.bin";
  std::error_code ec;
  if (fs::status(path, ec).type() == fs::file_type::not_found) {
    throw config::CaseError(
        fmt::format("--resume {}: no checkpoint.bin; the run stopped before its first checkpoint "
                    "(run it again)",
                    dir.string()));
  }
  return decode_checkpoint(text::read_file<CheckpointError>(path, "a run's checkpoint", kMaxFile),
                           pop, path.string());
}

}  // namespace snapjump::app
