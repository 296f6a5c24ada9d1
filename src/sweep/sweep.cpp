#include "sweep/sweep.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string_view>
#include <utility>

#include "config/files.hpp"
#include "config/text.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/run_status.hpp"
#include "theory/prefactors.hpp"
#include "theory/scaling.hpp"

namespace snapjump::sweep {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kResolutionKey = "numerics.resolution";
constexpr std::string_view kModelKey = "numerics.model";
constexpr std::string_view kBulkKey = "numerics.bulk_integration";
// The most runs a sweep holds; a range's count is held to it before its values are made.
constexpr std::int64_t kMaxRuns = 100000;

std::string at(const fs::path& file, const toml::source_region& r) {
  return fmt::format("{}:{}", file.string(), r.begin.line);
}

std::string known_keys() {
  std::string s;
  for (const auto& k : config::quantity_keys()) s += fmt::format(" {}.{}", k.table, k.name);
  s += ' ';
  s += kResolutionKey;
  s += ' ';
  s += kModelKey;
  s += ' ';
  s += kBulkKey;
  return s;
}

void check_key(const fs::path& file, const toml::source_region& r, const std::string& key) {
  if (key == kResolutionKey || key == kModelKey || key == kBulkKey ||
      config::find_quantity_key(key) != nullptr) {
    return;
  }
  throw SweepError(fmt::format("{}: unknown case key '{}'; a sweep may set or vary:{}", at(file, r),
                               text::excerpt(key), known_keys()));
}

// A scalar TOML value as case text: strings as written, numbers as bare (SI) numbers.
std::optional<std::string> scalar_text(const toml::node& n) {
  if (const auto* s = n.as_string()) return s->get();
  if (const auto* i = n.as_integer()) return fmt::format("{}", i->get());
  if (const auto* f = n.as_floating_point()) return fmt::format("{}", f->get());
  return std::nullopt;
}

// Visits the leaves of a table with dotted keys ("shell.h"), stopping at arrays and at tables
// that describe a range (they have a "from" key).
struct Leaf {
  std::string key;
  const toml::node* node;
  toml::source_region where;
};

void collect_leaves(const toml::table& t, const std::string& prefix, std::vector<Leaf>& out) {
  for (auto&& [k, node] : t) {
    const std::string key =
        prefix.empty() ? std::string(k.str()) : fmt::format("{}.{}", prefix, k.str());
    if (const auto* sub = node.as_table(); sub != nullptr && !sub->contains("from")) {
      collect_leaves(*sub, key, out);
    } else {
      out.push_back({key, &node, k.source()});
    }
  }
}

// Visits the leaves of a table in the order they are written in the file (toml++ keeps tables
// sorted by key), with dotted keys ("shell.h"); arrays and range tables (with "from") are leaves.
template <class Visit>
void for_each_leaf(const toml::table& t, Visit&& visit) {
  std::vector<Leaf> leaves;
  collect_leaves(t, "", leaves);
  std::stable_sort(leaves.begin(), leaves.end(), [](const Leaf& a, const Leaf& b) {
    return std::pair(a.where.begin.line, a.where.begin.column) <
           std::pair(b.where.begin.line, b.where.begin.column);
  });
  for (const auto& l : leaves) visit(l.key, *l.node, l.where);
}

// The values of one [vary] or [zip] entry: a list, or a range {from, to, count, scale}.
std::vector<Setting> values_of(const fs::path& file, const std::string& key, const toml::node& n,
                               const toml::source_region& where, const units::UnitParser& parser) {
  const std::string origin = at(file, where);
  std::vector<Setting> out;
  if (const auto* arr = n.as_array()) {
    for (const auto& item : *arr) {
      const auto text = scalar_text(item);
      if (!text) {
        throw SweepError(
            fmt::format("{}: {} lists values as strings with units or numbers", origin, key));
      }
      out.push_back({key, *text, origin});
    }
  } else if (const auto* range = n.as_table()) {
    const auto* spec = config::find_quantity_key(key);
    if (spec == nullptr) {
      throw SweepError(fmt::format("{}: {} cannot take a range (it is not a number)", origin, key));
    }
    const auto from = range->get("from"), to = range->get("to");
    const auto count = (*range)["count"].value<std::int64_t>();
    const std::string scale = (*range)["scale"].value_or(std::string("linear"));
    for (auto&& [rk, rv] : *range) {
      const auto name = rk.str();
      if (name != "from" && name != "to" && name != "count" && name != "scale") {
        throw SweepError(fmt::format("{}: {}: a range has from, to, count and scale, not '{}'",
                                     origin, key, text::excerpt(name)));
      }
    }
    if (from == nullptr || to == nullptr || !count || *count < 2) {
      throw SweepError(fmt::format(
          "{}: {}: a range needs from, to and count >= 2, e.g. {{ from = \"{}\", to = ..., "
          "count = 5 }}",
          origin, key, spec->example));
    }
    if (*count > kMaxRuns) {
      throw SweepError(fmt::format("{}: {}: count = {} is more runs than a sweep holds ({})",
                                   origin, key, *count, kMaxRuns));
    }
    if (scale != "linear" && scale != "log") {
      throw SweepError(fmt::format("{}: {}: scale must be \"linear\" or \"log\"", origin, key));
    }
    double a = 0, b = 0;
    try {
      a = parser.parse(scalar_text(*from).value_or(""), spec->dimension);
      b = parser.parse(scalar_text(*to).value_or(""), spec->dimension);
    } catch (const std::exception& e) {
      throw SweepError(fmt::format("{}: {}: {}", origin, key, e.what()));
    }
    if (scale == "log" && !(a > 0 && b > 0)) {
      throw SweepError(fmt::format("{}: {}: a log range needs positive ends", origin, key));
    }
    for (std::int64_t i = 0; i < *count; ++i) {
      const double s = static_cast<double>(i) / static_cast<double>(*count - 1);
      const double v = scale == "log" ? a * std::pow(b / a, s) : a + s * (b - a);
      out.push_back({key, fmt::format("{}", v), origin});  // a bare number is SI
    }
  } else {
    throw SweepError(fmt::format(
        "{}: {} must be a list of values or a range {{ from = ..., to = ..., count = ... }}",
        origin, key));
  }
  if (out.empty()) throw SweepError(fmt::format("{}: {} has no values", origin, key));
  return out;
}

using io::csv_field;

std::string num(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : std::string(); }

std::optional<nlohmann::json> read_json(const fs::path& p) {
  std::string text;
  if (text::read_file_into(p, text)) return std::nullopt;
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

// The file's text; empty when there is none.
std::string read_text(const fs::path& p) {
  std::string text;
  if (text::read_file_into(p, text)) return {};
  return text;
}

config::Case build_case(const Spec& spec, const RunPlan& run, const units::UnitParser& parser) {
  std::vector<config::Override> overrides;
  std::optional<config::Resolution> resolution;
  std::optional<config::Model> model;
  std::optional<config::BulkIntegration> bulk;
  // A string key's value as its parser reads it, or an error naming the setting and the choices.
  const auto parsed = [](const Setting& s, auto value, std::string_view choices) {
    if (!value) throw config::CaseError(fmt::format("{}: {} must be {}", s.origin, s.key, choices));
    return value;
  };
  const auto add = [&](const Setting& s) {
    if (s.key == kModelKey) {
      model = parsed(s, config::parse_model(s.text), config::kModelChoices);
    } else if (s.key == kBulkKey) {
      bulk = parsed(s, config::parse_bulk_integration(s.text), config::kBulkIntegrationChoices);
    } else if (s.key == kResolutionKey) {
      resolution = parsed(s, config::parse_resolution(s.text), config::kResolutionChoices);
    } else {
      overrides.push_back({s.key, s.text, s.origin});
    }
  };
  for (const auto& s : spec.fixed) add(s);
  for (const auto& s : run.settings) add(s);
  auto c = spec.base ? config::load_case_file(*spec.base, overrides, &parser)
                     : config::default_case(overrides, &parser);
  if (resolution) c.numerics.resolution = *resolution;
  if (model) c.numerics.model = *model;
  if (bulk) c.numerics.bulk_integration = bulk;
  if (!spec.title.empty()) {
    std::string vals;
    for (const auto& s : run.settings) vals += fmt::format(", {} = {}", s.key, s.text);
    c.title = fmt::format("{} {}{}", spec.title, run.name, vals);
  }
  return c;
}

}  // namespace

namespace {

// The values of a sweep file's [vary] and [zip] tables while it is read: per key, its values.
struct Lists {
  std::vector<std::vector<Setting>> vary, zip;
};

toml::table parse_toml(std::string_view toml_text, const fs::path& file) {
  try {
    return toml::parse(toml_text, file.string());
  } catch (const toml::parse_error& e) {
    throw SweepError(fmt::format("{}:{}: {}", file.string(), e.source().begin.line,
                                 text::library_message(e.description())));
  }
}

// A path the sweep file names (base, output), as written; it must be a string.
const std::string& path_text(const toml::node& node, const std::string& origin,
                             std::string_view what) {
  const auto* s = node.as_string();
  if (s == nullptr) throw SweepError(fmt::format("{}: {}", origin, what));
  if (text::has_control_characters(s->get())) {
    throw SweepError(
        fmt::format("{}: the path '{}' holds control characters", origin, text::excerpt(s->get())));
  }
  return s->get();
}

// One of the tables [set], [vary] and [zip] (`name`), into the spec's fixed settings or the lists.
void read_settings(const fs::path& file, const std::string& name, const toml::table& t,
                   const units::UnitParser& parser, Spec& spec, Lists& lists) {
  for_each_leaf(
      t, [&](const std::string& key, const toml::node& n, const toml::source_region& where) {
        check_key(file, where, key);
        for (const auto* varied : {&lists.vary, &lists.zip}) {
          for (const auto& values : *varied) {
            if (values.front().key == key) {
              throw SweepError(fmt::format("{}: {} is varied twice", at(file, where), key));
            }
          }
        }
        if (name == "set") {
          const auto text = scalar_text(n);
          if (!text) {
            throw SweepError(
                fmt::format("{}: [set] {} takes one value (a string with its unit or a number)",
                            at(file, where), key));
          }
          spec.fixed.push_back({key, *text, at(file, where)});
        } else {
          auto values = values_of(file, key, n, where, parser);
          (name == "vary" ? lists.vary : lists.zip).push_back(std::move(values));
        }
      });
}

// The sweep file's top-level keys: title, base, output and the tables of settings.
void read_document(const toml::table& doc, const fs::path& file, const units::UnitParser& parser,
                   Spec& spec, Lists& lists) {
  const fs::path folder = file.parent_path();
  for (auto&& [k, node] : doc) {
    const std::string name(k.str());
    const std::string origin = at(file, k.source());
    if (name == "title") {
      spec.title = text::capped_title(node.value_or(std::string()));
    } else if (name == "base") {
      spec.base = fs::absolute(folder / path_text(node, origin, "base must be a path (a string)"));
      if (!fs::is_regular_file(*spec.base)) {
        throw SweepError(
            fmt::format("{}: base case file {} does not exist", origin, spec.base->string()));
      }
    } else if (name == "output") {
      spec.output = folder / path_text(node, origin, "output must be a path");
    } else if (name == "set" || name == "vary" || name == "zip") {
      const auto* t = node.as_table();
      if (t == nullptr) throw SweepError(fmt::format("{}: [{}] must be a table", origin, name));
      read_settings(file, name, *t, parser, spec, lists);
    } else {
      throw SweepError(fmt::format(
          "{}: unknown key '{}'; a sweep file has title, base, output, [set], [vary] and [zip]",
          origin, text::excerpt(name)));
    }
  }
}

// The varied keys ([zip] first, then [vary]), once the lists are checked against each other and
// against [set].
void take_varied_keys(const fs::path& file, const Lists& lists, Spec& spec) {
  if (lists.vary.empty() && lists.zip.empty()) {
    throw SweepError(
        fmt::format("{}: nothing to vary: add a [vary] or [zip] table", file.string()));
  }
  for (const auto& z : lists.zip) {
    if (z.size() != lists.zip.front().size()) {
      throw SweepError(fmt::format("{}: [zip] lists differ in length ({} has {}, {} has {})",
                                   file.string(), lists.zip.front().front().key,
                                   lists.zip.front().size(), z.front().key, z.size()));
    }
  }
  for (const auto& z : lists.zip) spec.varied_keys.push_back(z.front().key);
  for (const auto& v : lists.vary) spec.varied_keys.push_back(v.front().key);
  for (const auto& f : spec.fixed) {
    for (const auto& v : spec.varied_keys) {
      if (v == f.key) throw SweepError(fmt::format("{}: {} is both set and varied", f.origin, v));
    }
  }
}

// The runs: the zip position outermost, then the [vary] keys, the last one fastest; held to
// kMaxRuns before any is made.
void expand_runs(const fs::path& file, const Lists& lists, Spec& spec) {
  const auto& vary = lists.vary;
  const auto& zip = lists.zip;
  const std::size_t nzip = zip.empty() ? 1 : zip.front().size();
  std::size_t nvary = 1;
  for (const auto& v : vary) {
    // Held to the cap as it grows, so that a product of several long lists cannot overflow.
    nvary *= v.size();
    if (nzip * nvary > static_cast<std::size_t>(kMaxRuns)) {
      throw SweepError(fmt::format("{}: {} runs or more is more than a sweep holds ({})",
                                   file.string(), nzip * nvary, kMaxRuns));
    }
  }
  if (nzip > static_cast<std::size_t>(kMaxRuns)) {
    throw SweepError(
        fmt::format("{}: {} runs is more than a sweep holds ({})", file.string(), nzip, kMaxRuns));
  }
  for (std::size_t z = 0; z < nzip; ++z) {
    for (std::size_t j = 0; j < nvary; ++j) {
      RunPlan r;
      r.name = fmt::format("run-{:04d}", spec.runs.size());
      for (const auto& list : zip) r.settings.push_back(list[z]);
      std::size_t rest = j;
      std::vector<Setting> vs(vary.size());
      for (std::size_t k = vary.size(); k-- > 0;) {
        vs[k] = vary[k][rest % vary[k].size()];
        rest /= vary[k].size();
      }
      for (auto& s : vs) r.settings.push_back(std::move(s));
      spec.runs.push_back(std::move(r));
    }
  }
}

}  // namespace

Spec parse_spec(std::string_view toml_text, const fs::path& file) {
  const toml::table doc = parse_toml(toml_text, file);
  const units::UnitParser parser;
  Spec spec;
  spec.file = file;
  Lists lists;
  read_document(doc, file, parser, spec, lists);
  take_varied_keys(file, lists, spec);
  expand_runs(file, lists, spec);
  if (spec.output.empty())
    spec.output = fs::path("runs") / fmt::format("sweep-{}", file.stem().string());

  // Every run's case, checked now rather than when it is its turn.
  for (const auto& r : spec.runs) {
    try {
      (void)build_case(spec, r, parser);
    } catch (const config::CaseError& e) {
      throw SweepError(fmt::format("{}: {}", r.name, e.what()));
    }
  }
  return spec;
}

Spec load_spec(const fs::path& file) {
  return parse_spec(text::read_file<SweepError>(file, "the sweep file"), file);
}

config::Case make_case(const Spec& spec, const RunPlan& run) {
  const units::UnitParser parser;
  return build_case(spec, run, parser);
}

RunPaths paths_of(const Spec& spec, const RunPlan& run) {
  return {spec.output / "cases" / fmt::format("{}.toml", run.name), spec.output / "runs" / run.name,
          spec.output / "logs" / fmt::format("{}.log", run.name),
          spec.output / "logs" / fmt::format("{}.failed", run.name)};
}

std::string_view to_string(RunState s) {
  switch (s) {
    case RunState::New:
      return "new";
    case RunState::Done:
      return "done";
    case RunState::Failed:
      return "failed";
    case RunState::Resumable:
      return "resumable";
    case RunState::Interrupted:
      return "interrupted";
  }
  return "?";
}

RunState state_of(const RunPaths& p) {
  if (const auto summary = read_json(p.dir / "summary.json")) {
    const std::string status = summary->value("status", std::string());
    if (io::run_status::finished(status)) return RunState::Done;
    if (io::run_status::failed(status)) return RunState::Failed;
  }
  if (fs::exists(p.failed)) return RunState::Failed;
  if (!fs::exists(p.dir)) return RunState::New;
  return fs::exists(p.dir / "checkpoint.bin") ? RunState::Resumable : RunState::Interrupted;
}

// An empty folder, or one that holds only a sweep's lock file (the lock is taken after the
// folder is checked and before it is prepared, so a sweep stopped in between leaves it alone).
static bool only_the_lock(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename() != "sweep.lock") return false;
  }
  return true;
}

