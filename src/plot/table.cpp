#include "plot/table.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <iterator>

#include "config/csv.hpp"
#include "config/files.hpp"
#include "config/text.hpp"
#include "plot/gnuplot.hpp"

namespace snapjump::plot {
namespace {

std::string trim(std::string_view s) { return std::string(text::trim(s)); }

}  // namespace

Table Table::read_csv_file(const std::filesystem::path& path) {
  return read_csv(text::read_file<PlotInputError>(path, "a CSV table"), path.string());
}

Table Table::read_csv(std::istream& in, std::string_view source) {
  return read_csv(std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()},
                  source);
}

Table Table::read_csv(std::string_view csv, std::string_view source) {
  auto records = text::split_csv<PlotInputError>(csv, ',', source);
  Table t;
  t.source_ = std::string(source);
  if (records.empty())
    throw PlotInputError(fmt::format("{}: empty table (no header line)", source));
  const auto& header = records.front();
  for (std::size_t k = 0; k < header.cells.size(); ++k) {
    const auto& h = header.cells[k];
    std::string name = h;
    std::string unit;
    if (const auto open = h.find('['); open != std::string::npos) {
      const auto close = h.find(']', open);
      name = trim(std::string_view(h).substr(0, open));
      unit = trim(std::string_view(h).substr(
          open + 1, (close == std::string::npos ? h.size() : close) - open - 1));
    }
    if (name.empty()) {
      throw PlotInputError(
          fmt::format("{}:{}: header column {} has no name", source, header.line, k + 1));
    }
    t.names_.push_back(std::move(name));
    t.units_.push_back(std::move(unit));
  }
  for (std::size_t r = 1; r < records.size(); ++r) {
    auto& rec = records[r];
    if (rec.cells.size() > t.names_.size()) {
      throw PlotInputError(fmt::format("{}:{}: the row has {} cells, the header {} columns", source,
                                       rec.line, rec.cells.size(), t.names_.size()));
    }
    rec.cells.resize(t.names_.size());
    t.cells_.push_back(std::move(rec.cells));
    t.lines_.push_back(rec.line);
  }
  return t;
}

std::optional<std::size_t> Table::index(std::string_view name) const {
  // The last column of that name: a sweep's varied keys come before its fixed columns.
  for (std::size_t i = names_.size(); i-- > 0;) {
    if (names_[i] == name) return i;
  }
  return std::nullopt;
}

std::size_t Table::column(std::string_view name) const {
  if (const auto i = index(name)) return *i;
  throw PlotInputError(fmt::format("{}: no column '{}' in the header", source_, name));
}

const std::string& Table::unit(std::string_view name) const { return units_[column(name)]; }

void Table::require(std::initializer_list<std::string_view> names) const {
  std::string missing;
  std::size_t count = 0;
  for (const auto name : names) {
    if (has(name)) continue;
    if (!missing.empty()) missing += ", ";
    missing += fmt::format("'{}'", name);
    ++count;
  }
  if (count > 0) {
    throw PlotInputError(
        fmt::format("{}: no column{} {} in the header", source_, count > 1 ? "s" : "", missing));
  }
}

const std::string& Table::text(std::size_t row, std::string_view name) const {
  return cells_.at(row)[column(name)];
}

std::optional<double> Table::number(std::size_t row, std::string_view name) const {
  const auto& cell = text(row, name);
  if (cell.empty()) return std::nullopt;
  std::string_view s = cell;
  if (s.front() == '+') s.remove_prefix(1);
  const auto lower = text::lower(s);
  if (lower == "nan" || lower == "-nan" || lower == "inf" || lower == "-inf") return std::nullopt;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) {
    throw PlotInputError(fmt::format("{}:{}: column '{}': '{}' is not a number", source_,
                                     lines_.at(row), name, text::excerpt(cell)));
  }
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

std::vector<std::optional<double>> Table::numbers(std::string_view name) const {
  std::vector<std::optional<double>> v;
  v.reserve(rows());
  for (std::size_t r = 0; r < rows(); ++r) v.push_back(number(r, name));
  return v;
}

}  // namespace snapjump::plot
