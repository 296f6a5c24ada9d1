// An exclusive lock on a folder for the life of a process (flock on FOLDER/NAME): two sweeps in
// one sweep folder, or two processes on one run folder, would otherwise write the same files at
// once. The lock goes with the process, however it ends (the kernel drops it).
//
// The lock file is never a way to write elsewhere or to damage a file of the user's: a symbolic
// link of that name is refused, never followed; a lock creates its file exclusively (O_EXCL)
// and writes its process id only into a file it created, or into one that holds nothing but
// what a lock writes (empty, or a process id left by a killed run, which is taken over). Any
// other regular file of that name is locked as it is and left unchanged.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "config/input_error.hpp"

namespace snapjump::io {

class FolderBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The lock file's name is taken by something a lock must not open: a symbolic link, a folder,
// a device or a pipe. The user has to move it away.
class LockFileRefused : public InputError {
 public:
  using InputError::InputError;
};

class FolderLock {
 public:
  // Takes the lock or throws FolderBusy naming the folder and the process that holds it (as far
  // as the lock file says), LockFileRefused for a link or other non-file of that name, and
  // std::runtime_error when the lock file cannot be made.
  FolderLock(const std::filesystem::path& folder, const std::string& name, const std::string& what);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace snapjump::io
