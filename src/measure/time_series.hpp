// A time series of a popper run: named columns of doubles (SI) plus an optional contact-state
// column, read from and written to CSV. The same type holds a simulated run and a measured
// force-plate record, so that one analysis (measure/analysis.hpp) serves both.
//
// CSV format (docs/analysis.md): one header line of comma-separated names, each with an optional
// unit in brackets ("t [ms]"); '#' lines and blank lines are comments. Known columns are converted
// to SI on reading; other columns are kept as plain numbers. Writing is always SI, plain names.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config/input_error.hpp"
#include "config/units.hpp"

namespace snapjump::measure {

// Bad series input or use. what() names the file, line and column where there is one.
class SeriesError : public InputError {
 public:
  using InputError::InputError;
};

// What touches the plate: nothing, a ring (the inverted shell's rim of contact), or a disk.
enum class ContactState { None, Ring, Disk };
std::string_view to_string(ContactState s);  // "none", "ring", "disk"
// "none" / "ring" / "disk", case-insensitive, surrounding blanks ignored.
std::optional<ContactState> parse_contact_state(std::string_view text);

// The column names with a known meaning and dimension. Any other name is allowed and kept as a
// plain number.
inline constexpr std::string_view kTime = "t";           // time [s], required, increasing
inline constexpr std::string_view kForce = "F";          // plate reaction, up on the popper [N]
inline constexpr std::string_view kHeight = "z";         // container above its t = 0 place [m]
inline constexpr std::string_view kContactRadius = "r";  // [m]
inline constexpr std::string_view kApexGap = "w";        // outer apex above the plate [m]
// Indentation: the plate's displacement into the undeformed shell (the rim's approach) [m].
inline constexpr std::string_view kIndentation = "e";
inline constexpr std::string_view kApexDisplacement = "e_apex";  // apex relative to the rim [m]
inline constexpr std::string_view kPressure = "delta_p";         // pressure difference [Pa]
inline constexpr std::string_view kContact = "contact";          // text: none / ring / disk

// The dimension of a known numeric column, or nothing for "contact" and unknown names.
std::optional<units::Dimension> column_dimension(std::string_view name);

// How to read a record that does not follow the project's own spelling (docs/analysis.md).
struct ReadOptions {
  // Which header names which column: {"t", "Time (s)"} reads the column headed "Time (s)" as t.
  std::vector<std::pair<std::string, std::string>> columns;
  // Units for columns whose header gives none: {"F", "mN"}.
  std::vector<std::pair<std::string, std::string>> units;
};

// A stretch where one column has no samples (a sensor's dropout), interpolated across.
struct Gap {
  std::string column;
  double from = 0.0;  // last sample before [s]
  double to = 0.0;    // first sample after [s]
};

class TimeSeries {
 public:
  // An empty series with these numeric columns (in this order; one must be "t"; no duplicates,
  // no empty names, not "contact") and, if with_contact, a contact-state column. Throws
  // SeriesError.
  explicit TimeSeries(std::vector<std::string> columns, bool with_contact = false);

  [[nodiscard]] const std::vector<std::string>& columns() const { return names_; }
  [[nodiscard]] bool has_contact() const { return with_contact_; }
  [[nodiscard]] std::size_t size() const { return time().size(); }
  [[nodiscard]] bool empty() const { return size() == 0; }

  [[nodiscard]] bool has(std::string_view name) const { return index(name).has_value(); }
  [[nodiscard]] std::optional<std::size_t> index(std::string_view name) const;
  // A numeric column's values. Throws SeriesError naming the missing column.
  [[nodiscard]] std::span<const double> column(std::string_view name) const;
  [[nodiscard]] std::span<const double> column(std::size_t i) const { return data_.at(i); }
  [[nodiscard]] std::span<const double> time() const { return data_[time_index_]; }
  // One state per row; empty when there is no contact column.
  [[nodiscard]] std::span<const ContactState> contact() const { return contact_; }

