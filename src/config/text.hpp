// Small text helpers shared by the readers (case values, units, CSV tables and records).
#pragma once

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

namespace snapjump::text {

// s without the blanks, tabs and carriage returns around it.
inline std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// s in lower case (ASCII letters).
inline std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return out;
}

// The most characters of a file's text that an error message quotes.
inline constexpr std::size_t kMaxExcerpt = 40;

// Text from a file the user named, as an error message may quote it: at most kMaxExcerpt bytes
// ("..." marking a cut), a newline as \n, a tab as \t and every other byte that is not printable
// ASCII as \xNN, so that a message neither echoes a whole file nor sends control sequences to a
// terminal.
std::string excerpt(std::string_view text, std::size_t max_bytes = kMaxExcerpt);

// Whether text holds a byte below 0x20 or 0x7f: a path named in a file must not, as it is quoted
// whole in messages.
inline bool has_control_characters(std::string_view text) {
  return std::any_of(text.begin(), text.end(), [](char c) {
    const auto ch = static_cast<unsigned char>(c);
    return ch < 0x20 || ch == 0x7f;
  });
}

// The most bytes of a message from a library that read a file (toml++, gmsh) that an error
// passes on: such a message may quote the file.
inline constexpr std::size_t kMaxLibraryMessage = 200;

// A library's message about a file, for an error of snapjump's: escaped as text::excerpt does and
// cut to kMaxLibraryMessage bytes.
inline std::string library_message(std::string_view message) {
  return excerpt(message, kMaxLibraryMessage);
}

// A title (or another line of the user's) for the terminal: control characters (below 0x20, and
// 0x7f) as \xNN, newlines as \n; other bytes (UTF-8) kept.
std::string printable_line(std::string_view text);

// The most bytes of a title (a case's, a sweep's, one read back from a run's summary) that is
// kept when it is read: a title is one line of a figure and of the terminal.
inline constexpr std::size_t kMaxTitleBytes = 200;

// title cut to kMaxTitleBytes at a UTF-8 character's boundary, "..." marking the cut.
std::string capped_title(std::string_view title);

}  // namespace snapjump::text
