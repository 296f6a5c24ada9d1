#include "app/run.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "app/cli.hpp"
#include "io/prediction_report.hpp"
#include "io/vtu.hpp"
#include "measure/analysis.hpp"
#include "measure/time_series.hpp"
#include "popper/popper.hpp"
#include "theory/scaling.hpp"

namespace snapjump::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A new folder: the given one must not exist or must be empty; the default one gets a suffix
// when it exists. Nothing is ever overwritten.
fs::path make_output_folder(const config::Case& c, const std::string& requested) {
  if (!requested.empty()) {
    const fs::path p(requested);
    if (fs::exists(p) && !(fs::is_directory(p) && fs::is_empty(p))) {
      throw config::CaseError(fmt::format(
          "--output {}: exists and is not an empty folder; snapjump never overwrites a run",
          p.string()));
    }
    fs::create_directories(p);
    return p;
  }
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
  std::string stem =
      c.source == "built-in default case" ? "default" : fs::path(c.source).stem().string();
  fs::path p = fs::path("runs") / fmt::format("{}-{}", stem, stamp);
  for (int k = 2; fs::exists(p); ++k)
    p = fs::path("runs") / fmt::format("{}-{}-{}", stem, stamp, k);
  fs::create_directories(p);
  return p;
}

void write_json_file(const fs::path& path, const nlohmann::json& doc) {
  const auto tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp);
    f << doc.dump(2) << '\n';
    if (!f) throw std::runtime_error(fmt::format("cannot write {}", tmp));
  }
  fs::rename(tmp, path);
}

}  // namespace

