#include "measure/time_series.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <istream>
#include <iterator>
#include <ostream>
#include <system_error>
#include <utility>

#include "config/files.hpp"
#include "config/text.hpp"

namespace snapjump::measure {
namespace {

struct KnownColumn {
  std::string_view name;
  units::Dimension dimension;
};

constexpr std::array kKnownColumns{
    KnownColumn{kTime, units::Dimension::Time},
    KnownColumn{kForce, units::Dimension::Force},
    KnownColumn{kHeight, units::Dimension::Length},
    KnownColumn{kContactRadius, units::Dimension::Length},
    KnownColumn{kApexGap, units::Dimension::Length},
    KnownColumn{kIndentation, units::Dimension::Length},
    KnownColumn{kApexDisplacement, units::Dimension::Length},
    KnownColumn{kPressure, units::Dimension::Pressure},
};

using text::trim;

// Checks a column list; returns the index of "t". `where` prefixes messages.
std::size_t check_columns(const std::vector<std::string>& names, std::string_view where) {
  std::optional<std::size_t> time_index;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto& n = names[i];
    if (trim(n).empty() || trim(n) != n || n.find_first_of(",\n\"") != std::string::npos) {
      throw SeriesError(fmt::format(
          "{}: column {} name '{}' is empty or has blanks around it, a comma, a quote or a newline",
          where, i + 1, n));
    }
    if (const auto open = n.find('['); open != std::string::npos) {
      // "T [degC]" is a kept unknown column; "z [mm]" would read back as z in mm.
      const auto base = trim(std::string_view(n).substr(0, open));
      if (column_dimension(base) || base == kContact) {
        throw SeriesError(fmt::format(
            "{}: column {} name '{}': the columns hold SI values, so '{}' takes no unit", where,
            i + 1, n, base));
      }
    }
    if (n == kContact) {
      throw SeriesError(fmt::format(
          "{}: 'contact' is not a numeric column; ask for the contact column separately", where));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (names[j] == n) {
        throw SeriesError(fmt::format("{}: column '{}' appears twice (columns {} and {})", where, n,
                                      j + 1, i + 1));
      }
    }
    if (n == kTime) time_index = i;
  }
  if (!time_index) {
    throw SeriesError(fmt::format("{}: there is no time column 't'", where));
  }
  return *time_index;
}

// The row checks shared by TimeSeries::add_row and CsvWriter::write_row.
void check_row(std::span<const double> values, std::size_t ncolumns, std::size_t time_index,
               bool with_contact, std::optional<ContactState> contact,
               std::optional<double> last_time, std::string_view where) {
  if (values.size() != ncolumns) {
    throw SeriesError(fmt::format("{}: a row has {} values, but there are {} numeric columns",
                                  where, values.size(), ncolumns));
  }
  if (with_contact && !contact) {
    throw SeriesError(
        fmt::format("{}: a row needs a contact state (the series has a contact column)", where));
  }
  if (!with_contact && contact) {
    throw SeriesError(
        fmt::format("{}: a row has a contact state, but the series has no contact column", where));
  }
  const double t = values[time_index];
  if (!std::isfinite(t)) {
    throw SeriesError(fmt::format("{}: time {} is not a finite number", where, t));
  }
  if (last_time && !(t > *last_time)) {
    throw SeriesError(
        fmt::format("{}: time {} s is not after the previous row's {} s", where, t, *last_time));
  }
}

std::string header_line(const std::vector<std::string>& names, bool with_contact) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) s += ',';
    s += names[i];
  }
  if (with_contact) {
    s += ',';
    s += kContact;
  }
  s += '\n';
  return s;
}

// fmt's "{}" for a double is the shortest text that reads back to the same double.
void append_row(fmt::memory_buffer& buf, std::span<const double> values,
                std::optional<ContactState> contact) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) buf.push_back(',');
    fmt::format_to(std::back_inserter(buf), "{}", values[i]);
  }
  if (contact) {
    buf.push_back(',');
    const auto text = to_string(*contact);
    buf.append(text.data(), text.data() + text.size());
  }
  buf.push_back('\n');
}

}  // namespace

std::string_view to_string(ContactState s) {
  switch (s) {
    case ContactState::None:
      return "none";
    case ContactState::Ring:
      return "ring";
    case ContactState::Disk:
      return "disk";
  }
  return "none";
}

std::optional<ContactState> parse_contact_state(std::string_view text) {
  const auto lower = text::lower(trim(text));
  for (const auto state : {ContactState::None, ContactState::Ring, ContactState::Disk}) {
    if (lower == to_string(state)) return state;
  }
  return std::nullopt;
}

std::optional<units::Dimension> column_dimension(std::string_view name) {
  for (const auto& k : kKnownColumns) {
    if (k.name == name) return k.dimension;
  }
  return std::nullopt;
}

// --- TimeSeries ------------------------------------------------------------------------------

TimeSeries::TimeSeries(std::vector<std::string> columns, bool with_contact)
    : names_(std::move(columns)), with_contact_(with_contact) {
  time_index_ = check_columns(names_, "time series");
  data_.resize(names_.size());
}

