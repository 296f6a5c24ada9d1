#include "config/files.hpp"

#include <array>
#include <fstream>
#include <system_error>

namespace snapjump::text {

WriteFailed::WriteFailed(const std::filesystem::path& path, const std::string& why)
    : std::runtime_error(fmt::format("could not write {}: {}", path.string(), why)), path_(path) {}

std::optional<std::string> read_file_into(const std::filesystem::path& path, std::string& bytes,
                                          std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) {
    return fmt::format("cannot be read ({})", ec.message());
  }
  if (!fs::exists(status)) return "no such file";
  if (fs::is_directory(status)) return "is a folder, not a file";
  // A pipe or a device could be endless: only regular files are read.
  if (!fs::is_regular_file(status)) return "is not a regular file";
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot be read";
  bytes.clear();
  // At most max_bytes + 1 bytes, so that a file that grew since it was looked at is still caught.
  std::array<char, 1 << 16> chunk{};
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    bytes.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (bytes.size() > max_bytes) {
      return fmt::format("more than the {} bytes such a file can have", max_bytes);
    }
  }
  if (in.bad()) return "cannot be read (an input error)";
  return std::nullopt;
}

}  // namespace snapjump::text