int run_simulation(const config::Case& c, const RunOptions& options, std::ostream& out,
                   std::ostream& err) {
  popper::check_simulable(c);
  const auto numerics = popper::resolve_numerics(c);
  const fs::path dir = make_output_folder(c, options.output);
  fmt::print(out, "snapjump run: {}\n  output      {}\n", c.title.empty() ? c.source : c.title,
             dir.string());
  nlohmann::json summary = {{"case", io::case_to_json(c)}, {"status", "running"}};
  write_json_file(dir / "summary.json", summary);

  const auto start = Clock::now();
  const auto wall = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  popper::Popper pop(c, numerics);
  const auto& body = pop.body();
  const auto step = mpm::choose_time_step(pop.elastic_time_step(), numerics.dx, 2.0, 0.5);
  fmt::print(out,
             "  mesh        {} ten-node tetrahedra, {} particles (element size {:.3g} mm, {} "
             "layers)\n  grid        {:.3g} mm cells\n  time step   {:.3g} us (elastic bound "
             "{:.3g} us, grid bound {:.3g} us at 2 m/s; {} limits)\n",
             body.num_elements(), body.num_nodes(), 1e3 * numerics.cap.element_size,
             numerics.cap.layers, 1e3 * numerics.dx, 1e6 * step.dt, 1e6 * step.elastic,
             1e6 * step.grid, step.limiting);
  summary["numerics"] = {{"elements", body.num_elements()},
                         {"particles", body.num_nodes()},
                         {"element_size", numerics.cap.element_size},
                         {"layers", numerics.cap.layers},
                         {"dx", numerics.dx},
                         {"dt", step.dt},
                         {"dt_elastic", step.elastic},
                         {"dt_grid", step.grid},
                         {"end_time", numerics.end_time}};

  double last_print = -1.0;
  const auto progress = [&](const std::string& phase, double t, double fraction) {
    if (options.quiet || wall() - last_print < 2.0) return;
    last_print = wall();
    fmt::print(err, "  [{:>6.1f} s] {:<14} t = {:.4f} s{}\n", wall(), phase, t,
               fraction >= 0 ? fmt::format(" ({:.0f} %)", 100 * fraction) : std::string());
  };
  const auto prep = pop.prepare(progress);
  fmt::print(out, "  prepared    {}\n", prep.message);
  summary["preparation"] = {{"inverted", prep.inverted},
                            {"held", prep.held},
                            {"buckling_pressure", prep.buckling_pressure},
                            {"delta_p_j", pop.delta_p_j()},
                            {"plate_force", prep.plate_force},
                            {"message", prep.message}};
  if (!prep.held) {
    summary["status"] = prep.inverted ? "snapped back before release" : "did not invert";
    write_json_file(dir / "summary.json", summary);
    fmt::print(out, "  result      {}\n", summary["status"].get<std::string>());
    return kExitOk;
  }

  pop.release();
  const auto columns = popper::sample_columns();
  measure::TimeSeries series(columns, true);
  measure::CsvWriter csv(dir / "series.csv", columns, true);
  csv.write_comment(fmt::format("snapjump run of {}; SI units; t = 0 at the release", c.source));
  fs::create_directories(dir / "snapshots");
  io::PvdCollection pvd(dir / "run.pvd");
  const auto snapshot = [&]() {
    const auto name = fmt::format("snapshots/frame_{:05d}.vtu", pvd.size());
    io::write_vtu(dir / name, body, pop.stepper().particles().x, pop.stepper().particles().v);
    pvd.add(pop.time(), name);
  };
  const auto record = [&]() {
    const auto s = pop.sample();
    const auto values = popper::sample_values(s);
    series.add_row(values, s.contact);
    csv.write_row(values, s.contact);
    return s;
  };
  record();
  snapshot();
  double next_sample = numerics.probe_interval, next_snapshot = numerics.snapshot_interval;
  double airborne_since = -1.0;
  std::string status = "completed";
  const double run_start = wall();
  try {
    while (pop.time() < numerics.end_time) {
      pop.step();
      if (pop.time() + 1e-12 >= next_sample) {
        next_sample += numerics.probe_interval;
        const auto s = record();
        // Stop at the apex of the flight: off the plate for 5 ms and coming down.
        if (s.contact == measure::ContactState::None && s.F == 0.0) {
          if (airborne_since < 0) airborne_since = s.t;
        } else {
          airborne_since = -1.0;
        }
        if (airborne_since >= 0 && s.t - airborne_since > 5e-3 && s.vz < 0.0) {
          status = "completed (apex of the flight)";
          break;
        }
      }
      if (pop.time() + 1e-12 >= next_snapshot) {
        next_snapshot += numerics.snapshot_interval;
        snapshot();
      }
      if (!options.quiet && wall() - last_print >= 5.0) {
        last_print = wall();
        const double rate = pop.stepper().steps() / std::max(1e-9, wall() - run_start);
        const double eta = (numerics.end_time - pop.time()) / pop.dt() / std::max(rate, 1e-9);
        fmt::print(err,
                   "  [{:>6.1f} s] release        t = {:.4f} s, {:.0f} steps/s, at most {:.0f} s "
                   "to go, delta_p = {:.0f} Pa, z = {:.2f} mm\n",
                   wall(), pop.time(), rate, eta, pop.gas().delta_p(), 1e3 * (pop.container().z));
      }
    }
  } catch (const std::exception& e) {
    status = fmt::format("failed: {}", e.what());
    fmt::print(err, "error: {}\n  what was written so far stays in {}\n", e.what(), dir.string());
  }
  snapshot();

  const auto analysis = measure::analyze(series, {}, &c);
  const auto prediction = theory::predict(c, theory::contact_constants());
  summary["status"] = status;
  summary["wall_time"] = wall();
  summary["steps"] = pop.stepper().steps();
  summary["measured"] = measure::to_json(analysis);
  summary["theory"] = io::to_json(c, prediction);
  const auto compare = [&](const char* name, const std::optional<double>& v, theory::Range r) {
    summary["comparison"][name] = {{"measured", v ? nlohmann::json(*v) : nlohmann::json(nullptr)},
                                   {"lower", r.lo},
                                   {"upper", r.hi},
                                   {"inside", v && *v >= r.lo && *v <= r.hi}};
  };
  compare("alpha_r", analysis.alpha_r, prediction.alpha.alpha_r);
  compare("alpha_e", analysis.alpha_e, prediction.alpha.alpha_e);
  compare("alpha_F", analysis.alpha_F, prediction.alpha.alpha_F);
  compare("alpha_t", analysis.alpha_t, prediction.alpha.alpha_t);
  summary["comparison"]["outcome"] = {{"simulated", measure::outcome_text(analysis.outcome)},
                                      {"predicted", prediction.outcome.text()}};
  write_json_file(dir / "summary.json", summary);

  const auto show = [&](const char* label, const std::optional<double>& v, double scale,
                        const char* unit, std::string theory) {
    fmt::print(out, "  {:<28} {:>10}  {:<4} theory {}\n", label,
               v ? fmt::format("{:.4g}", *v / scale) : std::string("-"), unit, theory);
  };
  const auto range = [](theory::Range r, double scale) {
    return fmt::format("{:.4g} .. {:.4g}", r.lo / scale, r.hi / scale);
  };
  fmt::print(out, "  status      {}\n  outcome     {} (theory: {})\n", status,
             measure::outcome_text(analysis.outcome), prediction.outcome.text());
  show("r*  contact radius", analysis.r_star, 1e-3, "mm", range(prediction.r_star, 1e-3));
  show("e*  apex displacement", analysis.e_star, 1e-3, "mm", range(prediction.e_star, 1e-3));
  show("F*  peak force", analysis.F_star, 1.0, "N", range(prediction.F_star, 1.0));
  show("t*  onset to launch", analysis.t_star, 1e-3, "ms", range(prediction.t_star, 1e-3));
  show("H_l lift to the onset", analysis.H_l, 1e-3, "mm", range(prediction.H_l, 1e-3));
  show("H_s flight from the snap", analysis.H_s, 1e-3, "mm", range(prediction.H_s, 1e-3));
  show("H   jump height", analysis.H, 1e-3, "mm", range(prediction.H, 1e-3));
  for (const auto& w : analysis.warnings) fmt::print(out, "  note        {}\n", w);
  fmt::print(out, "  files       {}/series.csv, summary.json, run.pvd ({} snapshots)\n",
             dir.string(), pvd.size());
  return status.rfind("failed", 0) == 0 ? kExitFailure : kExitOk;
}

}  // namespace snapjump::app
