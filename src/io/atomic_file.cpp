#include "io/atomic_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>
#include <system_error>

namespace snapjump::io {

void write_file_atomically(const std::filesystem::path& path, std::string_view contents,
                           bool binary) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
    f.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    f.flush();
    if (!f) throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    throw std::runtime_error(
        fmt::format("cannot replace {} with {}: {}", path.string(), tmp.string(), ec.message()));
  }
}

}  // namespace snapjump::io
