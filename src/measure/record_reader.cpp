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
  // "t_ms", "F_N", "z_mm": a known name, an underscore and a unit of the right dimension.
  if (!known && !unit) {
    const auto us = name.rfind('_');
    if (us != std::string_view::npos && us > 0) {
      const auto base = canonical(name.substr(0, us));
      const auto dim = base ? column_dimension(*base) : std::nullopt;
      if (dim) {
        try {
          (void)parser.to_si(1.0, name.substr(us + 1), *dim);
          known = base;
          unit = std::string(name.substr(us + 1));
        } catch (const units::UnitError&) {
          // not a unit: an unknown column
        }
      }
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
  text::CsvRecord record;
  std::size_t line_no = 0;
  const auto at = [&] { return fmt::format("{}:{}", source, line_no); };

  // The header: the first record (comments and blank lines are no records).
  if (!reader.next<SeriesError>(record, source)) {
    throw SeriesError(fmt::format(
        "{}: no header line; the first line that is not a '#' comment names the columns, e.g. "
        "\"t [ms],F [N],z [mm]\"",
        source));
  }
  line_no = record.line;
  const bool decimal_comma = sep != ',';
  const auto header_cells = std::move(record.cells);
  std::vector<HeaderColumn> header;
  std::optional<std::size_t> contact_col;
  std::vector<std::string> notes;
  for (std::size_t k = 0; k < header_cells.size(); ++k) {
    auto c = parse_header_cell(header_cells[k], at(), k + 1, parser, options);
    if (c.name.empty()) {
      notes.push_back(fmt::format("column {} has no name (an index column?): skipped", k + 1));
    }
    for (std::size_t j = 0; j < header.size() && !c.name.empty(); ++j) {
      if (header[j].name == c.name) {
        throw SeriesError(fmt::format("{}: column {} '{}': the name '{}' is also column {} '{}'",
                                      at(), k + 1, text::excerpt(c.text), text::excerpt(c.name),
                                      j + 1, text::excerpt(header[j].text)));
      }
    }
    if (c.is_contact) contact_col = k;
    header.push_back(std::move(c));
  }
  for (const auto& mapping : options.columns) {
    const auto& [to, from] = mapping;
    const auto wanted = trim(from);
    const bool found = std::any_of(header.begin(), header.end(),
                                   [wanted](const HeaderColumn& h) { return h.text == wanted; });
    if (!found) {
      std::vector<std::string> have;
      for (const auto& h : header) have.push_back(text::excerpt(h.text));
      throw SeriesError(fmt::format("{}: the column mapping {}=\"{}\" names no column; it has: {}",
                                    at(), to, from, fmt::join(have, ", ")));
    }
  }
  for (const auto& unit : options.units) {
    const std::string& col = unit.first;
    const bool found = std::any_of(header.begin(), header.end(),
                                   [&col](const HeaderColumn& h) { return h.name == col; });
    if (!found) {
      throw SeriesError(fmt::format(
          "{}: a unit is given for the column '{}', which the record has not", at(), col));
    }
  }
  const auto require = [&](std::string_view name, std::string_view what) {
    for (const auto& h : header) {
      if (h.name == name) return;
    }
    std::vector<std::string> have;
    for (const auto& h : header) have.push_back(text::excerpt(h.text));
    throw SeriesError(fmt::format(
        "{}: the header has no '{}' column ({}, required); it has: {} (name it with a column "
        "mapping, e.g. --column {}=\"Time (s)\")",
        at(), name, what, fmt::join(have, ", "), name));
  };
  require(kTime, "time");
  require(kForce, "the plate reaction force");

  std::vector<std::string> names;
  std::vector<std::size_t> numeric_cols;  // header position of each numeric column
  std::size_t time_pos = 0, force_pos = 0;
  for (std::size_t k = 0; k < header.size(); ++k) {
    if (header[k].is_contact || header[k].name.empty()) continue;
    if (header[k].name == kTime) time_pos = names.size();
    if (header[k].name == kForce) force_pos = names.size();
    names.push_back(header[k].name);
    numeric_cols.push_back(k);
  }

  // The rows as written.
  std::vector<RawRow> rows;
  std::vector<char> textual(names.size(), 0);
  bool gaps_anywhere = false;
  while (reader.next<SeriesError>(record, source)) {
    line_no = record.line;
    const auto& cells = record.cells;
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
    row.line = line_no;
    row.values.resize(numeric_cols.size());
    for (std::size_t i = 0; i < numeric_cols.size(); ++i) {
      const auto k = numeric_cols[i];
      if (is_missing(cells[k])) {
        if (i == time_pos) {
          throw SeriesError(fmt::format("{}: column {} '{}': the time is empty", at(), k + 1,
                                        text::excerpt(header[k].text)));
        }
        gaps_anywhere = true;
        continue;
      }
      const auto v = parse_number(cells[k], decimal_comma);
      if (!v && !column_dimension(names[i])) {
        textual[i] = true;  // a column the analysis does not read, holding text: left out
        continue;
      }
      if (!v) {
        throw SeriesError(fmt::format("{}: column {} '{}': '{}' is not a finite number", at(),
                                      k + 1, text::excerpt(header[k].text),
                                      text::excerpt(trim(cells[k]))));
      }
      row.values[i] = *v * header[k].to_si;
    }
    row.t = *row.values[time_pos];
    if (contact_col) {
      if (is_missing(cells[*contact_col])) {
        gaps_anywhere = true;
      } else {
        row.contact = parse_contact_state(cells[*contact_col]);
        if (!row.contact) {
          throw SeriesError(fmt::format(
              "{}: column {} 'contact': '{}' is not a contact state (none, ring or disk)", at(),
              *contact_col + 1, trim(cells[*contact_col])));
        }
      }
    }
    rows.push_back(std::move(row));
  }

  // Rows out of order are sorted (with a note); rows of one time are merged, each column from
  // the row that has it; two different values of one column at one time are an error.
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
            source, r.line, text::excerpt(header[numeric_cols[i]].text), r.t, m.line, *r.values[i],
            *m.values[i]));
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

  // One clock, the force plate's: the rows that have F. Every other column is interpolated onto
  // it linearly between its own samples (the contact state held from its last sample); the record
  // is cut to the times every kept column covers.
  std::vector<std::vector<double>> own_t(names.size()), own_v(names.size());
  std::vector<double> contact_t;
  std::vector<ContactState> contact_v;
  for (const auto& r : merged) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (r.values[i]) {
        own_t[i].push_back(r.t);
        own_v[i].push_back(*r.values[i]);
      }
    }
    if (r.contact) {
      contact_t.push_back(r.t);
      contact_v.push_back(*r.contact);
    }
  }
  const auto& clock = own_t[force_pos];
  if (merged.size() > 0 && clock.empty()) {
    throw SeriesError(fmt::format("{}: no row has a value of F", source));
  }
  std::vector<bool> keep(names.size(), true);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (textual[i]) {
      keep[i] = false;
      notes.push_back(fmt::format("column '{}' holds text: left out", names[i]));
    }
  }
  bool keep_contact = contact_col.has_value();
  std::vector<Gap> gaps;
  double lo = clock.empty() ? 0.0 : clock.front();
  double hi = clock.empty() ? 0.0 : clock.back();
  if (gaps_anywhere && clock.size() >= 2) {
    const double span = clock.back() - clock.front();
    const auto covered = [&](const std::vector<double>& ts) {
      return ts.size() >= 2 && ts.back() - ts.front() >= kMinCoverage * span;
    };
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (i == time_pos || i == force_pos || !keep[i]) continue;
      if (!covered(own_t[i])) {
        keep[i] = false;
        notes.push_back(
            fmt::format("column '{}' has {} values over {:.4g} s, less than half the force's "
                        "{:.4g} s: left out",
                        names[i], own_t[i].size(),
                        own_t[i].empty() ? 0.0 : own_t[i].back() - own_t[i].front(), span));
        continue;
      }
      // Only the columns the analysis reads cut the record to their time span; another column
      // is held at its end values beyond it.
      if (column_dimension(names[i])) {
        lo = std::max(lo, own_t[i].front());
        hi = std::min(hi, own_t[i].back());
      }
    }
    if (keep_contact && !covered(contact_t)) {
      keep_contact = false;
      notes.push_back("the contact column covers less than half the force's time: left out");
    } else if (keep_contact) {
      lo = std::max(lo, contact_t.front());
    }
    std::vector<std::string> resampled;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!keep[i] || i == time_pos) continue;
      const double dt = median_interval(own_t[i]);
      for (std::size_t j = 1; j < own_t[i].size(); ++j) {
        if (own_t[i][j] - own_t[i][j - 1] > kGapIntervals * dt) {
          gaps.push_back({names[i], own_t[i][j - 1], own_t[i][j]});
        }
      }
      if (i != force_pos && own_t[i].size() != clock.size()) {
        resampled.push_back(fmt::format("{} ({:.4g} Hz)", names[i], dt > 0.0 ? 1.0 / dt : 0.0));
      }
    }
    const double dt_clock = median_interval(clock);
    if (!resampled.empty()) {
      notes.push_back(fmt::format(
          "the columns have their own clocks: {} interpolated linearly onto the force's "
          "({:.4g} Hz){}",
          fmt::join(resampled, ", "), dt_clock > 0.0 ? 1.0 / dt_clock : 0.0,
          keep_contact ? "; the contact state held from its last sample" : ""));
    }
    if (lo > clock.front() || hi < clock.back()) {
      const auto from = std::lower_bound(clock.begin(), clock.end(), lo);
      const auto to = std::upper_bound(clock.begin(), clock.end(), hi);
      if (from >= to) {
        throw SeriesError(fmt::format(
            "{}: no time of the force's clock lies where every column has values ({:.6g} .. {:.6g} "
            "s)",
            source, lo, hi));
      }
      notes.push_back(fmt::format(
          "the record is cut to {:.6g} .. {:.6g} s, the times every column covers (the force: "
          "{:.6g} .. {:.6g} s)",
          *from, *(to - 1), clock.front(), clock.back()));
    }
    for (const auto& g : gaps) {
      notes.push_back(
          fmt::format("column '{}' has no values from {:.6g} to {:.6g} s ({:.3g} ms): "
                      "interpolated across",
                      g.column, g.from, g.to, 1e3 * (g.to - g.from)));
    }
  }

  for (std::size_t i = 0; i < names.size(); ++i) {
    if (keep[i] && i != time_pos && i != force_pos && !merged.empty() && own_t[i].empty()) {
      keep[i] = false;
      notes.push_back(fmt::format("column '{}' has no values: left out", names[i]));
    }
  }
  if (keep_contact && !merged.empty() && contact_t.empty()) {
    keep_contact = false;
    notes.push_back("the contact column has no values: left out");
  }
  std::vector<std::string> kept_names;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (keep[i]) kept_names.push_back(names[i]);
  }
  TimeSeries series(kept_names, keep_contact);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (keep[i] && i != time_pos)
      series.own_intervals_.emplace_back(names[i], median_interval(own_t[i]));
  }
  if (keep_contact)
    series.own_intervals_.emplace_back(std::string(kContact), median_interval(contact_t));
  series.notes_ = std::move(notes);
  series.gaps_ = std::move(gaps);
  series.reserve(clock.size());
  std::vector<double> values;
  std::vector<std::size_t> cursor(names.size(), 0);
  std::size_t contact_cursor = 0;
  for (const double t : clock) {
    if (t < lo || t > hi) continue;
    values.clear();
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!keep[i]) continue;
      if (i == time_pos) {
        values.push_back(t);
        continue;
      }
      const auto& ts = own_t[i];
      const auto& vs = own_v[i];
      auto& c = cursor[i];
      while (c + 1 < ts.size() && ts[c + 1] <= t) ++c;
      if (ts[c] == t || c + 1 == ts.size()) {
        values.push_back(vs[c]);
      } else {
        const double s = (t - ts[c]) / (ts[c + 1] - ts[c]);
        values.push_back(vs[c] + s * (vs[c + 1] - vs[c]));
      }
    }
    if (keep_contact) {
      while (contact_cursor + 1 < contact_t.size() && contact_t[contact_cursor + 1] <= t) {
        ++contact_cursor;
      }
      // Before the state's first sample there is nothing to hold: the record is cut there
      // (lo above), except on the single-clock path where every row has its state.
      series.append(values, contact_v[contact_cursor]);
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
