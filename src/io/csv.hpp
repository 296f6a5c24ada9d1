// Writing a CSV cell so that any text (a run's status, an error message, a file name) stays one
// cell on one line.
#pragma once

#include <string>
#include <string_view>

namespace snapjump::io {

// The text as it is when it holds no comma, quote or line break; otherwise in double quotes,
// quotes doubled and line breaks turned into spaces.
inline std::string csv_field(std::string_view s) {
  if (s.find_first_of(",\"\n") == std::string_view::npos) return std::string(s);
  std::string q = "\"";
  for (const char ch : s) {
    if (ch == '"') q += '"';
    q += ch == '\n' ? ' ' : ch;
  }
  q += '"';
  return q;
}

}  // namespace snapjump::io
