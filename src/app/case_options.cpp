#include "app/case_options.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <vector>

#include "config/units.hpp"

namespace snapjump::app {

void say_readings(const config::Case& c, bool allow, std::ostream& err) {
  for (const auto& w : c.bare_numbers) fmt::print(err, "warning: {}\n", w);
  if (c.implausible.empty()) return;
  if (allow) {
    for (const auto& w : c.implausible) fmt::print(err, "warning: {} (allowed)\n", w);
    return;
  }
  throw config::CaseError(fmt::format(
      "the case lies outside what a popper can plausibly be (README.md, \"Plausible values\"); "
      "--allow-implausible takes it as it is:\n  {}",
      fmt::join(c.implausible, "\n  ")));
}

void CaseOptions::add_to(CLI::App& cmd) {
  cmd.add_option("case", case_file,
                 "case file (TOML); without it, the built-in default case (the paper's "
                 "Fig. 2(a) popper)")
      ->check(CLI::ExistingFile);
  for (const auto& k : config::quantity_keys()) {
    const auto key = fmt::format("{}.{}", k.table, k.name);
    auto help = fmt::format(
        "{} [{}], e.g. {}; {}overrides {}", k.help, units::dimension_name(k.dimension), k.example,
        k.default_text.empty() ? std::string() : fmt::format("default {}; ", k.default_text), key);
    cmd.add_option_function<std::string>(
           fmt::format("--{}", k.flag), [this, key](const std::string& v) { values[key] = v; },
           help)
        ->group(fmt::format("Case values ([{}])", k.table))
        ->type_name("VALUE");
  }
  cmd.add_flag("--allow-implausible", allow_implausible,
               "take values outside what a popper can plausibly be (R or h of metres, E of "
               "pascals: README.md, \"Plausible values\") as they are, with a warning");
}

config::Case CaseOptions::load(std::ostream& err) const {
  std::vector<config::Override> overrides;
  for (const auto& k : config::quantity_keys()) {
    const auto key = fmt::format("{}.{}", k.table, k.name);
    if (const auto it = values.find(key); it != values.end()) {
      overrides.push_back({key, it->second, fmt::format("--{}", k.flag)});
    }
  }
  auto c = case_file.empty() ? config::default_case(overrides)
                             : config::load_case_file(case_file, overrides);
  say_readings(c, allow_implausible, err);
  return c;
}

}  // namespace snapjump::app
