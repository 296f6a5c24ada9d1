#include "app/design_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <vector>

#include "app/cli.hpp"
#include "app/option_values.hpp"
#include "app/sweep_command.hpp"
#include "io/atomic_file.hpp"
#include "io/folder_lock.hpp"
#include "plot/design_figure.hpp"
#include "popper/reverse_snap.hpp"
#include "sweep/sweep.hpp"
#include "theory/design.hpp"
#include "theory/prefactors.hpp"

namespace snapjump::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// "50mm" (at least) or "40mm..60mm" (within).
theory::Target target(const units::UnitParser& parser, const std::string& text, units::Dimension d,
                      const char* flag) {
  const auto dots = text.find("..");
  if (dots == std::string::npos) return {positive_option(parser, text, d, flag), std::nullopt};
  theory::Target t{positive_option(parser, text.substr(0, dots), d, flag),
                   positive_option(parser, text.substr(dots + 2), d, flag)};
  if (*t.hi < t.lo) {
    throw config::CaseError(fmt::format("{} {}: write the smaller end first", flag, text));
  }
  return t;
}

struct Row {
  theory::Design d;
  std::optional<popper::ReverseSnap> reverse;
  std::string reverse_why;
};

json range_json(const theory::Range& r) { return {{"lower", r.lo}, {"upper", r.hi}}; }

json row_json(const Row& r) {
  const auto& p = r.d.prediction;
  json j = {{"R", r.d.R},
            {"h", r.d.h},
            {"net_weight", r.d.net_weight},
            {"footprint", r.d.footprint},
            {"shell_mass", p.shell_mass},
            {"zoelly_pc", p.zoelly_pc},
            {"delta_p_j", p.delta_p_j},
            {"H", range_json(p.H)},
            {"H_s", range_json(p.H_s)},
            {"F_star", range_json(p.F_star)},
            {"t_star", range_json(p.t_star)},
            {"jump_margin", range_json(p.jump_margin)},
            {"stored_energy", p.inverted_energy},
            {"outcome", p.outcome_text()},
            {"slack", r.d.slack},
            {"binding", r.d.binding}};
  if (r.reverse) {
    j["reverse_snap"] = {
        {"p_minus", r.reverse->p_minus},
        {"p_hold", r.reverse->p_hold},
        {"holds_at_delta_p_j",
         std::isfinite(r.reverse->p_hold) ? json(p.delta_p_j >= r.reverse->p_hold) : json(nullptr)},
        {"model", r.reverse->model}};
  } else {
    j["reverse_snap"] = {{"computed", false}, {"why", r.reverse_why}};
  }
  return j;
}

