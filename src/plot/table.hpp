// A CSV table read by column name, for the figures: a sweep's combined table (one row per run,
// "name [unit]" headers, SI values, empty cells for missing values, "quoted, fields") or the
// contact solver's branch curves.
#pragma once

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace snapjump::plot {

class Table {
 public:
  // Reads a CSV file. The first line that is neither blank nor a '#' comment is the header; each
  // header cell is "name" or "name [unit]". Fields may be quoted ("a, b", "say ""x"""). Throws
  // PlotInputError naming the file (and line) when it cannot be read, has no header or has a row
  // with more cells than the header. Rows with fewer cells are padded with empty cells. A name
  // that appears twice refers to its last column.
  static Table read_csv_file(const std::filesystem::path& path);
  // The same from a stream; `source` names it in messages.
  static Table read_csv(std::istream& in, std::string_view source);
  // The same from CSV text (the rules of text::split_csv, comma-separated).
  static Table read_csv(std::string_view csv, std::string_view source);

  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] std::size_t rows() const { return cells_.size(); }
  [[nodiscard]] bool empty() const { return cells_.empty(); }
  // Column names (the header text before " ["), in file order.
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] bool has(std::string_view name) const { return index(name).has_value(); }
  [[nodiscard]] std::optional<std::size_t> index(std::string_view name) const;
  // The unit written in the header ("m" for "R [m]"), empty when none.
  [[nodiscard]] const std::string& unit(std::string_view name) const;

  // The cell as text (unquoted, blanks around it removed). Throws PlotInputError naming the file
  // and the column when the column is missing.
  [[nodiscard]] const std::string& text(std::size_t row, std::string_view name) const;
  // The cell as a number; nothing when it is empty or not finite. Throws PlotInputError naming
  // the file, line and column when the column is missing or the cell is not a number.
  [[nodiscard]] std::optional<double> number(std::size_t row, std::string_view name) const;
  // A whole column of numbers, as number().
  [[nodiscard]] std::vector<std::optional<double>> numbers(std::string_view name) const;

  // Throws PlotInputError naming the file and every missing column of `names`, if any.
  void require(std::initializer_list<std::string_view> names) const;

 private:
  [[nodiscard]] std::size_t column(std::string_view name) const;

  std::string source_;
  std::vector<std::string> names_;
  std::vector<std::string> units_;
  std::vector<std::vector<std::string>> cells_;
  std::vector<std::size_t> lines_;  // line of each row in the file, for messages
};

}  // namespace snapjump::plot
