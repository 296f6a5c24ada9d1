#include "config/text.hpp"

namespace snapjump::text {

std::string capped_title(std::string_view title) {
  if (title.size() <= kMaxTitleBytes) return std::string(title);
  constexpr std::string_view kCut = "...";
  std::size_t end = kMaxTitleBytes - kCut.size();
  // Back to the first byte of a character (continuation bytes are 10xxxxxx).
  while (end > 0 && (static_cast<unsigned char>(title[end]) & 0xC0) == 0x80) --end;
  return std::string(title.substr(0, end)) + std::string(kCut);
}

}  // namespace snapjump::text
