#include "app/run_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <optional>

#include "config/case.hpp"
#include "config/units.hpp"

namespace snapjump::app {
namespace {

// A time given on the command line [s], its flag named in the error.
double parse_time(const std::string& text, const char* flag) {
  const units::UnitParser parser;
  try {
    return parser.parse(text, units::Dimension::Time);
  } catch (const units::UnitError& e) {
    throw config::CaseError(fmt::format("{}: {}", flag, e.what()));
  }
}

// --end-time's value given with --resume [s].
double parse_end_time(const std::string& text) {
  const double t = parse_time(text, "--end-time");
  if (!(t > 0.0 && std::isfinite(t))) {
    throw config::CaseError(fmt::format("--end-time {}: must be positive", text));
  }
  return t;
}

}  // namespace

RunCommand::RunCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "run",
      "Simulate the popper (3D MPM, or --model axisymmetric): buckle, set delta_p_j, ground, "
      "release; write the time series, a summary and ParaView snapshots into a new folder.");
  case_.add_to(*cmd_);
  cmd_->add_option("--model", model_,
                   "discretisation of the shell: 3d (the paper's MPM, the default) or "
                   "axisymmetric (finite elements on the meridian section: a reference for the 3D "
                   "model, fast enough for sweeps); overrides numerics.model")
      ->check(CLI::IsMember({"3d", "axisymmetric"}));
  cmd_->add_option("--bulk-integration", bulk_,
                   "where the elements integrate the bulk energy: full (with the rest; the 3D "
                   "default, the paper's element) or reduced (3D: at each element's centroid; "
                   "axisymmetric: 2 x 2 points, its default); overrides numerics.bulk_integration")
      ->check(CLI::IsMember({"full", "reduced"}));
  cmd_->add_option("--fan-layer", fan_layer_,
                   "axisymmetric: tile the first 1 or 2 layers of elements through h so that "
                   "every inner corner node is a crease's root (three elements at each; 0: none); "
                   "overrides numerics.fan_layer")
      ->check(CLI::Range(0, 2));
  cmd_->add_option("--inverted-snaps", snaps_,
                   "axisymmetric: how the preparation passes a maximum of the inverted segment "
                   "below delta_p_j (a crease's nucleation): \"in time\" (the default: the "
                   "suction raised from there by the dynamics) or \"along the branch\" (snapped "
                   "at constant suction onto the branch's later part and followed on it); "
                   "overrides protocol.inverted_snaps")
      ->check(CLI::IsMember({"in time", "along the branch"}));
  cmd_->add_option("--output", options_.output,
                   "folder for the results (must not exist or be empty; default "
                   "runs/<case>-<date-time>)");
  cmd_->add_option("--resolution", resolution_, "coarse, default or fine")
      ->check(CLI::IsMember({"coarse", "default", "fine"}));
  cmd_->add_flag("--quiet", options_.quiet, "no progress lines");
  cmd_->add_option("--pause-at", pause_at_,
                   "stop at this time after the release (e.g. 0.2s), leaving a checkpoint");
  cmd_->add_option("--resume", options_.resume,
                   "continue a paused, interrupted or killed run in this folder from its last "
                   "checkpoint; with --end-time, a run that went to its cap goes on to the later "
                   "one (or to the apex)")
      ->check(CLI::ExistingDirectory);
  cmd_->add_option("--reanalyze", reanalyze_,
                   "analyse the time series of a finished run in this folder again and rewrite "
                   "its summary.json (after an update of the analysis); simulates nothing")
      ->check(CLI::ExistingDirectory);
}

bool RunCommand::parsed() const { return cmd_->parsed(); }

bool RunCommand::sets_up_a_run(const std::map<std::string, std::string>& values) const {
  return !case_.case_file.empty() || !values.empty() || !resolution_.empty() || !model_.empty() ||
         !bulk_.empty() || fan_layer_ >= 0 || !snaps_.empty() || !options_.output.empty();
}

int RunCommand::run(std::ostream& out, std::ostream& err, const CliHooks& hooks) const {
  RunOptions options = options_;
  if (!pause_at_.empty()) options.pause_at = parse_time(pause_at_, "--pause-at");
  if (!reanalyze_.empty()) {
    if (sets_up_a_run(case_.values) || !options.resume.empty() || options.pause_at) {
      throw config::CaseError(
          "--reanalyze reads a finished run's folder as it is: give no case file, case "
          "values, --resolution, --model, --bulk-integration, --inverted-snaps, --output, --resume "
          "or --pause-at "
          "with it");
    }
    return reanalyze_run(reanalyze_, out);
  }
  // Ctrl-C stops the run with a checkpoint, unless the embedding program stops it itself.
  std::optional<SigintStop> sigint;
  if (hooks.stop_requested) {
    options.stop_requested = hooks.stop_requested;
  } else {
    sigint.emplace();
    options.stop_requested = [&sigint] { return sigint->requested(); };
  }
  if (!options.resume.empty()) return resume(std::move(options), out, err);
  auto c = case_.load(err);
  if (const auto r = config::parse_resolution(resolution_)) c.numerics.resolution = *r;
  if (const auto m = config::parse_model(model_)) c.numerics.model = *m;
  if (const auto b = config::parse_bulk_integration(bulk_)) c.numerics.bulk_integration = *b;
  if (fan_layer_ >= 0) c.numerics.fan_layer = fan_layer_;
  if (const auto s = config::parse_inverted_snaps(snaps_)) c.protocol.inverted_snaps = *s;
  return run_simulation(c, options, out, err);
}

int RunCommand::resume(RunOptions options, std::ostream& out, std::ostream& err) const {
  // A new cap is the one case value a resume takes.
  auto values = case_.values;
  const auto end = values.find("numerics.end_time");
  if (end != values.end()) {
    options.end_time = parse_end_time(end->second);
    values.erase(end);
  }
  if (sets_up_a_run(values)) {
    throw config::CaseError(
        "--resume continues a run as it was set up (its case.toml, its folder): give no "
        "case file, case values (but --end-time, a later cap), --resolution, --model, "
        "--bulk-integration or --output with it");
  }
  return run_simulation(config::Case{}, options, out, err);
}

}  // namespace snapjump::app
