// Figures of one run: the time series (Fig. 2(a)) and cross-sections of the shell (Fig. 1(c)).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <system_error>

#include "config/text.hpp"
#include "measure/analysis.hpp"
#include "measure/time_series.hpp"
#include "plot/figures.hpp"
#include "plot/snapshots.hpp"
#include "plot/style.hpp"

namespace snapjump::plot {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void require_run_folder(const fs::path& run_dir) {
  std::error_code ec;
  if (!fs::exists(run_dir, ec)) {
    throw PlotInputError(fmt::format("{}: no such run folder", run_dir.string()));
  }
  if (!fs::is_directory(run_dir, ec)) {
    throw PlotInputError(fmt::format(
        "{}: not a folder; give the run folder that `snapjump run` wrote", run_dir.string()));
  }
}

// summary.json of a run, or null when there is none or it cannot be read (noted).
json read_summary(const fs::path& path, std::vector<std::string>& notes) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    notes.push_back(fmt::format("{} not found: no onset or launch marks", path.string()));
    return nullptr;
  }
  std::ifstream in(path);
  auto doc = json::parse(in, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) {
    notes.push_back(fmt::format("{} is not valid JSON: no onset or launch marks", path.string()));
    return nullptr;
  }
  return doc;
}

// summary["measured"]["quantities"][key]["value"], when it is a number.
std::optional<double> measured(const json& summary, const char* key) {
  if (!summary.is_object()) return std::nullopt;
  const auto m = summary.find("measured");
  if (m == summary.end() || !m->is_object()) return std::nullopt;
  const auto q = m->find("quantities");
  if (q == m->end() || !q->is_object()) return std::nullopt;
  const auto k = q->find(key);
  if (k == q->end() || !k->is_object()) return std::nullopt;
  const auto v = k->find("value");
  if (v == k->end() || !v->is_number()) return std::nullopt;
  const double d = v->get<double>();
  return std::isfinite(d) ? std::optional<double>(d) : std::nullopt;
}

// summary["theory"]["quantities"][key] {lower, upper}, when both are numbers.
std::optional<std::pair<double, double>> theory_range(const json& summary, const char* key) {
  if (!summary.is_object()) return std::nullopt;
  const auto t = summary.find("theory");
  if (t == summary.end() || !t->is_object()) return std::nullopt;
  const auto q = t->find("quantities");
  if (q == t->end() || !q->is_object()) return std::nullopt;
  const auto k = q->find(key);
  if (k == q->end() || !k->is_object()) return std::nullopt;
  const auto lo = k->find("lower");
  const auto hi = k->find("upper");
  if (lo == k->end() || hi == k->end() || !lo->is_number() || !hi->is_number()) return std::nullopt;
  const double a = lo->get<double>(), b = hi->get<double>();
  if (!std::isfinite(a) || !std::isfinite(b)) return std::nullopt;
  return std::make_pair(std::min(a, b), std::max(a, b));
}

std::string summary_title(const json& summary) {
  if (!summary.is_object()) return {};
  const auto c = summary.find("case");
  if (c == summary.end() || !c->is_object()) return {};
  const auto t = c->find("title");
  if (t == c->end() || !t->is_string()) return {};
  return text::capped_title(t->get<std::string>());
}

// Time intervals [t0, t1) of one contact state, runs of equal rows.
struct Interval {
  double t0 = 0.0, t1 = 0.0;
  measure::ContactState state = measure::ContactState::None;
};

std::vector<Interval> contact_intervals(const measure::TimeSeries& s) {
  std::vector<Interval> v;
  const auto t = s.time();
  const auto c = s.contact();
  if (c.empty()) return v;
  std::size_t start = 0;
  for (std::size_t i = 1; i <= c.size(); ++i) {
    if (i == c.size() || c[i] != c[start]) {
      const double t1 = i < c.size() ? t[i] : t[c.size() - 1];
      if (c[start] != measure::ContactState::None && t1 > t[start]) {
        v.push_back({t[start], t1, c[start]});
      }
      start = i;
    }
  }
  return v;
}

}  // namespace