  void reserve(std::size_t rows);
  // Adds `offset` to every value of a numeric column (a force plate's tare put back). Throws
  // SeriesError naming a missing column, or for the time column.
  void add_to_column(std::string_view name, double offset);
  // Appends one row: one value per numeric column, in the order of columns(); the contact state
  // when the series has a contact column (and only then). Throws SeriesError on a wrong number of
  // values, a missing or unexpected contact state, or a time that is not finite or not after the
  // previous row's.
  void add_row(std::span<const double> values);
  void add_row(std::span<const double> values, ContactState contact);
  void add_row(std::initializer_list<double> values) {
    add_row(std::span<const double>(values.begin(), values.size()));
  }
  void add_row(std::initializer_list<double> values, ContactState contact) {
    add_row(std::span<const double>(values.begin(), values.size()), contact);
  }

  // The whole series as CSV: SI values, plain names, the contact column last. Values are written
  // in the shortest form that reads back to the same double, so a round trip is exact.
  void write_csv(std::ostream& out) const;

  // Reads CSV text; `source` names it in messages (a file name). Throws SeriesError.
  // (src/measure/record_reader.cpp)
  static TimeSeries read_csv(std::istream& in, std::string_view source,
                             const units::UnitParser& parser, const ReadOptions& options = {});
  // The same from the text itself (the rules of text::split_csv; the separator is the header
  // line's: ',' or else ';' or a tab, with decimal commas).
  static TimeSeries read_csv(std::string_view csv, std::string_view source,
                             const units::UnitParser& parser, const ReadOptions& options = {});
  // Reads a CSV file; makes its own UnitParser when none is given. Throws SeriesError.
  static TimeSeries read_csv_file(const std::filesystem::path& path,
                                  const units::UnitParser* parser = nullptr,
                                  const ReadOptions& options = {});

  // What reading did to the record (rows sorted, columns resampled, cut or left out), in words.
  [[nodiscard]] const std::vector<std::string>& notes() const { return notes_; }
  // The stretches where a column had no samples (interpolated across).
  [[nodiscard]] const std::vector<Gap>& gaps() const { return gaps_; }
  // How far apart a column's own samples lie [s]: the median interval of the rows that had a
  // value of it in the file read (its sensor's rate, before any resampling onto the force's
  // clock), else the median interval of the series' times; "contact" for the contact column. 0
  // for fewer than two rows.
  [[nodiscard]] double sample_interval(std::string_view column) const;

 private:
  void append(std::span<const double> values, std::optional<ContactState> contact);

  std::vector<std::string> names_;
  std::vector<std::vector<double>> data_;  // one vector per column
  std::vector<ContactState> contact_;
  std::size_t time_index_ = 0;
  bool with_contact_ = false;
  std::vector<std::string> notes_;
  std::vector<Gap> gaps_;
  std::vector<std::pair<std::string, double>> own_intervals_;  // set by the reader
};

// Appends rows to a CSV file (or stream) as they come and flushes after each, so that a run that
// stops midway leaves every row it produced. Same format as TimeSeries::write_csv.
class CsvWriter {
 public:
  // Creates (truncates) the file and writes the header. Throws text::WriteFailed naming the file
  // if it cannot.
  CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
            bool with_contact = false);
  // Writes to a stream the caller keeps alive.
  CsvWriter(std::ostream& out, std::vector<std::string> columns, bool with_contact = false);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  CsvWriter(CsvWriter&&) noexcept;
  CsvWriter& operator=(CsvWriter&&) noexcept;

  // Same checks as TimeSeries::add_row, which throw SeriesError; a write to the writer's own file
  // that fails throws text::WriteFailed (SeriesError for a caller's stream).
  void write_row(std::span<const double> values);
  void write_row(std::span<const double> values, ContactState contact);
  // A '#' comment line (e.g. the case it came from); newlines in text become separate comments.
  void write_comment(std::string_view text);

  [[nodiscard]] std::size_t rows() const { return rows_; }
  [[nodiscard]] const std::vector<std::string>& columns() const { return names_; }

 private:
  void write(std::span<const double> values, std::optional<ContactState> contact);
  void put(std::string_view text);

  std::unique_ptr<std::ofstream> file_;  // when the writer owns the file
  std::ostream* out_ = nullptr;
  std::string where_;  // the file name, or "stream", for messages
  std::vector<std::string> names_;
  std::size_t time_index_ = 0;
  bool with_contact_ = false;
  std::size_t rows_ = 0;
  std::optional<double> last_time_;
};

}  // namespace snapjump::measure
