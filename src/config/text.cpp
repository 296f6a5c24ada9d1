#include "config/text.hpp"

#include <fmt/format.h>

namespace snapjump::text {

namespace {

// One byte as it is shown: itself when `keep` says so, else an escape.
void append_shown(std::string& out, unsigned char ch, bool keep) {
  if (ch == '\n') {
    out += "\\n";
  } else if (ch == '\t') {
    out += "\\t";
  } else if (keep) {
    out += static_cast<char>(ch);
  } else {
    out += fmt::format("\\x{:02X}", ch);
  }
}

}  // namespace

std::string excerpt(std::string_view text, std::size_t max_bytes) {
  std::string out;
  const bool cut = text.size() > max_bytes;
  for (const char c : text.substr(0, max_bytes)) {
    const auto ch = static_cast<unsigned char>(c);
    append_shown(out, ch, ch >= 0x20 && ch < 0x7f);
  }
  if (cut) out += "...";
  return out;
}

std::string printable_line(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const auto ch = static_cast<unsigned char>(c);
    append_shown(out, ch, ch >= 0x20 && ch != 0x7f);
  }
  return out;
}

std::string capped_title(std::string_view title) {
  if (title.size() <= kMaxTitleBytes) return std::string(title);
  constexpr std::string_view kCut = "...";
  std::size_t end = kMaxTitleBytes - kCut.size();
  // Back to the first byte of a character (continuation bytes are 10xxxxxx).
  while (end > 0 && (static_cast<unsigned char>(title[end]) & 0xC0) == 0x80) --end;
  return std::string(title.substr(0, end)) + std::string(kCut);
}

}  // namespace snapjump::text