bool resumes_after_kill(const RunPaths& p) {
  if (!fs::exists(p.dir / "checkpoint.bin")) return false;
  const auto summary = read_json(p.dir / "summary.json");
  if (!summary) return false;
  return !io::run_status::failed(summary->value("status", std::string()));
}

// plan.csv: the runs' names and varied settings, one row per run.
static std::string plan_of(const Spec& spec) {
  std::string plan = "run";
  for (const auto& k : spec.varied_keys) plan += fmt::format(",{}", k);
  plan += "\n";
  for (const auto& r : spec.runs) {
    plan += r.name;
    for (const auto& s : r.settings) plan += fmt::format(",{}", csv_field(s.text));
    plan += "\n";
  }
  return plan;
}

void check_folder(const Spec& spec) {
  const fs::path plan_file = spec.output / "plan.csv";
  if (fs::exists(plan_file)) {
    if (read_text(plan_file) != plan_of(spec)) {
      throw SweepError(fmt::format(
          "{} holds a different sweep (its plan.csv differs); give another output folder or "
          "remove that one",
          spec.output.string()));
    }
  } else if (fs::exists(spec.output) && !only_the_lock(spec.output)) {
    throw SweepError(
        fmt::format("{} exists and is not a sweep folder (no plan.csv)", spec.output.string()));
  }
}

