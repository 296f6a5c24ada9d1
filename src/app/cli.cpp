#include "app/cli.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "io/prediction_report.hpp"
#include "theory/scaling.hpp"

namespace snapjump::app {
namespace {

// Flags that set case keys, shared by the subcommands that read a case.
struct CaseOptions {
  std::string case_file;
  std::map<std::string, std::string> values;  // case key -> text

  void add_to(CLI::App& cmd) {
    cmd.add_option("case", case_file,
                   "case file (TOML); without it, the built-in default case (the paper's "
                   "Fig. 2(a) popper)")
        ->check(CLI::ExistingFile);
    for (const auto& k : config::quantity_keys()) {
      const auto key = fmt::format("{}.{}", k.table, k.name);
      auto help = fmt::format(
          "{} [{}], e.g. {}; {}overrides {}", k.help, units::dimension_name(k.dimension), k.example,
          k.default_text.empty() ? std::string() : fmt::format("default {}; ", k.default_text),
          key);
      cmd.add_option_function<std::string>(
             fmt::format("--{}", k.flag), [this, key](const std::string& v) { values[key] = v; },
             help)
          ->group(fmt::format("Case values ([{}])", k.table))
          ->type_name("VALUE");
    }
  }

  [[nodiscard]] config::Case load() const {
    std::vector<config::Override> overrides;
    for (const auto& k : config::quantity_keys()) {
      const auto key = fmt::format("{}.{}", k.table, k.name);
      if (const auto it = values.find(key); it != values.end()) {
        overrides.push_back({key, it->second, fmt::format("--{}", k.flag)});
      }
    }
    if (case_file.empty()) return config::default_case(overrides);
    return config::load_case_file(case_file, overrides);
  }
};

int predict(const CaseOptions& opts, const std::string& format, std::ostream& out) {
  const auto c = opts.load();
  const auto p = theory::predict(c, theory::contact_constants());
  if (format == "json") {
    io::write_json(out, c, p);
  } else if (format == "csv") {
    io::write_csv(out, p);
  } else {
    io::write_table(out, c, p);
  }
  return kExitOk;
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "snapjump: predicts and simulates how elastic shells snap and jump.\n"
      "Start with `snapjump predict` (the paper's default popper) or `snapjump predict "
      "examples/R30_h2.0.toml`."};
  app.name("snapjump");
  app.require_subcommand(1);
  app.set_version_flag("--version", "snapjump 0.1.0");

  auto* predict_cmd = app.add_subcommand(
      "predict",
      "Closed-form theory for one popper: r*, e*, F*, t*, H_l, H_s, H with their bounds, and "
      "the predicted outcome (Jump / Snap / No snap).");
  CaseOptions predict_opts;
  predict_opts.add_to(*predict_cmd);
  std::string format = "table";
  predict_cmd->add_option("--format", format, "output: table (for people), json or csv")
      ->check(CLI::IsMember({"table", "json", "csv"}));
  predict_cmd->footer(
      "Values take units: --R 30mm --h 2mm --E 1.2MPa --net-weight 0.48N --phi 80deg.\n"
      "A bare number is SI (metres, pascals, radians...).");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e, out, err);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    if (predict_cmd->parsed()) return predict(predict_opts, format, out);
  } catch (const config::CaseError& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace snapjump::app
