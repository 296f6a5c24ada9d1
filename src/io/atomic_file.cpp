#include "io/atomic_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace snapjump::io {

void write_file_atomically(const std::filesystem::path& path, std::string_view contents,
                           bool binary) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  const auto fail = [&](const std::string& why) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);  // no half-written temporary is left behind
    throw WriteFailed(path, why);
  };
  {
    errno = 0;
    std::ofstream f(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
    f.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    f.flush();
    if (f) f.close();
    if (!f) fail(errno != 0 ? std::strerror(errno) : "an output error");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) fail(fmt::format("cannot rename {} over it: {}", tmp.string(), ec.message()));
}

}  // namespace snapjump::io