void write_table(std::ostream& out, const std::vector<Row>& rows, const theory::DesignResult& res,
                 const std::string& rank) {
  fmt::print(out, "  {:>3} {:>7} {:>6} {:>6} {:>9} {:>7} {:>7} {:>15} {:>13} {:>7} {:>16}\n", "#",
             "R mm", "h mm", "mg N", "rim 2a mm", "mass g", "p_c kPa", "H mm (bounds)", "F* N",
             "F*/mg >", "holds at dp_j");
  int k = 0;
  for (const auto& r : rows) {
    const auto& p = r.d.prediction;
    std::string holds = "-";
    if (r.reverse && std::isfinite(r.reverse->p_hold)) {
      holds = fmt::format("{} ({:.3g} kPa)", p.delta_p_j >= r.reverse->p_hold ? "yes" : "NO",
                          r.reverse->p_hold / 1e3);
    }
    fmt::print(out,
               "  {:>3} {:>7.3f} {:>6.3f} {:>6.3g} {:>9.3f} {:>7.3g} {:>7.3g} {:>15} {:>13} "
               "{:>7.3g} {:>16}\n",
               ++k, 1e3 * r.d.R, 1e3 * r.d.h, r.d.net_weight, 1e3 * r.d.footprint,
               1e3 * p.shell_mass, p.zoelly_pc / 1e3,
               fmt::format("{:.4g}-{:.4g}", 1e3 * p.H.lo, 1e3 * p.H.hi),
               fmt::format("{:.3g}-{:.3g}", p.F_star.lo, p.F_star.hi), p.jump_margin.lo, holds);
  }
  k = 0;
  for (const auto& r : rows) {
    ++k;
    if (!r.reverse && r.reverse_why != "--no-branch") {
      fmt::print(out, "  #{}: reverse snap not computed: {}\n", k, r.reverse_why);
    } else if (r.reverse && !std::isfinite(r.reverse->p_hold)) {
      fmt::print(out,
                 "  #{}: the axisymmetric branch reaches no fully inverted state{}: this model "
                 "cannot verify it (try --model 3d)\n",
                 k, r.reverse->note.empty() ? "" : " (" + r.reverse->note + ")");
    }
  }
  fmt::print(out, "  ranked by {}; {} designs predicted\n", rank, res.evaluated);
  if (res.pareto.size() > 1) {
    fmt::print(out, "\ntrade-off: the smallest footprint for each height (lower bounds)\n");
    fmt::print(out, "  {:>9} {:>9} {:>7} {:>6} {:>6}\n", "rim 2a mm", "H >= mm", "R mm", "h mm",
               "mg N");
    const std::size_t step = std::max<std::size_t>(1, res.pareto.size() / 10);
    for (std::size_t i = 0; i < res.pareto.size(); i += step) {
      const auto& d = res.pareto[i];
      fmt::print(out, "  {:>9.3f} {:>9.4g} {:>7.3f} {:>6.3f} {:>6.3g}\n", 1e3 * d.footprint,
                 1e3 * d.prediction.H.lo, 1e3 * d.R, 1e3 * d.h, d.net_weight);
    }
  }
}

void write_csv(std::ostream& out, const std::vector<Row>& rows) {
  fmt::print(out,
             "rank,R,h,net_weight,footprint,shell_mass,zoelly_pc,delta_p_j,H_lo,H_hi,F_star_lo,"
             "F_star_hi,jump_margin_lo,stored_energy,outcome,p_hold\n");
  int k = 0;
  for (const auto& r : rows) {
    const auto& p = r.d.prediction;
    fmt::print(out,
               "{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},"
               "{:.6g},{:.6g},{:.6g},{},{}\n",
               ++k, r.d.R, r.d.h, r.d.net_weight, r.d.footprint, p.shell_mass, p.zoelly_pc,
               p.delta_p_j, p.H.lo, p.H.hi, p.F_star.lo, p.F_star.hi, p.jump_margin.lo,
               p.inverted_energy, p.outcome_text(),
               r.reverse && std::isfinite(r.reverse->p_hold)
                   ? fmt::format("{:.6g}", r.reverse->p_hold)
                   : "");
  }
}

}  // namespace