namespace {

// The run's R [m] from summary.json's case, for the experiment's onset (w / R).
std::optional<double> summary_radius(const json& summary) {
  if (!summary.is_object()) return std::nullopt;
  const auto c = summary.find("case");
  if (c == summary.end() || !c->is_object()) return std::nullopt;
  const auto R = c->find("R");
  if (R == c->end() || !R->is_number()) return std::nullopt;
  const double v = R->get<double>();
  return v > 0.0 && std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

// The series' columns the figure draws, in the order of its datablocks (after t).
constexpr std::array<const char*, 5> kDrawn = {"z", "r", "w", "F", "delta_p"};

// One panel of the figure: its columns (names in the series), label and colours.
struct Panel {
  std::vector<const char*> columns;
  std::vector<const char*> titles;
  std::vector<std::string_view> colours;
  std::string ylabel;
};

// A series read for the figure; a reader's error is the figure's input error.
measure::TimeSeries read_series(const fs::path& csv, const measure::ReadOptions& read = {}) {
  try {
    return measure::TimeSeries::read_csv_file(csv, nullptr, read);
  } catch (const measure::SeriesError& e) {
    throw PlotInputError(e.what());
  }
}

// The run's series has every column the figure draws, and rows.
void require_drawable(const measure::TimeSeries& s, const fs::path& csv) {
  std::string missing;
  for (const char* name : kDrawn) {
    if (s.has(name)) continue;
    missing += fmt::format("{}'{}'", missing.empty() ? "" : ", ", name);
  }
  if (!missing.empty()) {
    throw PlotInputError(
        fmt::format("{}: no column {} (the series figure needs t, z, r, w, F "
                    "and delta_p)",
                    csv.string(), missing));
  }
  if (s.empty()) throw PlotInputError(fmt::format("{}: the series has no rows", csv.string()));
}

double largest_pressure(const measure::TimeSeries& s, double so_far) {
  for (const double v : s.column("delta_p")) so_far = std::max(so_far, std::abs(v));
  return so_far;
}

// A measured record beside the run, on the run's clock: shifted so that its onset falls on the
// run's (or not shifted: both clocks start at the release).
struct Experiment {
  measure::TimeSeries series;
  double shift = 0.0;  // added to the record's times [s]
};

Experiment read_experiment(const SeriesFigureOptions& series_options, const json& summary,
                           std::vector<std::string>& notes) {
  Experiment x{read_series(series_options.experiment, series_options.read), 0.0};
  if (x.series.empty()) {
    throw PlotInputError(
        fmt::format("{}: the record has no rows", series_options.experiment.string()));
  }
  for (const auto& note : x.series.notes()) notes.push_back(fmt::format("record: {}", note));
  if (series_options.align_at_release) return x;
  const auto t_run = measured(summary, "t_onset");
  measure::AnalysisOptions ao;
  ao.R = summary_radius(summary);
  std::optional<double> t_exp;
  try {
    t_exp = measure::analyze(x.series, ao).t_onset;
  } catch (const measure::SeriesError& e) {
    notes.push_back(fmt::format("the record's onset could not be found: {}", e.what()));
  }
  if (t_run && t_exp) {
    x.shift = *t_run - *t_exp;
    notes.push_back(fmt::format(
        "aligned at the onset: the record's {:.6g} s drawn at the run's {:.6g} s", *t_exp, *t_run));
  } else {
    notes.push_back(fmt::format(
        "aligned at the release: no onset in the {} (w with the run's R, or a contact column)",
        t_run ? "record" : "run's summary"));
  }
  return x;
}

// The window drawn [s, on the run's clock]: the option's, or the run's and the record's times.
std::pair<double, double> series_window(const measure::TimeSeries& s,
                                        const SeriesFigureOptions& series_options,
                                        const std::optional<Experiment>& experiment) {
  const auto t = s.time();
  double w0 = t.front(), w1 = t.back();
  if (series_options.window) {
    w0 = series_options.window->first;
    w1 = series_options.window->second;
    if (!(w1 > w0)) {
      throw PlotInputError(
          fmt::format("--window {:.6g}s:{:.6g}s: the end must come after the start", w0, w1));
    }
  } else if (experiment) {
    w0 = std::min(w0, experiment->series.time().front() + experiment->shift);
    w1 = std::max(w1, experiment->series.time().back() + experiment->shift);
  }
  return {w0, w1};
}

// Rows of a series inside the window [w0, w1] (with the sample on either side), shifted by dt,
// thinned to 40000 (every k-th row; the largest F is kept), in the script's units.
std::vector<std::vector<double>> window_rows(const measure::TimeSeries& series, double dt,
                                             const char* what, std::pair<double, double> window,
                                             double dp_scale, std::vector<std::string>& notes) {
  const auto [w0, w1] = window;
  const auto ts = series.time();
  const double scale[] = {1e3, 1e3, 1e3, 1.0, dp_scale};
  std::size_t from = 0, to = ts.size();
  while (from + 1 < ts.size() && ts[from + 1] + dt <= w0) ++from;
  while (to > from + 1 && ts[to - 2] + dt >= w1) --to;
  const std::size_t count = to - from;
  const std::size_t limit = 40000;
  const std::size_t stride = count > limit ? (count + limit - 1) / limit : 1;
  std::size_t i_fmax = from;
  if (series.has("F")) {
    const auto f = series.column("F");
    for (std::size_t i = from; i < to; ++i) {
      if (f[i] > f[i_fmax]) i_fmax = i;
    }
  }
  std::vector<std::vector<double>> rows;
  for (std::size_t i = from; i < to; ++i) {
    if ((i - from) % stride != 0 && i != i_fmax && i + 1 != to) continue;
    std::vector<double> row{(ts[i] + dt) * 1e3};
    for (std::size_t k = 0; k < kDrawn.size(); ++k) {
      // A record may lack a column: 0 there, never drawn (a non-finite value would blank the
      // whole row of the datablock).
      row.push_back(series.has(kDrawn[k]) ? series.column(kDrawn[k])[i] * scale[k] : 0.0);
    }
    rows.push_back(std::move(row));
  }
  if (stride > 1) notes.push_back(fmt::format("{}: every {}th row is drawn", what, stride));
  if (rows.empty()) notes.push_back(fmt::format("{}: no rows inside the window", what));
  return rows;
}

// The contact states shaded behind every panel (not when they change more than 400 times);
// `ring` and `disk` say which were drawn, for the key.
std::string contact_shading(const measure::TimeSeries& s, std::vector<std::string>& notes,
                            bool& ring, bool& disk) {
  const auto intervals = contact_intervals(s);
  std::string gp;
  if (intervals.size() > 400) {
    notes.push_back(
        fmt::format("the contact state changes {} times: not shaded", intervals.size()));
    return gp;
  }
  int k = 1;
  for (const auto& iv : intervals) {
    const bool is_disk = iv.state == measure::ContactState::Disk;
    (is_disk ? disk : ring) = true;
    gp += fmt::format(
        "set object {} rect from first {}, graph 0 to first {}, graph 1 behind fc rgb '{}' "
        "fs solid 1.0 noborder\n",
        k++, number(iv.t0 * 1e3), number(iv.t1 * 1e3), is_disk ? "#d6e6f5" : "#fdebd3");
  }
  return gp;
}

// The onset and the launch from summary.json as vertical lines (the returned arrows) and their
// labels (`labels`, set on the first panel only).
std::string event_marks(const json& summary, std::vector<std::string>& notes, std::string& labels) {
  const auto t_onset = measured(summary, "t_onset");
  const auto t_launch = measured(summary, "t_launch");
  std::string gp;
  int arrow = 1;
  for (const auto& [tm, name] : {std::pair{t_onset, "onset"}, std::pair{t_launch, "launch"}}) {
    if (!tm) continue;
    gp += fmt::format(
        "set arrow {} from first {}, graph 0 to first {}, graph 1 nohead dt 2 lw 1.5 "
        "lc rgb '#404040' front\n",
        arrow, number(*tm * 1e3), number(*tm * 1e3));
    labels += fmt::format(
        "set label {} '{} ({:.1f} ms)' at first {}, graph 1 {} offset {},0.7 front\n", arrow, name,
        *tm * 1e3, number(*tm * 1e3), arrow == 1 ? "right" : "left", arrow == 1 ? -0.5 : 0.5);
    ++arrow;
  }
  if (summary.is_object() && !t_onset && !t_launch) {
    notes.push_back("summary.json has no measured onset or launch: no marks");
  }
  return gp;
}

// The panels; with a record, those it has no column of are left out.
std::vector<Panel> series_panels(bool kpa, const std::optional<Experiment>& experiment,
                                 std::vector<std::string>& notes) {
  std::vector<Panel> panels{
      {{"z"}, {"z"}, {style::kBlue}, "container height z [mm]"},
      {{"r", "w"}, {"contact radius r", "apex gap w"}, {style::kRed, style::kGreen}, "r, w [mm]"},
      {{"F"}, {"F"}, {style::kPurple}, "plate force F [N]"},
      {{"delta_p"},
       {"pressure difference δp (outside - inside)"},
       {style::kOrange},
       fmt::format("δp [{}]", kpa ? "kPa" : "Pa")},
  };
  if (!experiment) return panels;
  std::vector<Panel> kept;
  for (auto& p : panels) {
    const bool has = std::any_of(p.columns.begin(), p.columns.end(),
                                 [&](const char* c) { return experiment->series.has(c); });
    if (has) {
      kept.push_back(std::move(p));
    } else {
      notes.push_back(fmt::format("the record has no {}: that panel is left out",
                                  fmt::join(p.columns, " or ")));
    }
  }
  return kept;
}

// The column of a drawn quantity in the datablocks: t is column 1.
int column_index(const char* name) {
  const auto at = std::find_if(kDrawn.begin(), kDrawn.end(),
                               [&](const char* c) { return std::string_view(c) == name; });
  return static_cast<int>(at - kDrawn.begin()) + 2;
}

// What the panels draw besides the series: the summary's marks, the contact key entries.
struct PanelMarks {
  const json& summary;
  const measure::TimeSeries& run;
  bool ring = false, disk = false;
};

// The theory's H band and the measured H on the z panel, the contact key on the r panel, the
// theory's F* band and the measured F* on the force panel: their clauses, and the datablocks
// they need added to gp.
void panel_extras(const Panel& p, const PanelMarks& marks, std::string& gp,
                  std::vector<std::string>& clauses) {
  const auto& summary = marks.summary;
  const std::string_view first = p.columns.front();
  if (first == "z") {
    if (const auto H = theory_range(summary, "H")) {
      clauses.push_back(
          fmt::format("'+' using 1:({}):({}) with filledcurves {} title 'theory H bounds'",
                      number(H->first * 1e3), number(H->second * 1e3), style::kBand));
    }
    if (const auto H = measured(summary, "H")) {
      const auto t = marks.run.time();
      const auto z = marks.run.column("z");
      const auto top_z = std::max_element(z.begin(), z.end()) - z.begin();
      gp += fmt::format("$H << EOD\n{} {}\nEOD\n", number(t[static_cast<std::size_t>(top_z)] * 1e3),
                        number(*H * 1e3));
      clauses.push_back(
          fmt::format("$H using 1:2 {} title 'H (measured)'", style::points(style::kBlue, 8, 1.8)));
    }
  } else if (first == "r") {
    if (marks.ring) {
      clauses.emplace_back(
          "keyentry with boxes fc rgb '#fdebd3' fs solid 1.0 noborder title 'ring contact'");
    }
    if (marks.disk) {
      clauses.emplace_back(
          "keyentry with boxes fc rgb '#d6e6f5' fs solid 1.0 noborder title 'disk contact'");
    }
  } else if (first == "F") {
    if (const auto Fs = theory_range(summary, "F_star")) {
      clauses.push_back(
          fmt::format("'+' using 1:({}):({}) with filledcurves {} title 'theory F* bounds'",
                      number(Fs->first), number(Fs->second), style::kBand));
    }
    const auto F_star = measured(summary, "F_star");
    const auto t_F_star = measured(summary, "t_F_star");
    if (F_star && t_F_star) {
      gp += fmt::format("$Fstar << EOD\n{} {}\nEOD\n", number(*t_F_star * 1e3), number(*F_star));
      clauses.push_back(fmt::format("$Fstar using 1:2 {} title 'F* (measured)'",
                                    style::points(style::kPurple, 6, 2.0)));
    }
  }
}

// Panel k of n, stacked: its margins, axes, key and plot command (the event labels on the first).
std::string panel_script(int k, int n_panels, const Panel& p, const PanelMarks& marks,
                         const std::optional<Experiment>& experiment, const std::string& labels) {
  const double top = 0.94, bottom = 0.07, left = 0.1, right = 0.97;
  std::string gp = style::stacked_margins(k, n_panels, top, bottom, left, right);
  if (k + 1 < n_panels) {
    gp += "set format x ''\nunset xlabel\n";
  } else {
    gp += fmt::format("set format x '%g'\nset xlabel {}\n",
                      quote(experiment && experiment->shift != 0.0 ? "t after release (run) [ms]"
                                                                   : "t after release [ms]"));
  }
  if (k == 0) gp += labels;
  const bool force_panel = std::string_view(p.columns.front()) == "F";
  gp += fmt::format(
      "set ylabel {}\nset key {}\n", quote(p.ylabel),
      std::string_view(p.columns.front()) == "z" || force_panel ? "top left" : "bottom left");
  std::vector<std::string> clauses;
  for (std::size_t c = 0; c < p.columns.size(); ++c) {
    const int col = column_index(p.columns[c]);
    if (experiment && experiment->series.has(p.columns[c])) {
      clauses.push_back(fmt::format("$experiment using 1:{} with lines lw 2 lc rgb '{}' title {}",
                                    col, p.colours[c],
                                    quote(fmt::format("experiment {}", p.titles[c]))));
    }
    clauses.push_back(fmt::format("$series using 1:{} with lines lw {} {}lc rgb '{}' title {}", col,
                                  experiment ? 1.5 : 2.0, experiment ? "dt 2 " : "", p.colours[c],
                                  quote(fmt::format("simulation {}", p.titles[c]))));
  }
  panel_extras(p, marks, gp, clauses);
  gp += fmt::format("plot {}\n", fmt::join(clauses, ", "));
  if (k == 0 && !labels.empty()) gp += "unset label\n";
  return gp;
}

}  // namespace

FigureResult plot_series(const fs::path& run_dir, const FigureOptions& options,
                         const SeriesFigureOptions& series_options) {
  require_run_folder(run_dir);
  const auto csv = run_dir / "series.csv";
  // Read before anything is written: a folder without its series gets no figures folder.
  const auto s = read_series(csv);
  const bool with_experiment = !series_options.experiment.empty();
  auto result = figure_paths(
      options, run_dir / "figures" / (with_experiment ? "series-experiment" : "series"));
  auto& notes = result.notes;
  require_drawable(s, csv);

  const auto summary = read_summary(run_dir / "summary.json", notes);
  double dp_max = largest_pressure(s, 0.0);
  std::optional<Experiment> experiment;
  if (with_experiment) {
    experiment = read_experiment(series_options, summary, notes);
    if (experiment->series.has("delta_p")) dp_max = largest_pressure(experiment->series, dp_max);
  }
  const bool kpa = dp_max >= 2000.0;
  const double dp_scale = kpa ? 1e-3 : 1.0;
  const auto window = series_window(s, series_options, experiment);
  const auto [w0, w1] = window;

  std::string gp;
  gp += fmt::format(
      "# Fig. 2(a) of the paper: the time series of one run, from {}{}.\n"
      "# Written by `snapjump plot series`; edit and redraw with `gnuplot {}` in this folder.\n"
      "# Units: t in ms, z r w in mm, F in N, delta_p in {}.\n",
      printable(csv.string()),
      experiment ? fmt::format(", and the record {}", printable(series_options.experiment.string()))
                 : std::string(),
      printable(result.script.filename().string()), kpa ? "kPa" : "Pa");
  gp += terminal(options.format, 1200, 1000, result.figure, 14);
  const std::string columns =
      fmt::format("t [ms]  z [mm]  r [mm]  w [mm]  F [N]  delta_p [{}]", kpa ? "kPa" : "Pa");
  gp += datablock("series", columns, window_rows(s, 0.0, "run", window, dp_scale, notes));
  if (experiment) {
    gp += datablock(
        "experiment", columns,
        window_rows(experiment->series, experiment->shift, "record", window, dp_scale, notes));
  }

  // Marks shared by every panel: contact states shaded, onset and launch as vertical lines.
  PanelMarks marks{summary, s};
  gp += contact_shading(s, notes, marks.ring, marks.disk);
  std::string labels;
  gp += event_marks(summary, notes, labels);

  const auto title = summary_title(summary);
  gp += fmt::format("set multiplot title {} noenhanced\n",
                    quote(title.empty() ? run_dir.filename().string() : title));
  gp +=
      fmt::format("set xrange [{}:{}]\n", number(w0 * 1e3), number(std::max(w1, w0 + 1e-9) * 1e3));
  gp +=
      "set offsets 0, 0, graph 0.06, graph 0.06\nset key Left reverse opaque box lc rgb "
      "'#c0c0c0'\n";
  gp += "set grid xtics ytics lc rgb '#e0e0e0'\nset mxtics\n";
  const auto panels = series_panels(kpa, experiment, notes);
  const int n_panels = static_cast<int>(panels.size());
  for (int k = 0; k < n_panels; ++k) {
    gp += panel_script(k, n_panels, panels[static_cast<std::size_t>(k)], marks, experiment, labels);
  }
  gp += "unset multiplot\n";

  render(result, gp, options.gnuplot);
  return result;
}

namespace {

// One cross-section of the figure: the snapshot nearest a requested time and its points.
struct Section {
  double requested = 0.0;
  const Frame* frame = nullptr;
  std::vector<std::vector<double>> rows;  // x, z in mm
  bool projected = false;
};

// The snapshots nearest the times, each once (a note for one already drawn or far away).
std::vector<Section> pick_sections(const std::vector<Frame>& frames, std::span<const double> times,
                                   std::vector<std::string>& notes) {
  std::vector<Section> sections;
  for (const double t : times) {
    const Frame& f = nearest_frame(frames, t);
    const bool seen = std::any_of(sections.begin(), sections.end(),
                                  [&](const Section& s) { return s.frame == &f; });
    if (seen) {
      notes.push_back(
          fmt::format("t = {:.6g} s: nearest snapshot {} (t = {:.6g} s) is already drawn", t,
                      f.file.string(), f.time));
      continue;
    }
    if (std::abs(f.time - t) > 1e-4) {  // more than 0.1 ms away
      notes.push_back(fmt::format("t = {:.6g} s: nearest snapshot {} at t = {:.6g} s", t,
                                  f.file.string(), f.time));
    }
    sections.push_back({t, &f, {}, false});
  }
  return sections;
}

// The section's rows from its snapshot: the points in a slab around the plane through the middle
// of the shell, parallel to x-z, or, when too few lie there, every point projected on (signed
// distance to the axis, z).
void read_section(Section& sec, const fs::path& run_dir, std::vector<std::string>& notes) {
  const auto file = sec.frame->file.is_absolute() ? sec.frame->file : run_dir / sec.frame->file;
  const auto points = read_vtu_points(file);
  if (points.empty()) throw PlotInputError(fmt::format("{}: has no points", file.string()));
  double x0 = points[0][0], x1 = x0, y0 = points[0][1], y1 = y0;
  for (const auto& p : points) {
    x0 = std::min(x0, p[0]);
    x1 = std::max(x1, p[0]);
    y0 = std::min(y0, p[1]);
    y1 = std::max(y1, p[1]);
  }
  const double yc = 0.5 * (y0 + y1);
  const double half = 0.015 * std::max(x1 - x0, y1 - y0);
  for (const auto& p : points) {
    if (std::abs(p[1] - yc) <= half) sec.rows.push_back({p[0] * 1e3, p[2] * 1e3});
  }
  const std::size_t needed = std::max<std::size_t>(20, points.size() / 500);
  if (sec.rows.size() >= needed) return;
  sec.projected = true;
  sec.rows.clear();
  const double xc = 0.5 * (x0 + x1);
  for (const auto& p : points) {
    const double dx = p[0] - xc, dy = p[1] - yc;
    const double rho = std::copysign(std::hypot(dx, dy), dx) + xc;
    sec.rows.push_back({rho * 1e3, p[2] * 1e3});
  }
  notes.push_back(
      fmt::format("{}: few points near the plane y = {:.3g} mm; drawn projected on "
                  "(signed distance to the axis, z)",
                  file.string(), yc * 1e3));
}

// The extent of all sections' rows [mm].
struct Bounds2 {
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, zmin = xmin, zmax = -xmin;
};

Bounds2 sections_extent(const std::vector<Section>& sections) {
  Bounds2 b;
  for (const auto& sec : sections) {
    for (const auto& row : sec.rows) {
      b.xmin = std::min(b.xmin, row[0]);
      b.xmax = std::max(b.xmax, row[0]);
      b.zmin = std::min(b.zmin, row[1]);
      b.zmax = std::max(b.zmax, row[1]);
    }
  }
  return b;
}

std::string sections_script(const std::vector<Section>& sections, const fs::path& pvd,
                            const fs::path& run_dir, const FigureResult& result,
                            const FigureOptions& options) {
  const auto [xmin, xmax, zmin, zmax] = sections_extent(sections);
  std::string gp;
  gp += fmt::format(
      "# Fig. 1(c) of the paper: cross-sections of the shell, from {}.\n"
      "# Written by `snapjump plot sections`; edit and redraw with `gnuplot {}` in this folder.\n"
      "# Each block holds the mesh points (x, z in mm) of one snapshot that lie within a thin "
      "slab\n# around the plane y = y_mid (1.5 % of the shell's width on each side).\n",
      printable(pvd.string()), printable(result.script.filename().string()));
  // Equal scales on both axes: the canvas height follows the shape (plot about 850 px wide).
  const double aspect = (std::max(zmax, 0.0) - std::min(zmin, 0.0)) / std::max(xmax - xmin, 1e-9);
  const int height = static_cast<int>(std::clamp(850.0 * 1.15 * aspect + 220.0, 450.0, 1000.0));
  gp += terminal(options.format, 1200, height, result.figure, 15);
  for (std::size_t k = 0; k < sections.size(); ++k) {
    gp += fmt::format("# snapshot {} at t = {} s{}\n", printable(sections[k].frame->file.string()),
                      sections[k].frame->time,
                      sections[k].projected ? " (projected on signed distance to the axis)" : "");
    gp += datablock(fmt::format("section{}", k), "x [mm]  z [mm]", sections[k].rows);
  }
  const auto xr = style::padded(xmin, xmax, false, 0.06);
  gp += fmt::format("$plate << EOD\n{} 0\n{} 0\nEOD\n", number(xr.lo), number(xr.hi));
  gp += "set size ratio -1\n";
  gp += fmt::format("set xrange [{}:{}]\n", number(xr.lo), number(xr.hi));
  gp += "set offsets 0, 0, graph 0.08, graph 0.04\n";
  gp += "set xlabel 'x [mm]'\nset ylabel 'height above the plate z [mm]'\n";
  gp += "set key outside right top Left reverse box lc rgb '#c0c0c0'\n";
  gp += "set grid lc rgb '#e0e0e0'\n";
  gp += fmt::format(
      "set title {} noenhanced\n",
      quote(fmt::format("cross-sections of the shell, {}", run_dir.filename().string())));
  std::string plot = "plot $plate using 1:2 with lines lw 4 lc rgb 'black' title 'plate z = 0'";
  for (std::size_t k = 0; k < sections.size(); ++k) {
    plot += fmt::format(
        ", $section{} using 1:2 with points pt 7 ps 0.5 lc rgb '{}' title "
        "'t = {:.1f} ms'",
        k, style::kPalette[k % std::size(style::kPalette)], sections[k].frame->time * 1e3);
  }
  return gp + plot + "\n";
}

}  // namespace

FigureResult plot_sections(const fs::path& run_dir, std::span<const double> times,
                           const FigureOptions& options) {
  require_run_folder(run_dir);
  if (times.empty()) throw PlotInputError("--times: give at least one time, e.g. 0,0.2,0.45");
  const auto pvd = run_dir / "run.pvd";
  const auto frames = read_pvd(pvd);
  auto result = figure_paths(options, run_dir / "figures" / "sections");
  auto sections = pick_sections(frames, times, result.notes);
  for (auto& sec : sections) read_section(sec, run_dir, result.notes);
  const auto gp = sections_script(sections, pvd, run_dir, result, options);
  render(result, gp, options.gnuplot);
  return result;
}

}  // namespace snapjump::plot
