// Reading a whole file, the counterpart of io::write_file_atomically: every reader of the
// project (cases, sweep files, records, tables, snapshots, checkpoints) gets its bytes here, so a
// missing file, a folder given for a file or an unreadable one is reported in one way.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace snapjump::text {

// A file that could not be written (a full disk, a folder that cannot be written): its message
// is "could not write PATH: why"; the command line ends with app::kExitWriteFailed. Every writer
// throws it (io::write_file_atomically, and the series' writer that appends row by row), and
// io::WriteFailed names the same type.
class WriteFailed : public std::runtime_error {
 public:
  WriteFailed(const std::filesystem::path& path, const std::string& why);
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline constexpr std::uintmax_t kAnySize = std::numeric_limits<std::uintmax_t>::max();

// Reads the file into `bytes`. Returns what went wrong, in words that follow the file's name
// ("no such file", "is a folder, not a file", "is not a regular file", "more than N bytes such a
// file can have", "cannot be read (why)"), or nothing when it was read. Only regular files are
// read (a pipe or a device could be endless).
std::optional<std::string> read_file_into(const std::filesystem::path& path, std::string& bytes,
                                          std::uintmax_t max_bytes = kAnySize);

// The file's bytes. Throws Error (built from a message) naming the file and what went wrong;
// `what`, when given, says what the file should have been ("the case file").
template <class Error>
std::string read_file(const std::filesystem::path& path, std::string_view what = {},
                      std::uintmax_t max_bytes = kAnySize) {
  std::string bytes;
  if (const auto why = read_file_into(path, bytes, max_bytes)) {
    if (what.empty()) throw Error(fmt::format("{}: {}", path.string(), *why));
    throw Error(fmt::format("{}: {} ({})", path.string(), *why, what));
  }
  return bytes;
}

}  // namespace snapjump::text