DesignCommand::DesignCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "design",
      "From targets for a jump to the spherical caps (R, h) that meet them by the theory's lower "
      "bounds, within a footprint, the thinnest wall and the pump's suction; the material, phi, "
      "the protocol and the apparatus come from the case (docs/design.md). --verify N simulates "
      "the N best.");
  base_.add_to(*cmd_);
  cmd_->add_option("--jump-height", height_,
                   "jump height H: at least this (50mm), or within a range (40mm..60mm)")
      ->group("Targets");
  cmd_->add_option("--peak-force", force_, "peak force F*: at least this, or a range")
      ->group("Targets");
  cmd_->add_option("--margin", margin_, "F* / mg at least this (default 1: a sure jump)")
      ->group("Targets");
  cmd_->add_option("--energy", energy_, "stored energy of the inverted shell at least this (1mJ)")
      ->group("Targets");
  cmd_->add_option("--t-star-max", t_star_, "t* (the apex's touch-down to the launch) at most")
      ->group("Targets");
  cmd_->add_option("--net-weight-max", net_weight_max_,
                   "search the net weight from the case's (--net-weight) up to this")
      ->group("Constraints");
  cmd_->add_option("--footprint", footprint_, "the rim's diameter 2 R sin(phi) at most (100mm)")
      ->group("Constraints");
  cmd_->add_option("--min-h", min_h_, "the thinnest wall that can be made (0.5mm)")
      ->group("Constraints");
  cmd_->add_option("--max-h-over-R", max_h_over_R_,
                   "the thickest shell searched, h / R (0.1, the paper's thickest; at most 0.18)")
      ->group("Constraints");
  cmd_->add_option("--max-suction", suction_,
                   "the pump's largest suction: Zoelly's p_c must not exceed it (e.g. 20kPa)")
      ->group("Constraints");
  cmd_->add_option("--rank", rank_,
                   "smallest (footprint), lightest (shell), margin (F*/mg) or highest (H)")
      ->check(CLI::IsMember({"smallest", "lightest", "margin", "highest"}));
  cmd_->add_option("--count", count_, "how many designs to list (5)")->check(CLI::Range(1, 100));
  cmd_->add_option("--grid", grid_, "search points per dimension (120)")
      ->check(CLI::Range(2, 2000));
  cmd_->add_option("--format", format_, "table, csv or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  cmd_->add_option("--figure", figure_,
                   "draw the searched designs in the Fig. 3(c) plane (h/R against E h^2/mg) into "
                   "this image (.png or .svg)");
  cmd_->add_flag("--no-branch", no_branch_,
                 "skip each listed design's reverse snap (whether delta_p_j holds it inverted)");
  cmd_->add_option("--verify", verify_, "simulate the N best designs (a sweep in --output)")
      ->check(CLI::Range(1, 100))
      ->group("Verification");
  cmd_->add_option("--model", model_, "for --verify: axisymmetric (default) or 3d")
      ->check(CLI::IsMember({"axisymmetric", "3d"}))
      ->group("Verification");
  cmd_->add_option("--resolution", resolution_, "for --verify: coarse, default or fine")
      ->check(CLI::IsMember({"coarse", "default", "fine"}))
      ->group("Verification");
  cmd_->add_option("--output", output_, "for --verify: the folder (runs/design)")
      ->group("Verification");
  cmd_->add_option("--jobs", jobs_, "for --verify: runs at a time (default: the cores)")
      ->check(CLI::PositiveNumber)
      ->group("Verification");
}

bool DesignCommand::parsed() const { return cmd_->parsed(); }

namespace {

std::string toml_list(const std::vector<Row>& rows, int n, double (*get)(const theory::Design&),
                      const char* unit, double scale) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) {
    s += fmt::format("{}\"{:.6g} {}\"", i > 0 ? ", " : "",
                     get(rows[static_cast<std::size_t>(i)].d) / scale, unit);
  }
  return s + "]";
}

// The simulated quantity `key` of a finished run's summary, or nothing.
std::optional<double> simulated(const json& summary, const char* key) {
  const auto* q = summary.contains("measured") ? &summary["measured"]["quantities"] : nullptr;
  if (q == nullptr || !q->contains(key) || !(*q)[key]["value"].is_number()) return std::nullopt;
  return (*q)[key]["value"].get<double>();
}

}  // namespace

