// Reading a time series from CSV text, as simulations write it and as laboratories log it:
// separators, quotes, header spellings, a column mapping, units by option, several sensors on
// their own clocks in one merged file (empty or NaN cells), rows out of order. Rules:
// docs/analysis.md "Records as laboratories log them".
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <istream>
#include <iterator>
#include <map>
#include <numeric>
#include <system_error>
#include <utility>

#include "config/csv.hpp"
#include "config/files.hpp"
#include "config/text.hpp"
#include "measure/time_series.hpp"

namespace snapjump::measure {
namespace {

using text::lower;
using text::trim;

// A missing value: an empty cell or a spelling of NaN.
bool is_missing(std::string_view cell) {
  const auto s = lower(trim(cell));
  return s.empty() || s == "nan" || s == "-nan" || s == "na" || s == "n/a" || s == "null";
}

std::optional<double> parse_number(std::string_view cell, bool decimal_comma) {
  std::string s(trim(cell));
  if (decimal_comma && s.find('.') == std::string::npos) {
    std::replace(s.begin(), s.end(), ',', '.');
  }
  std::string_view v = s;
  if (!v.empty() && v.front() == '+') v.remove_prefix(1);
  if (v.empty()) return std::nullopt;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
  if (ec != std::errc() || ptr != v.data() + v.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Spellings of the known columns that instruments and spreadsheets use (compared in lower
// case); the one-letter names themselves are case-sensitive ("T" may be a temperature).
struct Alias {
  std::string_view spelling;
  std::string_view name;
};
constexpr std::array kAliases{
    Alias{"time", kTime},
    Alias{"force", kForce},
    Alias{"fz", kForce},
    Alias{"height", kHeight},
    Alias{"dp", kPressure},
    Alias{"delta p", kPressure},
    Alias{"contact state", kContact},
};

std::optional<std::string> canonical(std::string_view name) {
  if (column_dimension(name) || name == kContact) return std::string(name);
  const auto l = lower(name);
  for (const auto& a : kAliases) {
    if (l == a.spelling) return std::string(a.name);
  }
  return std::nullopt;
}

// "Unnamed: 0": the header pandas writes over a DataFrame's index.
bool is_pandas_index(std::string_view text) {
  if (!text.starts_with("Unnamed:")) return false;
  const auto rest = trim(text.substr(8));
  return !rest.empty() &&
         std::all_of(rest.begin(), rest.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

// One header cell: the column's name, its unit and the factor to SI.
struct HeaderColumn {
  std::string text;  // as written, quotes removed, trimmed
  std::string name;  // what the series calls it; empty for a skipped column
  double to_si = 1.0;
  bool is_contact = false;
};

// "t_ms", "F_N", "z_mm": a known name, an underscore and a unit of the right dimension; the
// name and the unit, or nothing.
std::optional<std::pair<std::string, std::string>> with_unit_suffix(
    std::string_view name, const units::UnitParser& parser) {
  const auto us = name.rfind('_');
  if (us == std::string_view::npos || us == 0) return std::nullopt;
  const auto base = canonical(name.substr(0, us));
  const auto dim = base ? column_dimension(*base) : std::nullopt;
  if (!dim) return std::nullopt;
  try {
    (void)parser.to_si(1.0, name.substr(us + 1), *dim);
  } catch (const units::UnitError&) {
    return std::nullopt;  // not a unit: an unknown column
  }
  return std::pair{*base, std::string(name.substr(us + 1))};
}

HeaderColumn parse_header_cell(std::string_view cell, std::string_view at, std::size_t k,
                               const units::UnitParser& parser, const ReadOptions& options) {
  HeaderColumn c;
  c.text = std::string(trim(cell));
  const auto fail = [&](std::string_view why) {
    return SeriesError(fmt::format("{}: column {} '{}': {}", at, k, text::excerpt(c.text), why));
  };
  if (c.text.empty() || is_pandas_index(c.text)) {
    return c;  // an index column (pandas) or a trailing separator: skipped
  }
  std::string_view name = c.text;
  std::optional<std::string> unit;
  std::optional<std::string> mapped;
  for (const auto& [to, from] : options.columns) {
    if (trim(from) == c.text) mapped = to;
  }
  // "name [unit]" or "name (unit)".
  for (const auto& [open_ch, close_ch] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    const auto open = c.text.find(open_ch);
    const auto close = c.text.rfind(close_ch);
    if (open == std::string::npos && close == std::string::npos) continue;
    const bool malformed = open == std::string::npos || close == std::string::npos ||
                           close < open ||
                           !trim(std::string_view(c.text).substr(close + 1)).empty();
    if (malformed && !mapped &&
        !canonical(trim(std::string_view(c.text).substr(0, std::min(open, close))))) {
      break;  // not a column the analysis reads: kept as written
    }
    if (open == std::string::npos || close == std::string::npos || close < open) {
      throw fail(
          fmt::format("unbalanced brackets; write the unit as \"name {}unit{}\", e.g. \"t {}ms{}\"",
                      open_ch, close_ch, open_ch, close_ch));
    }
    if (!trim(std::string_view(c.text).substr(close + 1)).empty()) {
      throw fail(fmt::format("text after the '{}'; write the unit as \"name {}unit{}\"", close_ch,
                             open_ch, close_ch));
    }
    name = trim(std::string_view(c.text).substr(0, open));
    unit = std::string(trim(std::string_view(c.text).substr(open + 1, close - open - 1)));
    break;
  }
  if (name.empty()) throw fail("the column has no name");
  if (mapped) {
    const auto standard = canonical(*mapped);
    if (!standard) {
      throw fail(fmt::format(
          "the column mapping names '{}', which is not a column the analysis knows (t, F, z, r, "
          "w, e, e_apex, delta_p, contact)",
          *mapped));
    }
    mapped = standard;
  }
  std::optional<std::string> known = mapped ? mapped : canonical(name);
  if (!known && !unit) {
    if (auto split = with_unit_suffix(name, parser)) {
      known = std::move(split->first);
      unit = std::move(split->second);
    }
  }
  if (!known) {
    // Not a known quantity: kept as written (unit and all), values unconverted.
    c.name = c.text;
    std::replace_if(
        c.name.begin(), c.name.end(), [](char ch) { return ch == ',' || ch == '"'; }, ' ');
    return c;
  }
  c.name = *known;
  if (c.name == kContact) {
    if (unit && !unit->empty()) throw fail("the contact column holds text and takes no unit");
    c.is_contact = true;
    return c;
  }
  for (const auto& [col, u] : options.units) {
    if (col != c.name) continue;
    if (unit && trim(*unit) != trim(u)) {
      throw fail(fmt::format("the header gives the unit '{}' and the options '{}': give one",
                             text::excerpt(*unit), text::excerpt(u)));
    }
    unit = u;
  }
  const auto dim = *column_dimension(c.name);
  if (unit) {
    try {
      c.to_si = parser.to_si(1.0, *unit, dim);
    } catch (const units::UnitError& e) {
      throw fail(fmt::format("{} (column '{}' is a {} in {})", e.what(), c.name,
                             units::dimension_name(dim), units::si_unit(dim)));
    }
  }
  return c;
}

// One row as read: the time, a value or nothing per numeric column, the contact state or
// nothing, and the line it came from.
struct RawRow {
  double t = 0.0;
  std::vector<std::optional<double>> values;
  std::optional<ContactState> contact;
  std::size_t line = 0;
};

double median_interval(const std::vector<double>& times) {
  std::vector<double> d;
  for (std::size_t i = 1; i < times.size(); ++i) d.push_back(times[i] - times[i - 1]);
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

// A gap: consecutive samples of one column further apart than this many of its median intervals.
constexpr double kGapIntervals = 5.0;
// A column must cover this fraction of the force's time span to be resampled onto its clock.
constexpr double kMinCoverage = 0.5;

// The header as read: its columns, the contact column's position and the header's line.
struct Header {
  std::vector<HeaderColumn> columns;
  std::optional<std::size_t> contact_col;
  std::size_t line = 0;
};

// The header's columns as excerpts, for messages that list them.
std::string listed(const Header& h) {
  std::vector<std::string> have;
  for (const auto& c : h.columns) have.push_back(text::excerpt(c.text));
  return fmt::format("{}", fmt::join(have, ", "));
}

// Every column mapping names a column of the header and every unit given by option one the
// record has; the time and the force are there.
void check_header(const Header& h, std::string_view at, const ReadOptions& options) {
  for (const auto& mapping : options.columns) {
    const auto& [to, from] = mapping;
    const auto wanted = trim(from);
    const bool found = std::any_of(h.columns.begin(), h.columns.end(),
                                   [wanted](const HeaderColumn& c) { return c.text == wanted; });
    if (!found) {
      throw SeriesError(fmt::format("{}: the column mapping {}=\"{}\" names no column; it has: {}",
                                    at, to, text::excerpt(from), listed(h)));
    }
  }
  for (const auto& unit : options.units) {
    const std::string& col = unit.first;
    const bool found = std::any_of(h.columns.begin(), h.columns.end(),
                                   [&col](const HeaderColumn& c) { return c.name == col; });
    if (!found) {
      throw SeriesError(fmt::format(
          "{}: a unit is given for the column '{}', which the record has not", at, col));
    }
  }
  const auto require = [&](std::string_view name, std::string_view what) {
    for (const auto& c : h.columns) {
      if (c.name == name) return;
    }
    throw SeriesError(fmt::format(
        "{}: the header has no '{}' column ({}, required); it has: {} (name it with a column "
        "mapping, e.g. --column {}=\"Time (s)\")",
        at, name, what, listed(h), name));
  };
  require(kTime, "time");
  require(kForce, "the plate reaction force");
}

// The header: the first record (comments and blank lines are no records).
Header read_header(text::CsvReader& reader, std::string_view source,
                   const units::UnitParser& parser, const ReadOptions& options,
                   std::vector<std::string>& notes) {
  text::CsvRecord record;
  if (!reader.next<SeriesError>(record, source)) {
    throw SeriesError(fmt::format(
        "{}: no header line; the first line that is not a '#' comment names the columns, e.g. "
        "\"t [ms],F [N],z [mm]\"",
        source));
  }
  Header h;
  h.line = record.line;
  const auto at = fmt::format("{}:{}", source, h.line);
  for (std::size_t k = 0; k < record.cells.size(); ++k) {
    auto c = parse_header_cell(record.cells[k], at, k + 1, parser, options);
    if (c.name.empty()) {
      notes.push_back(fmt::format("column {} has no name (an index column?): skipped", k + 1));
    }
    for (std::size_t j = 0; j < h.columns.size() && !c.name.empty(); ++j) {
      if (h.columns[j].name == c.name) {
        throw SeriesError(fmt::format("{}: column {} '{}': the name '{}' is also column {} '{}'",
                                      at, k + 1, text::excerpt(c.text), text::excerpt(c.name),
                                      j + 1, text::excerpt(h.columns[j].text)));
      }
    }
    if (c.is_contact) h.contact_col = k;
    h.columns.push_back(std::move(c));
  }
  check_header(h, at, options);
  return h;
}

// The numeric columns (neither skipped nor the contact state): their names, their positions in
// the header, and which of them are the time and the force.
struct Layout {
  std::vector<std::string> names;
  std::vector<std::size_t> header_pos;
  std::size_t time_pos = 0, force_pos = 0;
};

Layout layout_of(const Header& h) {
  Layout l;
  for (std::size_t k = 0; k < h.columns.size(); ++k) {
    const auto& c = h.columns[k];
    if (c.is_contact || c.name.empty()) continue;
    if (c.name == kTime) l.time_pos = l.names.size();
    if (c.name == kForce) l.force_pos = l.names.size();
    l.names.push_back(c.name);
    l.header_pos.push_back(k);
  }
  return l;
}

// The rows as written, which columns held text, and whether any cell was missing.
struct RawRows {
  std::vector<RawRow> rows;
  std::vector<char> textual;
  bool gaps_anywhere = false;
};

// One record's cells into a row (in SI), or an error naming the line and the column.
RawRow read_row(const std::vector<std::string>& cells, std::string_view source, std::size_t line,
                const Header& h, const Layout& l, bool decimal_comma, RawRows& raw) {
  const auto at = [&] { return fmt::format("{}:{}", source, line); };
  const auto& header = h.columns;
  if (cells.size() < header.size()) {
    throw SeriesError(fmt::format(
        "{}: {} cells, but the header has {} columns (column {} '{}' is missing)", at(),
        cells.size(), header.size(), cells.size() + 1, text::excerpt(header[cells.size()].text)));
  }
  if (cells.size() > header.size()) {
    throw SeriesError(fmt::format("{}: {} cells, but the header has only {} columns", at(),
                                  cells.size(), header.size()));
  }
  RawRow row;
  row.values.resize(l.header_pos.size());
  for (std::size_t i = 0; i < l.header_pos.size(); ++i) {
    const auto k = l.header_pos[i];
    if (is_missing(cells[k])) {
      if (i == l.time_pos) {
        throw SeriesError(fmt::format("{}: column {} '{}': the time is empty", at(), k + 1,
                                      text::excerpt(header[k].text)));
      }
      raw.gaps_anywhere = true;
      continue;
    }
    const auto v = parse_number(cells[k], decimal_comma);
    if (!v && !column_dimension(l.names[i])) {
      raw.textual[i] = true;  // a column the analysis does not read, holding text: left out
      continue;
    }
    if (!v) {
      throw SeriesError(fmt::format("{}: column {} '{}': '{}' is not a finite number", at(), k + 1,
                                    text::excerpt(header[k].text), text::excerpt(trim(cells[k]))));
    }
    row.values[i] = *v * header[k].to_si;
  }
  row.t = *row.values[l.time_pos];
  if (const auto col = h.contact_col) {
    if (is_missing(cells[*col])) {
      raw.gaps_anywhere = true;
    } else {
      row.contact = parse_contact_state(cells[*col]);
      if (!row.contact) {
        throw SeriesError(
            fmt::format("{}: column {} 'contact': '{}' is not a contact state (none, ring or disk)",
                        at(), *col + 1, text::excerpt(trim(cells[*col]))));
      }
    }
  }
  return row;
}

RawRows read_rows(text::CsvReader& reader, std::string_view source, const Header& h,
                  const Layout& l, bool decimal_comma) {
  RawRows raw;
  raw.textual.assign(l.names.size(), 0);
  text::CsvRecord record;
  while (reader.next<SeriesError>(record, source)) {
    auto row = read_row(record.cells, source, record.line, h, l, decimal_comma, raw);
    row.line = record.line;
    raw.rows.push_back(std::move(row));
  }
  return raw;
}

// Rows out of order are sorted (with a note); rows of one time are merged, each column from the
// row that has it; two different values of one column at one time are an error.
std::vector<RawRow> sort_and_merge(std::vector<RawRow> rows, std::string_view source,
                                   const Header& h, const Layout& l,
                                   std::vector<std::string>& notes) {
  std::size_t out_of_order = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) out_of_order += rows[i].t < rows[i - 1].t;
  if (out_of_order > 0) {
    std::stable_sort(rows.begin(), rows.end(),
                     [](const RawRow& a, const RawRow& b) { return a.t < b.t; });
    notes.push_back(fmt::format(
        "the rows were not in time order (the time goes back at {} places): sorted by time",
        out_of_order));
  }
  std::vector<RawRow> merged;
  std::size_t duplicates = 0;
  for (auto& r : rows) {
    if (merged.empty() || merged.back().t != r.t) {
      merged.push_back(std::move(r));
      continue;
    }
    auto& m = merged.back();
    ++duplicates;
    for (std::size_t i = 0; i < r.values.size(); ++i) {
      if (!r.values[i]) continue;
      if (m.values[i] && *m.values[i] != *r.values[i]) {
        throw SeriesError(fmt::format(
            "{}:{}: column '{}': time {} s is also on line {} with another value ({} against {}): "
            "time must increase from row to row",
            source, r.line, text::excerpt(h.columns[l.header_pos[i]].text), r.t, m.line,
            *r.values[i], *m.values[i]));
      }
      m.values[i] = r.values[i];
    }
    if (r.contact) {
      if (m.contact && *m.contact != *r.contact) {
        throw SeriesError(
            fmt::format("{}:{}: time {} s is also on line {} with another contact "
                        "state",
                        source, r.line, r.t, m.line));
      }
      m.contact = r.contact;
    }
  }
  if (duplicates > 0) {
    notes.push_back(fmt::format("{} rows repeated a time: merged with the row before", duplicates));
  }
  return merged;
}

// Each numeric column's own samples (the rows that have a value of it), and the contact state's.
struct Samples {
  std::vector<std::vector<double>> t, v;
  std::vector<double> contact_t;
  std::vector<ContactState> contact_v;
};

Samples samples_of(const std::vector<RawRow>& merged, std::size_t columns) {
  Samples s;
  s.t.resize(columns);
  s.v.resize(columns);
  for (const auto& r : merged) {
    for (std::size_t i = 0; i < columns; ++i) {
      if (r.values[i]) {
        s.t[i].push_back(r.t);
        s.v[i].push_back(*r.values[i]);
      }
    }
    if (r.contact) {
      s.contact_t.push_back(r.t);
      s.contact_v.push_back(*r.contact);
    }
  }
  return s;
}

// What is kept of the record: the columns, the contact state, the gaps found, and the times
// [lo, hi] of the force's clock that every kept column covers.
struct Selection {
  std::vector<bool> keep;
  bool keep_contact = false;
  std::vector<Gap> gaps;
  double lo = 0.0, hi = 0.0;
};

// Columns that cover less than kMinCoverage of the force's time span are left out; the columns
// the analysis reads, and the contact state, cut the record to the span they cover.
void drop_uncovered(const Layout& l, const Samples& s, Selection& sel,
                    std::vector<std::string>& notes) {
  const auto& clock = s.t[l.force_pos];
  const double span = clock.back() - clock.front();
  const auto covered = [&](const std::vector<double>& ts) {
    return ts.size() >= 2 && ts.back() - ts.front() >= kMinCoverage * span;
  };
  for (std::size_t i = 0; i < l.names.size(); ++i) {
    if (i == l.time_pos || i == l.force_pos || !sel.keep[i]) continue;
    const auto& ts = s.t[i];
    if (!covered(ts)) {
      sel.keep[i] = false;
      notes.push_back(fmt::format(
          "column '{}' has {} values over {:.4g} s, less than half the force's "
          "{:.4g} s: left out",
          text::excerpt(l.names[i]), ts.size(), ts.empty() ? 0.0 : ts.back() - ts.front(), span));
      continue;
    }
    // Only the columns the analysis reads cut the record to their time span; another column is
    // held at its end values beyond it.
    if (column_dimension(l.names[i])) {
      sel.lo = std::max(sel.lo, ts.front());
      sel.hi = std::min(sel.hi, ts.back());
    }
  }
  if (sel.keep_contact && !covered(s.contact_t)) {
    sel.keep_contact = false;
    notes.push_back("the contact column covers less than half the force's time: left out");
  } else if (sel.keep_contact) {
    sel.lo = std::max(sel.lo, s.contact_t.front());
  }
}

// The gaps of the kept columns, and notes on their own clocks, on the cut and on the gaps.
void note_clocks_and_cut(const Layout& l, const Samples& s, std::string_view source, Selection& sel,
                         std::vector<std::string>& notes) {
  const auto& clock = s.t[l.force_pos];
  std::vector<std::string> resampled;
  for (std::size_t i = 0; i < l.names.size(); ++i) {
    if (!sel.keep[i] || i == l.time_pos) continue;
    const auto& ts = s.t[i];
    const double dt = median_interval(ts);
    for (std::size_t j = 1; j < ts.size(); ++j) {
      if (ts[j] - ts[j - 1] > kGapIntervals * dt)
        sel.gaps.push_back({l.names[i], ts[j - 1], ts[j]});
    }
    if (i != l.force_pos && ts.size() != clock.size()) {
      resampled.push_back(
          fmt::format("{} ({:.4g} Hz)", text::excerpt(l.names[i]), dt > 0.0 ? 1.0 / dt : 0.0));
    }
  }
  const double dt_clock = median_interval(clock);
  if (!resampled.empty()) {
    notes.push_back(
        fmt::format("the columns have their own clocks: {} interpolated linearly onto the force's "
                    "({:.4g} Hz){}",
                    fmt::join(resampled, ", "), dt_clock > 0.0 ? 1.0 / dt_clock : 0.0,
                    sel.keep_contact ? "; the contact state held from its last sample" : ""));
  }
  if (sel.lo > clock.front() || sel.hi < clock.back()) {
    const auto from = std::lower_bound(clock.begin(), clock.end(), sel.lo);
    const auto to = std::upper_bound(clock.begin(), clock.end(), sel.hi);
    if (from >= to) {
      throw SeriesError(fmt::format(
          "{}: no time of the force's clock lies where every column has values ({:.6g} .. {:.6g} "
          "s)",
          source, sel.lo, sel.hi));
    }
    notes.push_back(fmt::format(
        "the record is cut to {:.6g} .. {:.6g} s, the times every column covers (the force: "
        "{:.6g} .. {:.6g} s)",
        *from, *(to - 1), clock.front(), clock.back()));
  }
  for (const auto& g : sel.gaps) {
    notes.push_back(
        fmt::format("column '{}' has no values from {:.6g} to {:.6g} s ({:.3g} ms): "
                    "interpolated across",
                    text::excerpt(g.column), g.from, g.to, 1e3 * (g.to - g.from)));
  }
}

// One clock, the force plate's: the rows that have F. Every other column is interpolated onto it
// linearly between its own samples (the contact state held from its last sample); the record is
// cut to the times every kept column covers. Columns of text or without values are left out.
Selection select(const Layout& l, const Samples& s, const RawRows& raw, bool has_contact,
                 bool any_rows, std::string_view source, std::vector<std::string>& notes) {
  const auto& clock = s.t[l.force_pos];
  Selection sel;
  sel.keep.assign(l.names.size(), true);
  for (std::size_t i = 0; i < l.names.size(); ++i) {
    if (raw.textual[i]) {
      sel.keep[i] = false;
      notes.push_back(fmt::format("column '{}' holds text: left out", text::excerpt(l.names[i])));
    }
  }
  sel.keep_contact = has_contact;
  sel.lo = clock.empty() ? 0.0 : clock.front();
  sel.hi = clock.empty() ? 0.0 : clock.back();
  if (raw.gaps_anywhere && clock.size() >= 2) {
    drop_uncovered(l, s, sel, notes);
    note_clocks_and_cut(l, s, source, sel, notes);
  }
  for (std::size_t i = 0; i < l.names.size(); ++i) {
    if (sel.keep[i] && i != l.time_pos && i != l.force_pos && any_rows && s.t[i].empty()) {
      sel.keep[i] = false;
      notes.push_back(
          fmt::format("column '{}' has no values: left out", text::excerpt(l.names[i])));
    }
  }
  if (sel.keep_contact && any_rows && s.contact_t.empty()) {
    sel.keep_contact = false;
    notes.push_back("the contact column has no values: left out");
  }
  return sel;
}

// The value of a column at time t of the force's clock, from its own samples ts, vs: linear
// between them, its end value beyond them; `cursor` walks the samples along the clock.
double value_at(double t, const std::vector<double>& ts, const std::vector<double>& vs,
                std::size_t& cursor) {
  auto& c = cursor;
  while (c + 1 < ts.size() && ts[c + 1] <= t) ++c;
  if (ts[c] == t || c + 1 == ts.size()) return vs[c];
  const double s = (t - ts[c]) / (ts[c + 1] - ts[c]);
  return vs[c] + s * (vs[c + 1] - vs[c]);
}

}  // namespace

TimeSeries TimeSeries::read_csv(std::istream& in, std::string_view source,
                                const units::UnitParser& parser, const ReadOptions& options) {
  const std::string csv{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return read_csv(std::string_view(csv), source, parser, options);
}

TimeSeries TimeSeries::read_csv(std::string_view csv, std::string_view source,
                                const units::UnitParser& parser, const ReadOptions& options) {
  const char sep = text::detect_separator(csv);
  text::CsvReader reader(csv, sep);
  std::vector<std::string> notes;
  const auto header = read_header(reader, source, parser, options, notes);
  const auto l = layout_of(header);
  auto raw = read_rows(reader, source, header, l, sep != ',');
  const auto merged = sort_and_merge(std::move(raw.rows), source, header, l, notes);
  const auto s = samples_of(merged, l.names.size());
  const auto& clock = s.t[l.force_pos];
  if (merged.size() > 0 && clock.empty()) {
    throw SeriesError(fmt::format("{}: no row has a value of F", source));
  }
  auto sel = select(l, s, raw, header.contact_col.has_value(), !merged.empty(), source, notes);

  std::vector<std::string> kept_names;
  for (std::size_t i = 0; i < l.names.size(); ++i) {
    if (sel.keep[i]) kept_names.push_back(l.names[i]);
  }
  TimeSeries series(kept_names, sel.keep_contact);
  for (std::size_t i = 0; i < l.names.size(); ++i) {
    if (sel.keep[i] && i != l.time_pos)
      series.own_intervals_.emplace_back(l.names[i], median_interval(s.t[i]));
  }
  if (sel.keep_contact)
    series.own_intervals_.emplace_back(std::string(kContact), median_interval(s.contact_t));
  series.notes_ = std::move(notes);
  series.gaps_ = std::move(sel.gaps);
  series.reserve(clock.size());
  std::vector<double> values;
  std::vector<std::size_t> cursor(l.names.size(), 0);
  std::size_t contact_cursor = 0;
  for (const double t : clock) {
    if (t < sel.lo || t > sel.hi) continue;
    values.clear();
    for (std::size_t i = 0; i < l.names.size(); ++i) {
      if (!sel.keep[i]) continue;
      values.push_back(i == l.time_pos ? t : value_at(t, s.t[i], s.v[i], cursor[i]));
    }
    if (sel.keep_contact) {
      while (contact_cursor + 1 < s.contact_t.size() && s.contact_t[contact_cursor + 1] <= t) {
        ++contact_cursor;
      }
      // Before the state's first sample there is nothing to hold: the record is cut there
      // (lo above), except on the single-clock path where every row has its state.
      series.append(values, s.contact_v[contact_cursor]);
    } else {
      series.append(values, std::nullopt);
    }
  }
  return series;
}

TimeSeries TimeSeries::read_csv_file(const std::filesystem::path& path,
                                     const units::UnitParser* parser, const ReadOptions& options) {
  const auto csv = text::read_file<SeriesError>(path, "a time series");
  if (parser != nullptr) return read_csv(std::string_view(csv), path.string(), *parser, options);
  const units::UnitParser own;
  return read_csv(std::string_view(csv), path.string(), own, options);
}

}  // namespace snapjump::measure
