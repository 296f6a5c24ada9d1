// Text a damaged or hostile file may hold where a reader quotes it, and the check that an error
// message quotes no more of it than text::excerpt allows.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "config/text.hpp"

namespace snapjump::test_support {

// The letter the hostile text repeats: a message holds at most an excerpt's worth of it.
inline constexpr char kHostileLetter = 'Q';

// An escape sequence that would clear a terminal, 200 of kHostileLetter and a colour sequence.
inline std::string hostile_word() {
  std::string word = "\x1b[2J";
  word.append(200, kHostileLetter);
  return word + "\x1b[31m";
}

// hostile_word() and a line break followed by a forged error line.
inline std::string hostile_text() { return hostile_word() + "\nerror: forged"; }

// hostile_text() in double quotes as a TOML string or key (its escapes written out).
inline std::string hostile_toml_quoted() {
  std::string text = "\"\\u001b[2J";
  text.append(200, kHostileLetter);
  return text + "\\u001b[31m\\nerror: forged\"";
}

// A message that quotes at most text::kMaxExcerpt bytes of hostile_text() (and some of it, when
// `quotes_some`), with no control byte (a line break only between lines of its own) and no
// forged line.
inline ::testing::AssertionResult quotes_only_an_excerpt(const std::string& message,
                                                         bool quotes_some = true) {
  const auto letters = std::count(message.begin(), message.end(), kHostileLetter);
  if (quotes_some && letters == 0) {
    return ::testing::AssertionFailure() << "the message quotes none of the text: " << message;
  }
  if (static_cast<std::size_t>(letters) > text::kMaxExcerpt) {
    return ::testing::AssertionFailure()
           << "the message quotes " << letters << " bytes of the file: " << message;
  }
  const auto control = std::find_if(message.begin(), message.end(), [](char c) {
    const auto ch = static_cast<unsigned char>(c);
    return (ch < 0x20 && ch != '\n') || ch == 0x7f;
  });
  if (control != message.end()) {
    return ::testing::AssertionFailure()
           << "the message holds the control byte " << static_cast<int>(*control) << ": "
           << text::printable_line(message);
  }
  if (message.find("\nerror: forged") != std::string::npos) {
    return ::testing::AssertionFailure() << "the message forges a line: " << message;
  }
  return ::testing::AssertionSuccess();
}

}  // namespace snapjump::test_support