namespace {

struct VerifyOptions {
  int count;
  std::string model, resolution, output;
  int jobs;
};

// The sweep that simulates the first `o.count` designs: DIR/base.toml (the case) and
// DIR/verify.toml (the designs' R, h and net weight, zipped), its runs in DIR/sweep; run here
// (again: it resumes; `snapjump sweep DIR/verify.toml` under MPI runs the same).
sweep::Spec write_verification(const config::Case& base, const std::vector<Row>& rows,
                               const VerifyOptions& o) {
  const fs::path dir = o.output;
  fs::create_directories(dir);
  io::write_file_atomically(dir / "base.toml", config::to_toml(base));
  const int n = std::min<int>(o.count, static_cast<int>(rows.size()));
  const std::string text = fmt::format(
      "# Written by snapjump design --verify: the {} best designs, simulated.\n"
      "title = \"design verification\"\nbase = \"base.toml\"\noutput = \"sweep\"\n"
      "[set]\nnumerics.model = \"{}\"\nnumerics.resolution = \"{}\"\n"
      "[zip]\nshell.R = {}\nshell.h = {}\npopper.net_weight = {}\n",
      n, o.model, o.resolution,
      toml_list(
          rows, n, [](const theory::Design& d) { return d.R; }, "mm", 1e-3),
      toml_list(
          rows, n, [](const theory::Design& d) { return d.h; }, "mm", 1e-3),
      toml_list(
          rows, n, [](const theory::Design& d) { return d.net_weight; }, "N", 1.0));
  io::write_file_atomically(dir / "verify.toml", text);
  return sweep::load_spec(dir / "verify.toml");
}

int verify(const config::Case& base, const std::vector<Row>& rows, const theory::DesignTargets& t,
           const VerifyOptions& o, std::ostream& out) {
  const auto spec = write_verification(base, rows, o);
  fmt::print(out, "\nverification: {} designs, {} model at the {} preset\n", spec.runs.size(),
             o.model, o.resolution);
  sweep::check_folder(spec);
  fs::create_directories(spec.output);
  int status = kExitOk;
  {
    const io::FolderLock lock(spec.output, "sweep.lock", "the sweep folder");
    sweep::prepare_folder(spec);
    sweep::ExecOptions exec;
    exec.executable = sweep::self_executable();
    status = run_here(spec, exec, o.jobs, false, out);
  }
  fmt::print(out, "  {:>3} {:>9} {:>15} {:>8} {:>13} {:>8}  {}\n", "#", "outcome", "H mm (bounds)",
             "H sim", "F* N (bounds)", "F* sim", "meets the targets");
  bool all_met = true;
  for (std::size_t i = 0; i < spec.runs.size(); ++i) {
    const auto& p = rows[i].d.prediction;
    std::ifstream in(sweep::paths_of(spec, spec.runs[i]).dir / "summary.json");
    json summary = json::object();
    if (in) summary = json::parse(in, nullptr, false);
    if (summary.is_discarded()) summary = json::object();
    const std::string outcome =
        summary.contains("measured") && summary["measured"]["outcome"].is_string()
            ? summary["measured"]["outcome"].get<std::string>()
            : std::string("no result");
    const auto H = simulated(summary, "H");
    auto F = simulated(summary, "F_star_plate");
    if (!F) F = simulated(summary, "F_star");
    std::vector<std::string> misses;
    if (outcome != "Jump") misses.push_back("not a Jump");
    if (t.H && (!H || *H < t.H->lo || (t.H->hi && *H > *t.H->hi))) misses.push_back("H");
    if (t.F_star && (!F || *F < t.F_star->lo || (t.F_star->hi && *F > *t.F_star->hi))) {
      misses.push_back("F*");
    }
    all_met = all_met && misses.empty();
    const auto show = [](const std::optional<double>& v, double scale) {
      return v ? fmt::format("{:.4g}", *v / scale) : std::string("-");
    };
    fmt::print(
        out, "  {:>3} {:>9} {:>15} {:>8} {:>13} {:>8}  {}\n", i + 1, outcome,
        fmt::format("{:.4g}-{:.4g}", 1e3 * p.H.lo, 1e3 * p.H.hi), show(H, 1e-3),
        fmt::format("{:.3g}-{:.3g}", p.F_star.lo, p.F_star.hi), show(F, 1.0),
        misses.empty() ? std::string("yes") : fmt::format("MISSES: {}", fmt::join(misses, ", ")));
  }
  fmt::print(out, "  runs in {}; F* simulated through the paper's 170 Hz plate\n",
             spec.output.string());
  if (status != kExitOk) return status;
  return all_met ? kExitOk : kExitFailure;
}

}  // namespace

