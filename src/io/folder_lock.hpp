// An exclusive lock on a folder for the life of a process (flock on FOLDER/NAME): two sweeps in
// one sweep folder, or two processes on one run folder, would otherwise write the same files at
// once. The lock goes with the process, however it ends (the kernel drops it).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace snapjump::io {

class FolderBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FolderLock {
 public:
  // Takes the lock or throws FolderBusy naming the folder and the process that holds it (as far
  // as the lock file says); std::runtime_error when the lock file cannot be made.
  FolderLock(const std::filesystem::path& folder, const std::string& name, const std::string& what);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace snapjump::io
