#include "config/csv.hpp"

#include <algorithm>

#include "config/text.hpp"

namespace snapjump::text {
namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

std::string_view without_byte_order_mark(std::string_view text) {
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  return text;
}

// A line no record starts on: blank, or a comment.
bool skipped_line(std::string_view line) {
  const auto t = trim(line);
  return t.empty() || t.front() == '#';
}

// The line of `text` that starts at i, without its line break.
std::string_view line_at(std::string_view text, std::size_t i) {
  const auto end = text.find('\n', i);
  return text.substr(i, end == std::string_view::npos ? std::string_view::npos : end - i);
}

// From i (the start of a line), the start of the first line a record can start on, or the end of
// the text; `line` counts the lines passed.
std::size_t past_skipped_lines(std::string_view text, std::size_t i, std::size_t& line) {
  while (i < text.size()) {
    const auto l = line_at(text, i);
    if (!skipped_line(l)) break;
    i = std::min(text.size(), i + l.size() + 1);  // and its line break, if it has one
    ++line;
  }
  return i;
}

}  // namespace

CsvReader::CsvReader(std::string_view text, char separator)
    : text_(without_byte_order_mark(text)), separator_(separator) {}

bool CsvReader::next(CsvRecord& record) {
  if (problem_) return false;
  const auto& text = text_;
  const std::size_t n = text.size();
  // Blanks within a line: a tab that separates cells is not one.
  const auto skip_blanks = [&](std::size_t i) {
    while (i < n && text[i] != separator_ && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r'))
      ++i;
    return i;
  };
  i_ = past_skipped_lines(text, i_, line_);
  if (i_ >= n) return false;
  record.cells.clear();
  record.line = line_;
  std::size_t i = i_;
  while (true) {
    // One cell, from i.
    std::string cell;
    const auto first = skip_blanks(i);
    if (first < n && text[first] == '"') {
      const std::size_t opened_on = line_;
      i = first + 1;
      while (true) {
        if (i >= n) {
          problem_ = CsvProblem{opened_on, "a quoted cell is never closed"};
          return false;
        }
        if (text[i] == '"') {
          if (i + 1 < n && text[i + 1] == '"') {
            cell += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        if (text[i] == '\n') ++line_;
        cell += text[i++];
      }
      i = skip_blanks(i);
      if (i < n && text[i] != separator_ && text[i] != '\n') {
        problem_ = CsvProblem{line_, "text after the closing quote of a cell"};
        return false;
      }
    } else {
      const auto start = i;
      while (i < n && text[i] != separator_ && text[i] != '\n') ++i;
      cell = trim(text.substr(start, i - start));
    }
    if (record.cells.size() == kMaxCells) {
      problem_ = CsvProblem{record.line, fmt::format("more than {} cells on one line", kMaxCells)};
      return false;
    }
    record.cells.push_back(std::move(cell));
    if (i >= n) break;
    if (text[i] == '\n') {
      ++i;
      ++line_;
      break;
    }
    ++i;  // the separator: another cell follows, empty at the end of the text
  }
  i_ = i;
  return true;
}

char detect_separator(std::string_view text) {
  text = without_byte_order_mark(text);
  std::size_t lines = 0;
  const auto header = line_at(text, past_skipped_lines(text, 0, lines));
  std::size_t commas = 0, semicolons = 0, tabs = 0;
  bool quoted = false;
  for (const char ch : header) {
    if (ch == '"') quoted = !quoted;
    if (quoted) continue;
    commas += ch == ',';
    semicolons += ch == ';';
    tabs += ch == '\t';
  }
  if (commas == 0 && semicolons > 0) return ';';
  if (commas == 0 && tabs > 0) return '\t';
  return ',';
}

}  // namespace snapjump::text
