#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

namespace snapjump::io {

FolderLock::FolderLock(const std::filesystem::path& folder, const std::string& name,
                       const std::string& what) {
  const auto path = folder / name;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error(
        fmt::format("cannot make the lock file {}: {}", path.string(), std::strerror(errno)));
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    std::string holder;
    std::ifstream(path) >> holder;
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK) {
      throw FolderBusy(
          fmt::format("{} {} is in use by another process{} (lock {})", what, folder.string(),
                      holder.empty() ? "" : fmt::format(" (pid {})", holder), path.string()));
    }
    throw std::runtime_error(fmt::format("cannot lock {}: {}", path.string(), std::strerror(err)));
  }
  // Say who holds it, for the message of the next one that tries.
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const auto n = ::pwrite(fd_, pid.data(), pid.size(), 0);
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace snapjump::io