void prepare_folder(const Spec& spec) {
  check_folder(spec);
  const std::string plan = plan_of(spec);
  const fs::path plan_file = spec.output / "plan.csv";
  fs::create_directories(spec.output / "cases");
  fs::create_directories(spec.output / "runs");
  fs::create_directories(spec.output / "logs");
  const auto write_atomic = [](const fs::path& p, const std::string& text) {
    try {
      io::write_file_atomically(p, text);
    } catch (const io::WriteFailed&) {
      throw;  // a write failure, not a bad sweep file
    } catch (const std::runtime_error& e) {
      throw SweepError(e.what());
    }
  };
  const units::UnitParser parser;
  for (const auto& r : spec.runs) {
    const auto p = paths_of(spec, r);
    if (!fs::exists(p.case_file))
      write_atomic(p.case_file, config::to_toml(build_case(spec, r, parser)));
  }
  if (!fs::exists(plan_file)) write_atomic(plan_file, plan);
}

namespace {

// What one row of sweep.csv is made from, beside the run's name, state and varied settings.
struct RowSource {
  const config::Case& c;
  const theory::Prediction& pred;
  const nlohmann::json* measured;  // the summary's "measured", or null
};

// A numeric column of sweep.csv: its header and how a row gets its value. One list makes both
// the header and the rows, so that they cannot fall out of step.
struct Column {
  std::string header;
  std::function<double(const RowSource&)> value;
};

std::vector<Column> table_columns() {
  using R = const RowSource&;
  std::vector<Column> cols = {
      {"R [m]", [](R r) { return r.c.shell.R; }},
      {"h [m]", [](R r) { return r.c.shell.h; }},
      {"phi [rad]", [](R r) { return r.c.shell.phi; }},
      {"E [Pa]", [](R r) { return r.c.material.E; }},
      {"nu [1]", [](R r) { return r.c.material.nu; }},
      {"rho [kg/m^3]", [](R r) { return r.c.material.rho; }},
      {"mu [1]", [](R r) { return r.c.friction.mu; }},
      {"net_weight [N]", [](R r) { return r.pred.net_weight; }},
      {"moving_mass [kg]", [](R r) { return r.pred.moving_mass; }},
      {"delta_p_j [Pa]", [](R r) { return r.pred.delta_p_j; }},
      {"p_c [Pa]", [](R r) { return r.pred.zoelly_pc; }},
      {"r_c [m]", [](R r) { return r.pred.r_c; }},
      {"e_c [m]", [](R r) { return r.pred.e_c; }},
      {"F_c [N]", [](R r) { return r.pred.F_c; }},
      {"t_c [s]", [](R r) { return r.pred.t_c; }},
      {"h_over_R [1]", [](R r) { return r.c.shell.h / r.c.shell.R; }},
      {"Eh2_over_mg [1]",
       [](R r) { return r.c.material.E * r.c.shell.h * r.c.shell.h / r.pred.net_weight; }},
      {"Eh4_over_mgR2 [1]",
       [](R r) {
         return r.c.material.E * std::pow(r.c.shell.h, 4) /
                (r.pred.net_weight * r.c.shell.R * r.c.shell.R);
       }},
      {"delta_p_j_over_p_c [1]", [](R r) { return r.pred.delta_p_j / r.pred.zoelly_pc; }},
  };
  // The measured quantities, then the theory's range of each.
  struct Quantity {
    const char* key;
    const char* unit;
    const theory::Range& (*range)(const theory::Prediction&);
  };
  static constexpr Quantity kQuantities[] = {
      {"r_star", "m", [](const theory::Prediction& p) -> const theory::Range& { return p.r_star; }},
      {"e_star", "m", [](const theory::Prediction& p) -> const theory::Range& { return p.e_star; }},
      {"F_star", "N", [](const theory::Prediction& p) -> const theory::Range& { return p.F_star; }},
      {"t_star", "s", [](const theory::Prediction& p) -> const theory::Range& { return p.t_star; }},
      {"H_l", "m", [](const theory::Prediction& p) -> const theory::Range& { return p.H_l; }},
      {"H_s", "m", [](const theory::Prediction& p) -> const theory::Range& { return p.H_s; }},
      {"H", "m", [](const theory::Prediction& p) -> const theory::Range& { return p.H; }},
      {"alpha_r", "1",
       [](const theory::Prediction& p) -> const theory::Range& { return p.alpha.alpha_r; }},
      {"alpha_e", "1",
       [](const theory::Prediction& p) -> const theory::Range& { return p.alpha.alpha_e; }},
      {"alpha_F", "1",
       [](const theory::Prediction& p) -> const theory::Range& { return p.alpha.alpha_F; }},
      {"alpha_t", "1",
       [](const theory::Prediction& p) -> const theory::Range& { return p.alpha.alpha_t; }},
  };
  for (const auto& q : kQuantities) {
    cols.push_back({fmt::format("{} [{}]", q.key, q.unit), [key = q.key](R r) {
                      if (r.measured && r.measured->contains("quantities") &&
                          (*r.measured)["quantities"].contains(key)) {
                        const auto& j = (*r.measured)["quantities"][key]["value"];
                        if (j.is_number()) return j.get<double>();
                      }
                      return static_cast<double>(NAN);
                    }});
  }
  for (const auto& q : kQuantities) {
    cols.push_back({fmt::format("{}_lo [{}]", q.key, q.unit),
                    [range = q.range](R r) { return range(r.pred).lo; }});
    cols.push_back({fmt::format("{}_hi [{}]", q.key, q.unit),
                    [range = q.range](R r) { return range(r.pred).hi; }});
  }
  return cols;
}

constexpr std::string_view kUndetermined = "undetermined";

// A run's outcome for the table and, when it has none, why: the analysis' reason, or that the run
// was not analysed (its status says how it ended). Never a blank outcome.
std::pair<std::string, std::string> outcome_of(const nlohmann::json* measured,
                                               const std::string& status) {
  if (measured == nullptr) {
    return {std::string(kUndetermined), fmt::format("not analysed ({})", status)};
  }
  const auto text = [&](const char* key) {
    const auto it = measured->find(key);
    return it != measured->end() && it->is_string() ? it->get<std::string>() : std::string();
  };
  if (auto outcome = text("outcome"); !outcome.empty()) return {outcome, ""};
  auto why = text("undetermined");
  if (why.empty()) why = "no reason recorded (snapjump run --reanalyze writes it)";
  return {std::string(kUndetermined), why};
}

}  // namespace

