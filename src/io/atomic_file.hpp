// Replacing a file so that a crash at any moment leaves either the old contents or the new ones:
// the text goes to PATH.tmp in the same folder, which is then renamed over PATH (an atomic step
// on POSIX file systems). Every file that a run or a sweep rewrites goes through here; the series
// of a resumed run, written row by row, uses the same rename (app/run.cpp).
#pragma once

#include <filesystem>
#include <string_view>

#include "config/files.hpp"

namespace snapjump::io {

// A file that could not be written: "could not write PATH: why" (config/files.hpp).
using WriteFailed = text::WriteFailed;

// Throws WriteFailed naming the file when it cannot be written or renamed; PATH.tmp is removed
// then, and PATH keeps what it held.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents,
                           bool binary = false);

}  // namespace snapjump::io
