// Reading CSV text into records of cells: one set of rules for every table the project reads
// (the figures' tables, sweep tables, time series as simulations write them and as laboratories
// log them). Writing a cell is io::csv_field, whose output these rules read back unchanged.
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace snapjump::text {

struct CsvRecord {
  std::vector<std::string> cells;
  std::size_t line = 0;  // the line it starts on, from 1
};

struct CsvProblem {
  std::size_t line = 0;
  std::string why;
};

// The rules: records end at a line break outside quotes; cells at the separator outside quotes.
// A cell whose first character other than blanks is '"' is quoted: it runs to the next single
// quote and may hold the separator, line breaks and doubled quotes (one quote each); only blanks
// may follow its closing quote. A quoted cell is kept as written, an unquoted one without the
// blanks, tabs and carriage returns around it. A record whose first character other than blanks
// is '#' is a comment, and a blank record is skipped; neither is returned. A UTF-8 byte-order
// mark at the start is dropped. Returns the first problem instead of the records when the text
// breaks the rules (an unclosed quote, text after a closing quote).
std::vector<CsvRecord> split_csv(std::string_view text, char separator,
                                 std::optional<CsvProblem>& problem);

// The same, throwing Error("SOURCE:LINE: why") on a problem.
template <class Error>
std::vector<CsvRecord> split_csv(std::string_view text, char separator, std::string_view source) {
  std::optional<CsvProblem> problem;
  auto records = split_csv(text, separator, problem);
  if (problem) throw Error(fmt::format("{}:{}: {}", source, problem->line, problem->why));
  return records;
}

// The separator that a header line uses: ';' or a tab when it has one of them and no comma
// outside quotes, else ','. Only the first line of `text` that is neither blank nor a comment is
// looked at.
char detect_separator(std::string_view text);

}  // namespace snapjump::text
