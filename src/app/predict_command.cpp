#include "app/predict_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "app/cli.hpp"
#include "config/case.hpp"
#include "io/csv.hpp"
#include "io/prediction_report.hpp"
#include "popper/reverse_snap.hpp"
#include "theory/scaling.hpp"

namespace snapjump::app {
namespace {

// The reverse snap from the axisymmetric branch, or why it is not known; never fails predict.
std::optional<popper::ReverseSnap> reverse_snap_of(const config::Case& c, std::string& why) {
  try {
    return popper::reverse_snap(c);
  } catch (const std::exception& e) {
    why = e.what();
    return std::nullopt;
  }
}

void write_reverse_snap(std::ostream& out, const std::optional<popper::ReverseSnap>& r,
                        const std::string& why, double pc, double delta_p_j) {
  if (!r) {
    fmt::print(out, "\nreverse snap: not computed ({})\n", why);
    return;
  }
  fmt::print(out, "\nreverse snap ({}; {:.1f} s)\n", r->model, r->wall_time);
  const auto row = [&](const char* label, double p) {
    if (std::isfinite(p)) {
      fmt::print(out, "  {:<42} {:>11.4g}              kPa  ({:.3f} Zoelly's p_c)\n", label,
                 p / 1e3, p / pc);
    } else {
      fmt::print(out, "  {:<42} {:>11}  not reached\n", label, "-");
    }
  };
  row("p_c    buckling suction (branch maximum)", r->p_c);
  row("p_-    lowest suction of a buckled state", r->p_minus);
  row("p_hold lowest suction holding it inverted", r->p_hold);
  if (!r->note.empty()) fmt::print(out, "  the branch stopped {}\n", r->note);
  if (std::isfinite(r->p_minus)) {
    fmt::print(out, "  {}\n",
               r->p_minus > 0.0
                   ? "monostable: without suction the inverted shell snaps back (p_- > 0)"
                   : "bistable: the inverted shell stays inverted without suction (p_- < 0)");
  }
  if (std::isfinite(r->p_hold)) {
    fmt::print(out, "  delta_p_j = {:.4g} kPa {} the fully inverted shell (p_hold = {:.4g} kPa)\n",
               delta_p_j / 1e3, delta_p_j >= r->p_hold ? "holds" : "does not hold",
               r->p_hold / 1e3);
  }
}

nlohmann::json reverse_snap_json(const std::optional<popper::ReverseSnap>& r,
                                 const std::string& why) {
  using nlohmann::json;
  if (!r) return {{"computed", false}, {"why", why}};
  const auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"computed", true},
          {"model", r->model},
          {"p_c", num(r->p_c)},
          {"p_minus", num(r->p_minus)},
          {"p_hold", num(r->p_hold)},
          {"note", r->note},
          {"monostable", std::isfinite(r->p_minus) ? json(r->p_minus > 0.0) : json(nullptr)}};
}

// A valid case can still lie where the closed forms overflow or vanish (h/R of 1e-309, with
// --allow-implausible): say which quantity, rather than print inf or nan. An end the theory gives
// no value beyond its range (NaN, Prediction::beyond_range) is not such a one.
void check_evaluated(const config::Case& c, const theory::Prediction& p) {
  const auto failed = [&](double v) {
    return std::isinf(v) || (std::isnan(v) && p.beyond_range.empty());
  };
  for (const auto& row : io::prediction_rows(p)) {
    if (failed(row.lo) || failed(row.hi)) {
      throw config::CaseError(fmt::format(
          "the case gives a non-finite {} ({} .. {}): h/R = {:.3g} and E h^2 / mg = {:.3g} lie "
          "outside what the closed forms can evaluate",
          row.key, row.lo, row.hi, c.shell.h / c.shell.R,
          c.material.E * c.shell.h * c.shell.h / c.popper.net_weight));
    }
  }
}

}  // namespace

PredictCommand::PredictCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "predict",
      "Closed-form theory for one popper: r*, e*, F*, t*, H_l, H_s, H with their bounds, and "
      "the predicted outcome (Jump / Snap / No snap); then the buckling and reverse-snap "
      "suctions from the axisymmetric model's quasi-static pressure-volume branch (a few "
      "seconds).");
  case_.add_to(*cmd_);
  cmd_->add_option("--format", format_, "output: table (for people), json or csv")
      ->check(CLI::IsMember({"table", "json", "csv"}));
  cmd_->add_flag("--no-branch", no_branch_,
                 "skip the pressure-volume branch (the closed forms only, at once)");
  cmd_->footer(
      "Values take units: --R 30mm --h 2mm --E 1.2MPa --net-weight 0.48N --phi 80deg (or\n"
      "--R 30 mm). A bare number is SI (metres, pascals, radians...), with a warning; a value no\n"
      "popper has (R of metres, E of pascals) is refused unless --allow-implausible.");
}

bool PredictCommand::parsed() const { return cmd_->parsed(); }

int PredictCommand::run(std::ostream& out, std::ostream& err) const {
  const auto& format = format_;
  const bool branch = !no_branch_;
  const auto c = case_.load(err);
  const auto p = theory::predict(c, theory::contact_constants());
  check_evaluated(c, p);
  if (!p.beyond_range.empty()) {
    fmt::print(err, "warning: the predicted outcome is unknown: {}\n", p.beyond_range);
  }
  std::string why = "--no-branch";
  const auto r = branch ? reverse_snap_of(c, why) : std::nullopt;
  if (format == "json") {
    auto doc = io::to_json(c, p);
    doc["reverse_snap"] = reverse_snap_json(r, why);
    out << doc.dump(2) << '\n';
  } else if (format == "csv") {
    io::write_csv(out, p);
    if (r) {
      for (const auto& [key, v] : {std::pair{"reverse_p_c", r->p_c},
                                   {"reverse_p_minus", r->p_minus},
                                   {"reverse_p_hold", r->p_hold}}) {
        if (std::isfinite(v)) fmt::print(out, "{},{:.10g},{:.10g},Pa\n", key, v, v);
      }
    }
  } else {
    io::write_table(out, c, p);
    write_reverse_snap(out, r, why,
                       theory::zoelly_pressure(c.material.E, c.shell.h, c.shell.R, c.material.nu),
                       theory::jump_pressure(c));
  }
  return kExitOk;
}

}  // namespace snapjump::app
