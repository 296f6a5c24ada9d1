#include "app/cli.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/analyze_command.hpp"
#include "app/compare_command.hpp"
#include "app/contact_command.hpp"
#include "app/design_command.hpp"
#include "app/mesh_command.hpp"
#include "app/plot_command.hpp"
#include "app/predict_command.hpp"
#include "app/run_command.hpp"
#include "app/sweep_command.hpp"
#include "config/case.hpp"
#include "config/input_error.hpp"
#include "config/units.hpp"
#include "io/atomic_file.hpp"

namespace snapjump::app {
namespace {

// Levenshtein distance, case-insensitive.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// ", did you mean X?" for the nearest of `known` within two edits of `word`, or "".
std::string suggestion(std::string_view word, const std::vector<std::string>& known,
                       std::string_view prefix) {
  std::string best;
  std::size_t best_d = 3;
  for (const auto& k : known) {
    const auto d = edit_distance(word, k);
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best.empty() ? std::string() : fmt::format("; did you mean {}{}?", prefix, best);
}

// An unknown subcommand or --option in the command line, named with a suggestion, before CLI11
// parses it (CLI11 would take `--r 30mm` as a case file "30mm" that does not exist, and
// `snapjump analyse` as no subcommand at all). Nothing when every word is known.
std::optional<std::string> unknown_word(CLI::App& app, int argc, const char* const* argv) {
  std::vector<CLI::App*> chain{&app};
  int k = 1;
  // The subcommands named first (snapjump plot series ...).
  while (k < argc) {
    const std::string_view word = argv[k];
    if (word.starts_with("-")) break;
    CLI::App* next = nullptr;
    std::vector<std::string> names;
    for (auto* sub : chain.back()->get_subcommands({})) {
      names.push_back(sub->get_name());
      if (sub->get_name() == word) next = sub;
    }
    if (next == nullptr) {
      if (names.empty()) break;  // a positional argument of the subcommand
      if (chain.size() == 1) {
        return fmt::format("unknown subcommand '{}' (the subcommands: {}){}", word,
                           fmt::join(names, ", "), suggestion(word, names, ""));
      }
      return fmt::format("unknown subcommand '{}' of '{}' (its subcommands: {}){}", word,
                         chain.back()->get_name(), fmt::join(names, ", "),
                         suggestion(word, names, ""));
    }
    chain.push_back(next);
    ++k;
  }
  std::string path;  // "snapjump plot series" less "snapjump"
  for (std::size_t j = 1; j < chain.size(); ++j) path += " " + chain[j]->get_name();
  std::vector<std::string> known;
  for (auto* level : chain) {
    for (const auto* opt : level->get_options()) {
      for (const auto& name : opt->get_lnames()) known.push_back(name);
    }
  }
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word == "--") break;  // what follows is positional, whatever it looks like
    if (!word.starts_with("--")) continue;
    const auto eq = word.find('=');
    const auto name = word.substr(2, eq == std::string_view::npos ? eq : eq - 2);
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    return fmt::format("unknown option --{} for 'snapjump{}'{}", name, path,
                       suggestion(name, known, "--"));
  }
  return std::nullopt;
}

// The flags besides the case keys' that take a quantity with a unit.
constexpr std::array<std::string_view, 4> kOtherQuantityFlags = {"pause-at", "force-threshold",
                                                                 "force-offset", "settle-time"};

bool takes_quantity(std::string_view flag) {
  for (const auto& k : config::quantity_keys()) {
    if (k.dimension != units::Dimension::Dimensionless && flag == k.flag) return true;
  }
  return std::find(kOtherQuantityFlags.begin(), kOtherQuantityFlags.end(), flag) !=
         kOtherQuantityFlags.end();
}

// The command line with `--R 40 mm` read as `--R "40 mm"`: a bare number after a quantity's flag
// (or in --R=40) and the word after it, when that is a unit the database knows and no file, are
// one value. Otherwise CLI11 would take the unit for the positional argument, the case file.
std::vector<std::string> with_units_joined(int argc, const char* const* argv) {
  std::vector<std::string> args(argv, argv + argc);
  std::optional<units::UnitParser> parser;  // loaded only where a word may be a unit
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string_view word = args[i];
    if (word == "--") break;  // what follows is positional
    if (!word.starts_with("--")) continue;
    const auto eq = word.find('=');
    if (!takes_quantity(word.substr(2, eq == std::string_view::npos ? eq : eq - 2))) continue;
    const std::size_t value = eq == std::string_view::npos ? i + 1 : i;  // the number's word
    if (value + 1 >= args.size()) continue;
    const std::string number = eq == std::string_view::npos ? args[value] : args[i].substr(eq + 1);
    const std::string unit = args[value + 1];
    std::error_code ec;
    if (!units::is_bare_number(number) || unit.starts_with("-") ||
        std::filesystem::exists(unit, ec)) {
      continue;
    }
    if (!parser) parser.emplace();
    if (!parser->is_unit(unit)) continue;
    args[value] += " " + unit;
    args.erase(args.begin() + static_cast<std::ptrdiff_t>(value + 1));
  }
  return args;
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            const CliHooks& hooks) {
  CLI::App app{
      "snapjump: predicts and simulates how elastic shells snap and jump.\n"
      "Start with `snapjump predict` (the theory for the paper's default popper), then "
      "`snapjump run` (its simulated jump; wall time: docs/performance.md)."};
  app.name("snapjump");
  app.require_subcommand(1);
  app.set_version_flag("--version", "snapjump 0.1.0");
  // The subcommands, in the order of the help text.
  PredictCommand predict_cmd(app);
  ContactCommand contact_cmd(app);
  AnalyzeCommand analyze_cmd(app);
  MeshCommand mesh_cmd(app);
  RunCommand run_cmd(app);
  SweepCommand sweep_cmd(app);
  PlotCommand plot_cmd(app);
  CompareCommand compare_cmd(app);
  DesignCommand design_cmd(app);

  const auto args = with_units_joined(argc, argv);
  std::vector<const char*> words;
  for (const auto& a : args) words.push_back(a.c_str());
  const int count = static_cast<int>(words.size());
  if (const auto unknown = unknown_word(app, count, words.data())) {
    fmt::print(err, "error: {}\nRun with --help for more information.\n", *unknown);
    return kExitBadInput;
  }
  try {
    app.parse(count, words.data());
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e, out, err);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    if (predict_cmd.parsed()) return predict_cmd.run(out, err);
    if (contact_cmd.parsed()) return contact_cmd.run(out, err);
    if (analyze_cmd.parsed()) return analyze_cmd.run(out, err);
    if (mesh_cmd.parsed()) return mesh_cmd.run(out, err);
    if (sweep_cmd.parsed()) return sweep_cmd.run(out, err);
    if (plot_cmd.parsed()) return plot_cmd.run(out, err);
    if (compare_cmd.parsed()) return compare_cmd.run(out, err);
    if (design_cmd.parsed()) return design_cmd.run(out, err);
    if (run_cmd.parsed()) return run_cmd.run(out, err, hooks);
  } catch (const io::WriteFailed& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitWriteFailed;
  } catch (const InputError& e) {  // a case, a unit, a series, a mesh, a sweep file, a figure
    fmt::print(err, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    const auto subcommands = app.get_subcommands();
    const auto doing =
        fmt::format("running snapjump {}",
                    subcommands.empty() ? std::string() : subcommands.front()->get_name());
    fmt::print(err, "error: {}\n", error_text(e, doing));
    return kExitFailure;
  }
  return kExitOk;
}

std::string error_text(const std::exception& e, std::string_view doing) {
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr) {
    return fmt::format(
        "out of memory while {} (an input asks for more memory than the machine has left)", doing);
  }
  return e.what();
}

}  // namespace snapjump::app
