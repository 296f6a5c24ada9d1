#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <optional>

#include "config/text.hpp"

namespace snapjump::io {
namespace {

namespace fs = std::filesystem;

std::runtime_error cannot_make(const fs::path& path, int err) {
  return std::runtime_error(
      fmt::format("cannot make the lock file {}: {}", path.string(), std::strerror(err)));
}

// What stands where the lock file should be, when it cannot be opened as a file.
LockFileRefused refused(const fs::path& path) {
  std::error_code ec;
  const auto status = fs::symlink_status(path, ec);
  std::string what = "is not a regular file";
  if (fs::is_symlink(status)) {
    const auto target = fs::read_symlink(path, ec);
    // The link's target is the file system's text: quoted as an excerpt.
    what = fmt::format("is a symbolic link{}",
                       ec ? "" : fmt::format(" (to {})", text::excerpt(target.string())));
  } else if (fs::is_directory(status)) {
    what = "is a folder";
  }
  return LockFileRefused(
      fmt::format("{} {}: a lock file is never opened through a link or in place of something "
                  "else; move it away and start again",
                  path.string(), what));
}

struct LockFile {
  int fd = -1;
  bool created = false;
};

// Opens the lock file without following a link: creates it exclusively when absent, opens an
// existing regular file as it is (never truncated). A file removed between the two attempts is
// created again.
LockFile open_lock_file(const fs::path& path) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int made = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (made >= 0) return {made, true};
    if (errno != EEXIST) throw cannot_make(path, errno);
    // O_NONBLOCK: a pipe of that name must not hang the open; it is refused just below.
    const int fd = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0 && errno == ENOENT) continue;
    if (fd < 0 && (errno == ELOOP || errno == EISDIR || errno == ENXIO)) throw refused(path);
    if (fd < 0) throw cannot_make(path, errno);
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      throw refused(path);
    }
    return {fd, false};
  }
  throw std::runtime_error(
      fmt::format("cannot make the lock file {}: it keeps disappearing", path.string()));
}

// The file's text when it is what a lock writes: nothing, or a process id and a newline. A lock
// may rewrite such a file (one it made, or one a killed process left); anything else, or a file
// with other hard links, is not a lock's and stays as it is.
std::optional<std::string> lock_text(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || st.st_nlink != 1 || st.st_size > 24) return std::nullopt;
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  if (::pread(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
    return std::nullopt;
  }
  if (text.empty()) return text;
  const bool digits = std::all_of(text.begin(), text.end() - 1,
                                  [](unsigned char c) { return std::isdigit(c) != 0; });
  if (text.size() < 2 || text.back() != '\n' || !digits) return std::nullopt;
  return text;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& folder, const std::string& name,
                       const std::string& what) {
  const auto path = folder / name;
  const auto file = open_lock_file(path);
  fd_ = file.fd;
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    auto holder = lock_text(fd_).value_or("");
    if (!holder.empty()) holder.pop_back();
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK) {
      throw FolderBusy(
          fmt::format("{} {} is in use by another process{} (lock {})", what, folder.string(),
                      holder.empty() ? "" : fmt::format(" (pid {})", holder), path.string()));
    }
    throw std::runtime_error(fmt::format("cannot lock {}: {}", path.string(), std::strerror(err)));
  }
  // Say who holds it, for the message of the next one that tries: only in a file of a lock's.
  if (!file.created && !lock_text(fd_)) return;
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (file.created || ::ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const auto n = ::pwrite(fd_, pid.data(), pid.size(), 0);
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace snapjump::io