std::optional<std::size_t> TimeSeries::index(std::string_view name) const {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == name) return i;
  }
  return std::nullopt;
}

std::span<const double> TimeSeries::column(std::string_view name) const {
  const auto i = index(name);
  if (!i) {
    throw SeriesError(fmt::format("the time series has no column '{}' (it has: {})", name,
                                  fmt::join(names_, ", ")));
  }
  return data_[*i];
}

double TimeSeries::sample_interval(std::string_view column) const {
  for (const auto& [name, dt] : own_intervals_) {
    if (name == column) return dt;
  }
  const auto t = time();
  if (t.size() < 2) return 0.0;
  std::vector<double> d(t.size() - 1);
  for (std::size_t i = 1; i < t.size(); ++i) d[i - 1] = t[i] - t[i - 1];
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

void TimeSeries::add_to_column(std::string_view name, double offset) {
  const auto i = index(name);
  if (!i) throw SeriesError(fmt::format("the time series has no column '{}'", name));
  if (*i == time_index_) throw SeriesError("the time column cannot be shifted");
  for (auto& v : data_[*i]) v += offset;
}

void TimeSeries::reserve(std::size_t rows) {
  for (auto& d : data_) d.reserve(rows);
  if (with_contact_) contact_.reserve(rows);
}

void TimeSeries::add_row(std::span<const double> values) { append(values, std::nullopt); }

void TimeSeries::add_row(std::span<const double> values, ContactState contact) {
  append(values, contact);
}

void TimeSeries::append(std::span<const double> values, std::optional<ContactState> contact) {
  const auto& t = data_[time_index_];
  check_row(values, names_.size(), time_index_, with_contact_, contact,
            t.empty() ? std::nullopt : std::optional<double>(t.back()), "time series");
  for (std::size_t i = 0; i < values.size(); ++i) data_[i].push_back(values[i]);
  if (contact) contact_.push_back(*contact);
}

void TimeSeries::write_csv(std::ostream& out) const {
  out << header_line(names_, with_contact_);
  fmt::memory_buffer buf;
  std::vector<double> row(names_.size());
  for (std::size_t r = 0; r < size(); ++r) {
    for (std::size_t i = 0; i < names_.size(); ++i) row[i] = data_[i][r];
    append_row(buf, row, with_contact_ ? std::optional(contact_[r]) : std::nullopt);
    if (buf.size() > 1 << 16) {
      out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
      buf.clear();
    }
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
}

// --- CsvWriter -------------------------------------------------------------------------------

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                     bool with_contact)
    : file_(std::make_unique<std::ofstream>(path, std::ios::out | std::ios::trunc)),
      out_(file_.get()),
      where_(path.string()),
      names_(std::move(columns)),
      with_contact_(with_contact) {
  time_index_ = check_columns(names_, where_);
  if (!*file_)
    throw text::WriteFailed(path, fmt::format("cannot create it: {}", std::strerror(errno)));
  put(header_line(names_, with_contact_));
}

CsvWriter::CsvWriter(std::ostream& out, std::vector<std::string> columns, bool with_contact)
    : out_(&out), where_("CSV stream"), names_(std::move(columns)), with_contact_(with_contact) {
  time_index_ = check_columns(names_, where_);
  put(header_line(names_, with_contact_));
}

CsvWriter::~CsvWriter() = default;
CsvWriter::CsvWriter(CsvWriter&&) noexcept = default;
CsvWriter& CsvWriter::operator=(CsvWriter&&) noexcept = default;

void CsvWriter::write_row(std::span<const double> values) { write(values, std::nullopt); }

void CsvWriter::write_row(std::span<const double> values, ContactState contact) {
  write(values, contact);
}

void CsvWriter::write(std::span<const double> values, std::optional<ContactState> contact) {
  check_row(values, names_.size(), time_index_, with_contact_, contact, last_time_, where_);
  fmt::memory_buffer buf;
  append_row(buf, values, contact);
  put(std::string_view(buf.data(), buf.size()));
  last_time_ = values[time_index_];
  ++rows_;
}

void CsvWriter::write_comment(std::string_view text) {
  std::string s;
  std::size_t start = 0;
  while (start <= text.size()) {
    auto end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    s += "# ";
    s += text.substr(start, end - start);
    s += '\n';
    start = end + 1;
  }
  put(s);
}

void CsvWriter::put(std::string_view text) {
  errno = 0;
  out_->write(text.data(), static_cast<std::streamsize>(text.size()));
  out_->flush();
  if (*out_) return;
  // A file of its own that cannot be written (a full disk) is a write failure, not bad data.
  const auto why =
      fmt::format("{} after {} rows", errno != 0 ? std::strerror(errno) : "an output error", rows_);
  if (file_) throw text::WriteFailed(where_, why);
  throw SeriesError(fmt::format("{}: write failed: {}", where_, why));
}

}  // namespace snapjump::measure
