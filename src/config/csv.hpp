// Reading CSV text into records of cells: one set of rules for every table the project reads
// (the figures' tables, sweep tables, time series as simulations write them and as laboratories
// log them). io::csv_field writes cells that these rules read back, except that a cell is read
// without the blanks around it unless quoted, and a line break written into a cell comes back as
// the space csv_field made of it.
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
// A line that is blank (spaces, tabs, a carriage return) or whose first other character is '#' is
// skipped where a record would start. A cell whose first character other than blanks is '"' is
// quoted: it runs to the next single quote and may hold the separator, line breaks and doubled
// quotes (one quote each); only blanks may follow its closing quote. A quoted cell is kept as
// written, an unquoted one without the spaces, tabs and carriage returns around it. A UTF-8
// byte-order mark at the start is dropped.
//
// Records are read one at a time (a long laboratory log is never held as cells all at once). A
// record of more than kMaxCells cells breaks the rules: no table the project reads has that many
// columns, and a line of separators alone would otherwise cost a string per cell.
inline constexpr std::size_t kMaxCells = 1000;

class CsvReader {
 public:
  CsvReader(std::string_view text, char separator);

  // The next record into `record`; false at the end of the text, or at a break of the rules,
  // which problem() then describes (and every later call returns false).
  bool next(CsvRecord& record);
  [[nodiscard]] const std::optional<CsvProblem>& problem() const { return problem_; }

  // next(), throwing Error("SOURCE:LINE: why") at a break of the rules.
  template <class Error>
  bool next(CsvRecord& record, std::string_view source) {
    if (next(record)) return true;
    if (problem_) throw Error(fmt::format("{}:{}: {}", source, problem_->line, problem_->why));
    return false;
  }

 private:
  std::string_view text_;
  char separator_;
  std::size_t i_ = 0, line_ = 1;
  std::optional<CsvProblem> problem_;
};

// Every record of the text; throws Error("SOURCE:LINE: why") at a break of the rules.
template <class Error>
std::vector<CsvRecord> split_csv(std::string_view text, char separator, std::string_view source) {
  CsvReader reader(text, separator);
  std::vector<CsvRecord> records;
  CsvRecord record;
  while (reader.next<Error>(record, source)) records.push_back(std::move(record));
  return records;
}

// The separator that a header line uses: ';' or a tab when it has one of them and no comma
// outside quotes, else ','. Only the first line of `text` that a record could start on (neither
// blank nor a comment) is looked at.
char detect_separator(std::string_view text);

}  // namespace snapjump::text
