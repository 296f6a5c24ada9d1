#include "config/csv.hpp"

#include "config/text.hpp"

namespace snapjump::text {
namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// From position i, the first character that is not a blank, tab or carriage return (or the
// end); a tab that separates cells is not a blank.
std::size_t skip_blanks(std::string_view s, std::size_t i, char separator) {
  const auto blank = [separator](char ch) {
    return ch != separator && (ch == ' ' || ch == '\t' || ch == '\r');
  };
  while (i < s.size() && blank(s[i])) ++i;
  return i;
}

}  // namespace

std::vector<CsvRecord> split_csv(std::string_view text, char separator,
                                 std::optional<CsvProblem>& problem) {
  problem.reset();
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  std::vector<CsvRecord> records;
  std::size_t line = 1, i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    CsvRecord rec;
    rec.line = line;
    if (const auto first = skip_blanks(text, i, separator); first < n && text[first] == '#') {
      while (i < n && text[i] != '\n') ++i;
      if (i < n) ++i;
      ++line;
      continue;
    }
    bool end_of_record = false;
    while (!end_of_record) {
      // One cell, from i.
      std::string cell;
      const auto first = skip_blanks(text, i, separator);
      if (first < n && text[first] == '"') {
        const std::size_t opened_on = line;
        i = first + 1;
        while (true) {
          if (i >= n) {
            problem = CsvProblem{opened_on, "a quoted cell is never closed"};
            return {};
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
          if (text[i] == '\n') ++line;
          cell += text[i++];
        }
        i = skip_blanks(text, i, separator);
        if (i < n && text[i] != separator && text[i] != '\n') {
          problem = CsvProblem{line, "text after the closing quote of a cell"};
          return {};
        }
      } else {
        const auto start = i;
        while (i < n && text[i] != separator && text[i] != '\n') ++i;
        cell = trim(text.substr(start, i - start));
      }
      rec.cells.push_back(std::move(cell));
      if (i >= n) {
        end_of_record = true;
      } else if (text[i] == '\n') {
        ++i;
        ++line;
        end_of_record = true;
      } else {
        ++i;  // the separator: another cell follows, empty at the end of the text
      }
    }
    const bool is_blank = rec.cells.size() == 1 && rec.cells.front().empty();
    if (!is_blank) records.push_back(std::move(rec));
  }
  return records;
}

char detect_separator(std::string_view text) {
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  std::string_view header;
  while (!text.empty()) {
    const auto end = text.find('\n');
    const auto line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    const auto t = trim(line);
    if (!t.empty() && t.front() != '#') {
      header = line;
      break;
    }
  }
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
