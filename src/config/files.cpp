#include "config/files.hpp"

#include <fstream>
#include <system_error>

namespace snapjump::text {

std::optional<std::string> read_file_into(const std::filesystem::path& path, std::string& bytes,
                                          std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) return "no such file";
  if (fs::is_directory(status)) return "is a folder, not a file";
  const auto size = fs::file_size(path, ec);
  if (!ec && size > max_bytes) {
    return fmt::format("{} bytes, more than the {} such a file can have", size, max_bytes);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot be read";
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in.bad()) return "cannot be read";
  return std::nullopt;
}

}  // namespace snapjump::text