int write_table(const Spec& spec, const fs::path& csv) {
  const units::UnitParser parser;
  const auto& constants = theory::contact_constants();
  std::vector<std::string> header = {"run", "status", "outcome", "predicted_outcome"};
  std::vector<const config::KeySpec*> varied;
  for (const auto& k : spec.varied_keys) {
    const auto* ks = config::find_quantity_key(k);
    varied.push_back(ks);
    const std::string unit = ks ? std::string(units::si_unit(ks->dimension)) : "";
    header.push_back(ks ? fmt::format("{} [{}]", k, unit.empty() ? "1" : unit) : k);
  }
  const auto columns = table_columns();
  for (const auto& col : columns) header.push_back(col.header);
  header.push_back("wall_time [s]");
  header.push_back("undetermined");
  header.push_back("error");

  std::string out;
  out += fmt::format("{}", fmt::join(header, ","));
  out += "\n";
  int with_result = 0;
  for (const auto& r : spec.runs) {
    const auto p = paths_of(spec, r);
    const auto c = build_case(spec, r, parser);
    const auto pred = theory::predict(c, constants);
    const auto summary = read_json(p.dir / "summary.json");
    const auto state = state_of(p);
    std::string status = summary ? summary->value("status", std::string()) : std::string();
    std::string error;
    if (state == RunState::Failed && fs::exists(p.failed)) error = read_text(p.failed);
    if (io::run_status::failed(status)) error = status;
    if (status.empty()) status = std::string(to_string(state));
    if (io::run_status::failed(status)) status = io::run_status::kFailed;
    const nlohmann::json* m = nullptr;
    if (summary && summary->contains("measured")) m = &(*summary)["measured"];
    const auto [outcome, why] = outcome_of(m, status);
    if (outcome != kUndetermined) ++with_result;
    std::vector<std::string> row = {r.name, status, outcome, pred.outcome_text()};
    for (std::size_t k = 0; k < r.settings.size(); ++k) {
      const auto& s = r.settings[k];
      row.push_back(varied[k] ? num(parser.parse(s.text, varied[k]->dimension)) : s.text);
    }
    const RowSource source{c, pred, m};
    for (const auto& col : columns) row.push_back(num(col.value(source)));
    double wall = NAN;
    if (summary && (*summary)["wall_time"].is_number())
      wall = (*summary)["wall_time"].get<double>();
    row.push_back(num(wall));
    row.push_back(why);
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
    row.push_back(error);
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out += ',';
      out += csv_field(row[i]);
    }
    out += "\n";
  }
  try {
    io::write_file_atomically(csv, out);
  } catch (const std::runtime_error& e) {
    throw SweepError(e.what());
  }
  return with_result;
}

}  // namespace snapjump::sweep