namespace {

// The design figure, or a warning when gnuplot fails; returns the line that says where it is.
std::string draw(const theory::DesignResult& res, const std::string& file, std::ostream& err) {
  const auto fo = plot::options_for_image(file, "--figure");
  try {
    const auto r = plot::plot_design(res, res.designs.front().prediction.alpha.alpha_F, fo);
    return fmt::format("figure {} (script {})", r.figure.string(), r.script.string());
  } catch (const plot::PlotError& e) {
    fmt::print(err, "warning: the figure could not be drawn: {}\n", e.what());
    return {};
  }
}

}  // namespace

int DesignCommand::run(std::ostream& out, std::ostream& err) const {
  const auto base = base_.load(err);
  const units::UnitParser parser;
  theory::DesignTargets t;
  if (!height_.empty()) t.H = target(parser, height_, units::Dimension::Length, "--jump-height");
  if (!force_.empty()) t.F_star = target(parser, force_, units::Dimension::Force, "--peak-force");
  if (!(margin_ > 0.0)) throw config::CaseError("--margin must be positive");
  t.margin = margin_;
  if (!energy_.empty()) {
    t.energy = positive_option(parser, energy_, units::Dimension::Energy, "--energy");
  }
  if (!t_star_.empty())
    t.t_star = positive_option(parser, t_star_, units::Dimension::Time, "--t-star-max");
  theory::DesignSpace s;
  s.net_weight_lo = s.net_weight_hi = base.popper.net_weight;
  if (!net_weight_max_.empty()) {
    s.net_weight_hi =
        positive_option(parser, net_weight_max_, units::Dimension::Force, "--net-weight-max");
  }
  s.max_footprint = positive_option(parser, footprint_, units::Dimension::Length, "--footprint");
  s.min_h = positive_option(parser, min_h_, units::Dimension::Length, "--min-h");
  if (!suction_.empty()) {
    s.max_suction = positive_option(parser, suction_, units::Dimension::Pressure, "--max-suction");
  }
  s.max_h_over_R = max_h_over_R_;
  s.grid = grid_;
  const auto rank = *theory::parse_rank(rank_);
  const auto res = theory::design(base, t, s, rank, count_);
  if (res.designs.empty()) throw config::CaseError("design: " + res.infeasible);

  std::string figure_line;
  if (!figure_.empty()) figure_line = draw(res, figure_, err);
  std::vector<Row> rows;
  for (const auto& d : res.designs) {
    Row r{d, std::nullopt, "--no-branch"};
    if (!no_branch_) {
      try {
        r.reverse = popper::reverse_snap(theory::design_case(base, d.R, d.h, d.net_weight));
      } catch (const std::exception& e) {
        r.reverse_why = e.what();
      }
    }
    rows.push_back(std::move(r));
  }
  if (format_ == "json") {
    json j = {{"units", "SI"}, {"rank", theory::to_string(rank)}, {"evaluated", res.evaluated}};
    j["designs"] = json::array();
    for (const auto& r : rows) j["designs"].push_back(row_json(r));
    j["pareto"] = json::array();
    for (const auto& d : res.pareto) {
      j["pareto"].push_back({{"footprint", d.footprint},
                             {"H_lower", d.prediction.H.lo},
                             {"R", d.R},
                             {"h", d.h},
                             {"net_weight", d.net_weight}});
    }
    out << j.dump(2) << '\n';
  } else if (format_ == "csv") {
    write_csv(out, rows);
  } else {
    fmt::print(out,
               "snapjump design: E = {:.4g} MPa, nu = {:.3g}, phi = {:.4g} deg, delta_p_j as the "
               "case gives it; the theory's lower bounds meet every target\n",
               base.material.E / 1e6, base.material.nu, base.shell.phi * 180.0 / std::numbers::pi);
    write_table(out, rows, res, theory::to_string(rank));
    if (!figure_line.empty()) fmt::print(out, "  {}\n", figure_line);
  }
  if (verify_ > 0) {
    return verify(base, rows, t, {verify_, model_, resolution_, output_, jobs_}, out);
  }
  return kExitOk;
}

}  // namespace snapjump::app
