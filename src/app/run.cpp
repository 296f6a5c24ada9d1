#include "app/run.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <fmt/ranges.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string_view>

#include "app/checkpoint.hpp"
#include "app/cli.hpp"
#include "app/preparation_hints.hpp"
#include "config/text.hpp"
#include "config/units.hpp"
#include "fem/surface_instability.hpp"
#include "io/atomic_file.hpp"
#include "io/folder_lock.hpp"
#include "io/prediction_report.hpp"
#include "io/run_status.hpp"
#include "io/vtu.hpp"
#include "measure/analysis.hpp"
#include "measure/bounds_check.hpp"
#include "measure/time_series.hpp"
#include "plot/figures.hpp"
#include "popper/material.hpp"
#include "popper/popper.hpp"
#include "popper/reverse_snap.hpp"
#include "theory/scaling.hpp"

namespace snapjump::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Set by the SIGINT handler, read by SigintStop::requested. A signal handler gets no argument
// through which it could reach an object of the run's, so what it tells the run must be an object
// of static storage, and the one such object a handler may write and the program read back
// without lock-free atomics is a volatile std::sig_atomic_t. Only SigintStop touches it.
volatile std::sig_atomic_t g_sigint = 0;

// Async-signal-safe: one store, nothing else (no allocation, no I/O, no lock). The run sees the
// flag in its loop and stops there.
void note_sigint(int /*signal*/) { g_sigint = 1; }

// dir as one word of a shell command line: as it is when it holds only safe characters, quoted
// otherwise.
std::string shell_word(const fs::path& dir) {
  const std::string s = dir.string();
  const bool safe = !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) ||
           std::string_view("/._-+:=@,").find(ch) != std::string_view::npos;
  });
  if (safe) return s;
  std::string quoted = "'";
  for (const char ch : s) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return quoted + "'";
}

// The command that continues the run in dir.
std::string resume_command(const fs::path& dir) {
  return "snapjump run --resume " + shell_word(dir);
}

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
  // Values changed by flags go into the name (h2mm, mu0.6), so that the folder does not name
  // the case file's popper alone.
  for (const auto& [key, text] : c.overridden) {
    std::string part = key.substr(key.find('.') + 1);
    for (const char ch : text) {
      if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-') part += ch;
    }
    if (stem.size() + part.size() < 80) stem += "-" + part;
  }
  fs::path p = fs::path("runs") / fmt::format("{}-{}", stem, stamp);
  for (int k = 2; fs::exists(p); ++k)
    p = fs::path("runs") / fmt::format("{}-{}-{}", stem, stamp, k);
  fs::create_directories(p);
  return p;
}

void write_json_file(const fs::path& path, const nlohmann::json& doc) {
  io::write_file_atomically(path, doc.dump(2) + "\n");
}

void print_numerics(std::ostream& out, const popper::Popper& pop) {
  out << pop.model().report().describe();
  // What the model assumes where the paper is silent (docs/popper.md, "Assumptions").
  const auto& c = pop.input();
  fmt::print(out,
             "  apparatus   popper {:.4g} g, counterweight {:.4g} g, inertia {:.4g} g ({} wire); "
             "t_c uses the inertia\n  gas         container {:.4g} mL; reference: the undeformed "
             "popper at p0 ({:.4g} mL)\n",
             1e3 * c.popper.mass, 1e3 * c.popper.counterweight(), 1e3 * c.popper.moving_mass(),
             c.popper.wire_stiffness ? fmt::format("{:.4g} N/m", *c.popper.wire_stiffness)
                                     : std::string("rigid"),
             1e6 * c.gas.container_volume, 1e6 * pop.gas().V_ref());
  if (!c.defaults_used.empty()) {
    fmt::print(out, "  assumed     {}\n", fmt::join(c.defaults_used, "; "));
  }
  const double cap = pop.numerics().end_time;
  if (c.numerics.end_time) {
    fmt::print(out,
               "  end         the apex of the flight, at most {:.6g} s after the release "
               "(numerics.end_time)\n",
               cap);
  } else {
    const auto d = popper::default_end(c);
    // Beyond the theory's range (theory::Prediction::beyond_range) it may give no highest H.
    const auto height = std::isfinite(d.height) ? fmt::format("{:.3g} mm", 1e3 * d.height)
                                                : std::string("none beyond its range");
    fmt::print(out,
               "  end         the apex of the flight, at most {:.4g} s after the release: {} x "
               "{:.3g} s, the valve's refill of the cavity at delta_p_j, + 2 x {:.3g} s, the rise "
               "to the theory's highest H, {} (numerics.end_time sets another cap)\n",
               cap, popper::kRefillsBeforeTheCap, d.refill, d.rise, height);
  }
}

// The end rule in the summary: where the run stops, and where its cap comes from.
nlohmann::json end_json(const config::Case& c, double cap) {
  return {{"rule", "the apex of the flight, at most the cap"},
          {"cap", cap},
          {"cap_from", c.numerics.end_time ? "numerics.end_time" : "default"}};
}

// A record that ends at the cap stops before the apex (or before any flight): its H and H_s are
// lower bounds whatever its last samples show, and the analysis says so.
void note_lower_bounds(measure::Analysis& a, const measure::TimeSeries& series) {
  const std::string_view said = "H and H_s are lower bounds";
  if (std::none_of(a.warnings.begin(), a.warnings.end(),
                   [&](const std::string& w) { return w.find(said) != std::string::npos; })) {
    a.warnings.push_back(
        fmt::format("the run stopped at its cap, t = {:.6g} s, before the apex of the flight: {}",
                    series.empty() ? 0.0 : series.time().back(), said));
  }
}

// summary.json's comparison: each measured prefactor beside its bounds, the outcomes, and the
// prefactors far from their bounds with their likely causes (also returned, to print).
std::vector<measure::FarFromBounds> compare_with_theory(nlohmann::json& comparison,
                                                        const measure::Analysis& analysis,
                                                        const theory::Prediction& prediction) {
  const auto compare = [&](const char* name, const std::optional<double>& v, theory::Range r) {
    comparison[name] = {{"measured", v ? nlohmann::json(*v) : nlohmann::json(nullptr)},
                        {"lower", r.lo},
                        {"upper", r.hi},
                        {"inside", v && *v >= r.lo && *v <= r.hi}};
  };
  compare("alpha_r", analysis.alpha_r, prediction.alpha.alpha_r);
  compare("alpha_e", analysis.alpha_e, prediction.alpha.alpha_e);
  compare("alpha_F", analysis.alpha_F, prediction.alpha.alpha_F);
  compare("alpha_t", analysis.alpha_t, prediction.alpha.alpha_t);
  comparison["outcome"] = {{"simulated", measure::outcome_text(analysis.outcome)},
                           {"predicted", prediction.outcome_text()}};
  auto far = measure::far_from_bounds(analysis, prediction.alpha);
  comparison["warnings"] = nlohmann::json::array();
  for (const auto& f : far) {
    comparison[f.quantity]["far_from_bounds"] = {
        {"factor", f.factor}, {"above", f.above}, {"likely_cause", f.cause}};
    comparison["warnings"].push_back(f.text());
  }
  return far;
}

// Analyses the run's time series, puts the measured quantities, the theory's and their
// comparison into the summary, writes it and prints the results.
measure::Analysis write_results(const fs::path& dir, nlohmann::json& summary, const config::Case& c,
                                const measure::TimeSeries& series, const std::string& status,
                                std::ostream& out) {
  // F also as the paper's force plate would have recorded it (F_star_plate, alpha_F_plate).
  measure::AnalysisOptions options;
  options.plate_frequency = measure::kPaperPlateFrequency;
  auto analysis = measure::analyze(series, options, &c);
  const bool capped = io::run_status::capped(status);
  if (capped) note_lower_bounds(analysis, series);
  const auto prediction = theory::predict(c, theory::contact_constants());
  summary["measured"] = measure::to_json(analysis);
  if (capped) {
    for (const char* key : {"H", "H_s", "H_s_scaled"})
      summary["measured"]["quantities"][key]["lower_bound"] = true;
  }
  summary["theory"] = io::to_json(c, prediction);
  const auto far = compare_with_theory(summary["comparison"], analysis, prediction);
  write_json_file(dir / "summary.json", summary);

  const auto show = [&](const char* label, const std::optional<double>& v, double scale,
                        const char* unit, std::string theory, bool at_least = false) {
    fmt::print(out, "  {:<28} {:>10}  {:<4} theory {}\n", label,
               v ? fmt::format("{}{:.4g}", at_least ? ">= " : "", *v / scale) : std::string("-"),
               unit, theory);
  };
  const auto range = [](theory::Range r, double scale) {
    return fmt::format("{:.4g} .. {:.4g}", r.lo / scale, r.hi / scale);
  };
  fmt::print(out, "  status      {}\n  outcome     {} (theory: {})\n", status,
             measure::outcome_text(analysis.outcome), prediction.outcome_text());
  for (const auto& f : far) fmt::print(out, "  warning     {}\n", f.text());
  if (!analysis.undetermined.empty()) fmt::print(out, "              {}\n", analysis.undetermined);
  show("r*  contact radius", analysis.r_star, 1e-3, "mm", range(prediction.r_star, 1e-3));
  show("e*  indentation", analysis.e_star, 1e-3, "mm", range(prediction.e_star, 1e-3));
  show("F*  peak force of the snap", analysis.F_star, 1.0, "N", range(prediction.F_star, 1.0));
  show("t*  onset to launch", analysis.t_star, 1e-3, "ms", range(prediction.t_star, 1e-3));
  const auto beside = [&](const char* label, const std::optional<double>& v, double scale,
                          const char* unit) {
    if (v) fmt::print(out, "  {:<28} {:>10.4g}  {}\n", label, *v / scale, unit);
  };
  beside("  through a 170 Hz plate", analysis.F_star_plate, 1.0, "N");
  beside("  apex displacement at onset", analysis.e_apex_star, 1e-3, "mm");
  if (analysis.t_force_rise && analysis.t_onset) {
    fmt::print(out, "  {:<28} {:>10.4g}  ms   ({:.3g} ms before the onset)\n",
               "  force rise starts at", *analysis.t_force_rise * 1e3,
               (*analysis.t_onset - *analysis.t_force_rise) * 1e3);
  }
  beside("  force rise to launch", analysis.t_star_rise, 1e-3, "ms");
  show("H_l lift to the onset", analysis.H_l, 1e-3, "mm", range(prediction.H_l, 1e-3));
  show("H_s flight from the snap", analysis.H_s, 1e-3, "mm", range(prediction.H_s, 1e-3), capped);
  show("H   jump height", analysis.H, 1e-3, "mm", range(prediction.H, 1e-3), capped);
  if (analysis.delta_p_onset) {
    fmt::print(out, "  {:<28} {:>10.4g}  kPa  (suction left when the apex comes down)\n",
               "delta_p at the onset", *analysis.delta_p_onset / 1e3);
  }
  // The prefactors, each with the definition behind it.
  const auto alpha = [&](const char* label, const std::optional<double>& v, theory::Range r,
                         const char* definition) {
    fmt::print(out, "  {:<8} {:>8}  bounds {:.3g} .. {:.3g}  {}\n", label,
               v ? fmt::format("{:.3f}", *v) : std::string("-"), r.lo, r.hi, definition);
  };
  const auto& b = prediction.alpha;
  alpha("alpha_r", analysis.alpha_r, b.alpha_r,
        "r* / sqrt(hR); r*: radius of the outer particles the plate pushes, at w/R = 0.03");
  alpha("alpha_e", analysis.alpha_e, b.alpha_e,
        "e* / h; e*: indentation (rim's approach to the plate) at the onset");
  alpha("alpha_F", analysis.alpha_F, b.alpha_F,
        "F* / (E h^3 / R); F*: peak plate force from the foot of its rise to the snap's end");
  if (analysis.alpha_F_plate) {
    fmt::print(out,
               "  {:<8} {:>8.3f}  with F* through the paper's 170 Hz force plate (damping 0.7)\n",
               "", *analysis.alpha_F_plate);
  }
  alpha("alpha_t", analysis.alpha_t, b.alpha_t,
        "t* / sqrt(m R / (E h^2)); m = popper + counterweight (rigid wire)");
  if (analysis.alpha_t_own) {
    fmt::print(out, "  {:<8} {:>8.3f}  with m = the popper's own mass (the limit of a soft wire)\n",
               "", *analysis.alpha_t_own);
  }
  if (analysis.alpha_t_net) {
    fmt::print(out, "  {:<8} {:>8.3f}  with m = mg / g (no counterweight's inertia)\n", "",
               *analysis.alpha_t_net);
  }
  for (const auto& w : analysis.warnings) fmt::print(out, "  note        {}\n", w);
  return analysis;
}

// The grounded shell's inner surface against the crease threshold of an incompressible
// neo-Hookean solid and Biot's instability of the case's own law (fem/surface_instability.hpp),
// in words and for summary.json.
std::pair<std::string, nlohmann::json> surface_report(const config::Case& c,
                                                      const popper::Preparation& prep) {
  std::optional<double> biot;
  try {
    biot = fem::biot_instability(popper::body_material(c.material)).ratio;
  } catch (const std::runtime_error&) {
    // stable down to the scan's end: no instability to compare with
  }
  const double ratio = *prep.surface_ratio, crease = fem::kNeoHookeanCreaseRatio;
  const bool past = ratio >= crease;
  auto words = fmt::format(
      "the inner surface is compressed along itself most {:.3g} mm from the rim, its principal "
      "stretches {:.3g} to 1; an incompressible neo-Hookean surface creases from {:g} to 1",
      1e3 * prep.surface_from_rim, ratio, crease);
  if (biot) words += fmt::format(", this law's smooth surface wrinkles from {:.3g} (Biot)", *biot);
  const bool past_biot = biot && ratio > *biot;
  const int closed = prep.surface_closed_creases;
  if (closed > 0) {
    words += fmt::format(
        "; it touches itself in {}: creased, {} faces closed (docs/axisymmetric.md, \"The crease "
        "at the clamp\")",
        closed == 1 ? std::string("one place") : fmt::format("{} places", closed),
        closed == 1 ? "the crease's" : "each crease's");
  } else if (past_biot) {
    words +=
        ": past both, so no smooth surface of this law is stable there; no two parts of the "
        "model's surface touch, so it is held smooth by its mesh alone, or creased with its faces "
        "apart or closed within one element's edge (docs/axisymmetric.md, \"The crease at the "
        "clamp\")";
  } else if (past) {
    words +=
        ": past the crease threshold and short of Biot's, so a shell of a nearly incompressible "
        "rubber creases there, while the model's surface stays smooth (docs/axisymmetric.md, \"The "
        "crease at the clamp\")";
  }
  nlohmann::json j = {{"ratio", ratio},
                      {"from_rim", prep.surface_from_rim},
                      {"crease_ratio", crease},
                      {"biot_ratio", biot ? nlohmann::json(*biot) : nlohmann::json(nullptr)},
                      {"past_crease_threshold", past},
                      {"past_biot", past_biot},
                      {"closed_creases", closed}};
  return {words, j};
}

// A resume refused before anything was changed: the run stays as it was (not "failed").
class ResumeRefused : public config::CaseError {
 public:
  using config::CaseError::CaseError;
};

// The run stopped on request before its release; what() is its status.
class StoppedInThePreparation : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run continues only with the numerics it started with: a snapjump whose defaults have changed
// since (a new time step factor, say) would go on with another time step or grid, silently. The
// end time may differ (it is not part of the discretisation).
void check_same_numerics(const nlohmann::json& before_in, const nlohmann::json& now,
                         const fs::path& dir) {
  // Keys that summaries have carried only since a later version: a run made before had the value
  // its model had then.
  nlohmann::json before = before_in;
  if (!before.contains("bulk_integration")) {
    before["bulk_integration"] = before.value("model", "3d") == "axisymmetric" ? "reduced" : "full";
  }
  if (before.value("model", "3d") == "axisymmetric" && !before.contains("fan_layer")) {
    before["fan_layer"] = 0;
  }
  if (before.value("model", "3d") == "axisymmetric" && !before.contains("crease_seeds_from_rim")) {
    // Summaries carried one seeded root, or none, as crease_seed_from_rim.
    auto seeds = nlohmann::json::array();
    if (before.contains("crease_seed_from_rim") && !before["crease_seed_from_rim"].is_null()) {
      seeds.push_back(before["crease_seed_from_rim"]);
    }
    before.erase("crease_seed_from_rim");
    before["crease_seeds_from_rim"] = seeds;
    if (!before.contains("crease_seed_depth")) before["crease_seed_depth"] = 0.0;
  }
  std::string differ;
  for (const auto& [key, value] : before.items()) {
    if (key == "end_time") continue;
    if (!now.contains(key) || now[key] != value) {
      differ += fmt::format("\n  {}: {} when it started, {} now", key, value.dump(),
                            now.contains(key) ? now[key].dump() : std::string("absent"));
    }
  }
  if (!differ.empty()) {
    throw ResumeRefused(fmt::format(
        "--resume {}: this snapjump would continue the run with other numerics than it started "
        "with:{}\n(a default changed since; set the value in the folder's case.toml, e.g. "
        "numerics.time_step_factor = 0.4 for runs made before the factor became {}, or start "
        "the run again)",
        dir.string(), differ, popper::kTimeStepFactor));
  }
}

// Marks the run in dir as failed in its summary.json, keeping what the summary already holds.
// Never throws: it runs while another error is on its way out.
void record_failure(const fs::path& dir, const std::string& what) {
  try {
    nlohmann::json summary = nlohmann::json::object();
    if (std::ifstream f(dir / "summary.json"); f) {
      auto before = nlohmann::json::parse(f, nullptr, false);
      if (before.is_object()) summary = std::move(before);
    }
    summary["status"] = io::run_status::failure(what);
    write_json_file(dir / "summary.json", summary);
  } catch (const std::exception&) {
    // The error that stopped the run is reported by the caller.
  }
}

}  // namespace

namespace {

// A run after its folder is set up, in the shape of the experiment: prepare (buckle, set
// delta_p_j, ground) and release, or resume from a checkpoint; then step to the apex of the
// flight; then analyse and draw. It owns what those share: the popper, the time series and its
// file, the snapshots' collection, the checkpoint's loop state and the summary.
class Run {
 public:
  Run(const config::Case& c, const popper::Numerics& numerics, fs::path dir,
      const RunOptions& options, nlohmann::json& summary, std::ostream& out, std::ostream& err)
      : c_(c),
        numerics_(numerics),
        dir_(std::move(dir)),
        options_(options),
        summary_(summary),
        out_(out),
        err_(err),
        start_(Clock::now()),
        pop_(c, numerics),
        columns_(popper::sample_columns()),
        series_(columns_, true),
        pvd_(dir_ / "run.pvd") {
    print_numerics(out_, pop_);
    summary_["numerics"] = pop_.model().report().numerics_json();
    summary_["numerics"]["end_time"] = numerics_.end_time;
    summary_["end"] = end_json(c_, numerics_.end_time);
  }

  // Phases 1-3 and the release. False when the shell did not stay inverted under delta_p_j (the
  // summary says so and the run ends there).
  bool prepare_and_release();
  // Continues from the folder's checkpoint, with the series as it was there.
  void resume();

  enum class Stop { No, Pause, Interrupt };
  struct End {
    std::string status;
    Stop stop = Stop::No;
  };
  // Steps to the apex of the flight after the snap, the cap, a pause, a stop request or a failure
  // (the status says which; what was written stays). At the cap it leaves a checkpoint, from
  // which a resume with a later cap goes on.
  End go_to_the_apex();
  // A paused or interrupted run's summary; the run goes on with --resume.
  int pause();
  int interrupt();
  // The analysis, the summary, the files and the figures.
  int finish(const std::string& status);

 private:
  [[nodiscard]] double wall() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }
  // The run's wall time so far, the parts before a resume included, into the summary: the sum
  // as wall_time, each part (this one last) as wall_time_parts.
  void note_wall_time() {
    auto parts = nlohmann::json::array();
    for (const double p : earlier_parts_) parts.push_back(p);
    const double now = wall();
    parts.push_back(now);
    summary_["wall_time"] = earlier_wall_ + now;
    summary_["wall_time_parts"] = parts;
  }
  // A resumed run keeps what its first part knew and the folder's case.toml does not: where the
  // case came from, which values were defaults, and the wall time of the parts before.
  void keep_earlier_summary(const nlohmann::json& before);
  double earlier_wall_ = 0.0;
  std::vector<double> earlier_parts_;
  void snapshot();
  popper::Sample record();
  // The preparation's progress line for a phase; stops the run when the user asked.
  void preparation_progress(const std::string& phase, double t, double fraction);
  // Refuses (ResumeRefused) a resume of a run with this status that has nothing to continue to.
  void check_continuable(const std::string& status) const;
  // Refuses a new cap that is not after the time the run has reached (last_t) [s].
  void check_new_end(double last_t) const;
  bool stop_requested();
  // The release's progress line, every five seconds.
  void progress(double run_start, long start_steps);

  const config::Case& c_;
  const popper::Numerics& numerics_;
  const fs::path dir_;
  const RunOptions& options_;
  nlohmann::json& summary_;
  std::ostream& out_;
  std::ostream& err_;
  const Clock::time_point start_;
  popper::Popper pop_;
  std::vector<std::string> columns_;
  measure::TimeSeries series_;
  std::optional<measure::CsvWriter> csv_;
  io::PvdCollection pvd_;
  LoopState loop_;
  double last_print_ = -1.0;
  double last_stop_check_ = 0.0;
  std::string current_phase_;
  double phase_start_ = 0.0;
};

void Run::snapshot() {
  const auto name = fmt::format("snapshots/frame_{:05d}.vtu", pvd_.size());
  pop_.model().report().write_snapshot(dir_ / name, pop_.time());
  // The plate and the container (its side, up to a height of the shell's radius) as simple
  // geometry for ParaView.
  io::write_apparatus_vtu(dir_ / io::apparatus_file(name), 2.0 * c_.shell.R,
                          pop_.model().outer_rim_radius(), pop_.model().outer_rim_z(), c_.shell.R);
  pvd_.add(pop_.time(), name);
  loop_.frames.emplace_back(pop_.time(), name);
}

// series.csv has no comment line: ParaView's CSV reader would read the columns as text (the case
// is in case.toml, the units are SI, t = 0 at the release: docs/analysis.md).
popper::Sample Run::record() {
  const auto s = pop_.sample();
  const auto values = popper::sample_values(s);
  series_.add_row(values, s.contact);
  csv_->write_row(values, s.contact);
  ++loop_.rows;
  return s;
}

// The stop hook, asked at most four times a second.
bool Run::stop_requested() {
  if (!options_.stop_requested || wall() - last_stop_check_ < 0.25) return false;
  last_stop_check_ = wall();
  return options_.stop_requested();
}

// Each phase with its share done and, from its pace so far, at most how long it has to go (the
// buckling and the grounding may end early).
void Run::preparation_progress(const std::string& phase, double t, double fraction) {
  if (stop_requested()) {
    throw StoppedInThePreparation(fmt::format(
        "{} in the preparation ({}, t = {:.4f} s), before the release: nothing to resume; start "
        "the run again",
        io::run_status::kInterrupted, phase, t));
  }
  if (phase != current_phase_) {
    current_phase_ = phase;
    phase_start_ = wall();
  }
  if (options_.quiet || wall() - last_print_ < 2.0) return;
  last_print_ = wall();
  std::string share;
  if (fraction > 0.0) {
    share = fmt::format(" ({:.0f} %, at most {:.0f} s to go)", 100 * fraction,
                        (wall() - phase_start_) * (1.0 - fraction) / fraction);
  }
  fmt::print(err_, "  [{:>6.1f} s] {:<14} t = {:.4f} s{}\n", wall(), phase, t, share);
}

bool Run::prepare_and_release() {
  const auto prep = pop_.prepare([this](const std::string& phase, double t, double fraction) {
    preparation_progress(phase, t, fraction);
  });
  fmt::print(out_, "  prepared    {}\n", prep.message);
  std::optional<std::pair<std::string, nlohmann::json>> surface;
  if (prep.surface_ratio) {
    surface = surface_report(c_, prep);
    fmt::print(out_, "  surface     {}\n", surface->first);
  }
  const auto or_null = [](const std::optional<double>& p) {
    return p ? nlohmann::json(*p) : nlohmann::json(nullptr);
  };
  summary_["preparation"] = {{"inverted", prep.inverted},
                             {"held", prep.held},
                             {"buckling_pressure", or_null(prep.buckling_pressure)},
                             {"reverse_pressure", or_null(prep.reverse_pressure)},
                             {"hold_pressure", or_null(prep.hold_pressure)},
                             {"delta_p_j", pop_.delta_p_j()},
                             {"plate_force", prep.plate_force},
                             {"message", prep.message}};
  if (surface) summary_["preparation"]["inner_surface"] = surface->second;
  if (!prep.held) {
    summary_["status"] =
        prep.inverted ? io::run_status::kSnappedBack : io::run_status::kDidNotInvert;
    const auto hints =
        preparation_hints(c_, prep, pop_.preparation_settings().buckle_factor, pop_.delta_p_j());
    summary_["hints"] = hints;
    write_json_file(dir_ / "summary.json", summary_);
    fmt::print(out_, "  result      {}\n", summary_["status"].get<std::string>());
    for (const auto& h : hints) fmt::print(out_, "  try         {}\n", h);
    return false;
  }
  write_json_file(dir_ / "summary.json", summary_);
  pop_.release();
  csv_.emplace(dir_ / "series.csv", columns_, true);
  fs::create_directories(dir_ / "snapshots");
  record();
  snapshot();
  loop_.next_sample = numerics_.probe_interval;
  loop_.next_snapshot = numerics_.snapshot_interval;
  loop_.next_checkpoint = numerics_.checkpoint_interval;
  return true;
}

void Run::check_continuable(const std::string& status) const {
  namespace rs = io::run_status;
  const auto refuse = [&](const std::string& why) {
    throw ResumeRefused(fmt::format("--resume {}: {}", dir_.string(), why));
  };
  if (status == rs::kCompletedAtApex) {
    refuse("the run ended at the apex of its flight: there is nothing to continue");
  }
  if (status == rs::kSnappedBack || status == rs::kDidNotInvert) {
    refuse(
        fmt::format("the run ended in its preparation ({}): there is nothing to continue", status));
  }
  if (rs::interrupted(status) && !fs::exists(dir_ / "checkpoint.bin")) {
    refuse(fmt::format("the run has no state to continue from ({}): start it again", status));
  }
  if (rs::capped(status) && !options_.end_time) {
    refuse(fmt::format(
        "the run went to its cap on simulated time before the apex ({}); continue it to a later "
        "cap: {} --end-time T",
        status, resume_command(dir_)));
  }
}

void Run::check_new_end(double last_t) const {
  if (options_.end_time && !(*options_.end_time > last_t + 1e-12)) {
    throw ResumeRefused(fmt::format(
        "--resume {} --end-time {:.6g} s: the run has reached t = {:.6g} s already; give a later "
        "end",
        dir_.string(), *options_.end_time, last_t));
  }
}

void Run::keep_earlier_summary(const nlohmann::json& before) {
  if (before.contains("case") && before["case"].is_object()) {
    for (const char* key : {"source", "defaults_used"}) {
      if (before["case"].contains(key)) summary_["case"][key] = before["case"][key];
    }
  }
  const auto parts = before.find("wall_time_parts");
  if (parts != before.end() && parts->is_array()) {
    for (const auto& p : *parts) {
      if (p.is_number() && std::isfinite(p.get<double>())) {
        earlier_parts_.push_back(std::max(0.0, p.get<double>()));
      }
    }
  } else if (before.contains("wall_time") && before["wall_time"].is_number()) {
    earlier_parts_.push_back(std::max(0.0, before["wall_time"].get<double>()));
  }
  earlier_wall_ = 0.0;
  for (const double p : earlier_parts_) earlier_wall_ += p;
}

void Run::resume() {
  std::string status;
  if (std::ifstream prev(dir_ / "summary.json"); prev) {
    const auto before = nlohmann::json::parse(prev, nullptr, false);
    if (before.is_object() && before.contains("preparation")) {
      summary_["preparation"] = before["preparation"];
    }
    if (before.is_object()) keep_earlier_summary(before);
    if (before.is_object() && before.contains("numerics")) {
      check_same_numerics(before["numerics"], summary_["numerics"], dir_);
    }
    if (before.is_object() && before.contains("status") && before["status"].is_string()) {
      status = before["status"].get<std::string>();
    }
  }
  check_continuable(status);
  loop_ = read_checkpoint(dir_, pop_);
  // The series as it was at the checkpoint: rows written after it are dropped.
  const auto old = measure::TimeSeries::read_csv_file(dir_ / "series.csv");
  if (old.size() < loop_.rows)
    throw std::runtime_error("series.csv is shorter than its checkpoint");
  // A run at its cap may have gone on past its last checkpoint (an earlier build wrote none at
  // the cap): the new cap must lie beyond both.
  const bool at_its_cap = io::run_status::capped(status) && !old.empty();
  check_new_end(at_its_cap ? std::max(pop_.time(), old.time().back()) : pop_.time());
  // The rows that belong to the checkpoint go to a new file, which then replaces the old one in
  // one rename: a run killed at any moment keeps either series.csv as it was or the new one,
  // never a series shorter than its checkpoint. The writer goes on appending to the renamed file.
  const fs::path tmp_series = dir_ / "series.csv.tmp";
  try {
    csv_.emplace(tmp_series, columns_, true);
    std::vector<double> row(columns_.size());
    for (std::size_t i = 0; i < loop_.rows; ++i) {
      for (std::size_t k = 0; k < columns_.size(); ++k) row[k] = old.column(columns_[k])[i];
      series_.add_row(row, old.contact()[i]);
      csv_->write_row(row, old.contact()[i]);
      if (options_.fault_after_rewritten_rows && i + 1 == *options_.fault_after_rewritten_rows) {
        throw std::runtime_error("injected fault in the middle of the series' rewrite");
      }
    }
  } catch (const io::WriteFailed&) {
    // A full disk: series.csv stays as it was, and no temporary is left beside it.
    csv_.reset();
    std::error_code ignored;
    fs::remove(tmp_series, ignored);
    throw;
  }
  fs::rename(tmp_series, dir_ / "series.csv");
  const auto frames = loop_.frames;
  loop_.frames.clear();
  for (const auto& [t, name] : frames) {
    pvd_.add(t, name);
    loop_.frames.emplace_back(t, name);
  }
  fmt::print(out_, "  resumed     at t = {:.4f} s, step {}\n", pop_.time(), pop_.steps());
}

Run::End Run::go_to_the_apex() {
  End end{io::run_status::capped_at(numerics_.end_time)};
  bool apex = false;
  last_stop_check_ = 0.0;
  const double run_start = wall();
  const long start_steps = pop_.steps();
  // Whether the apex has come down (the snap's onset) in the series so far.
  loop_.flight.R = c_.shell.R;
  for (double w : series_.column("w")) loop_.flight.see_apex_gap(w);
  try {
    while (pop_.time() < numerics_.end_time) {
      pop_.step();
      if (pop_.time() + 1e-12 >= loop_.next_sample) {
        loop_.next_sample += numerics_.probe_interval;
        // Stop at the apex of the flight after the snap (popper::FlightWatch).
        if (loop_.flight.apex_reached(record())) {
          end.status = io::run_status::kCompletedAtApex;
          apex = true;
          break;
        }
      }
      if (pop_.time() + 1e-12 >= loop_.next_snapshot) {
        loop_.next_snapshot += numerics_.snapshot_interval;
        snapshot();
      }
      if (options_.pause_at && pop_.time() + 1e-12 >= *options_.pause_at) {
        end.stop = Stop::Pause;
      } else if (stop_requested()) {
        end.stop = Stop::Interrupt;
      }
      if (pop_.time() + 1e-12 >= loop_.next_checkpoint || end.stop != Stop::No) {
        loop_.next_checkpoint += numerics_.checkpoint_interval;
        write_checkpoint(dir_, pop_, loop_);
        // The wall time with it: a run killed now resumes knowing how long it had run.
        note_wall_time();
        write_json_file(dir_ / "summary.json", summary_);
      }
      if (end.stop != Stop::No) break;
      progress(run_start, start_steps);
    }
    // At the cap: the state there, for a resume to a later cap.
    if (!apex && end.stop == Stop::No) write_checkpoint(dir_, pop_, loop_);
  } catch (const io::WriteFailed&) {
    throw;  // a full disk: the run ends as a write failure, its summary saying which file
  } catch (const std::exception& e) {
    end.status = io::run_status::failure(e.what());
    end.stop = Stop::No;
    fmt::print(err_, "error: {}\n  what was written so far stays in {}\n", e.what(), dir_.string());
  }
  return end;
}

void Run::progress(double run_start, long start_steps) {
  if (options_.quiet || wall() - last_print_ < 5.0) return;
  last_print_ = wall();
  const double rate = (pop_.steps() - start_steps) / std::max(1e-9, wall() - run_start);
  const double eta = (numerics_.end_time - pop_.time()) / pop_.dt() / std::max(rate, 1e-9);
  fmt::print(err_,
             "  [{:>6.1f} s] release        t = {:.4f} s, {:.0f} steps/s, at most {:.0f} s to go, "
             "delta_p = {:.0f} Pa, z = {:.2f} mm\n",
             wall(), pop_.time(), rate, eta, pop_.gas().delta_p(), 1e3 * pop_.container().z);
}

int Run::pause() {
  summary_["status"] = fmt::format("{} at t = {:.6g} s; continue with {}", io::run_status::kPaused,
                                   pop_.time(), resume_command(dir_));
  note_wall_time();
  write_json_file(dir_ / "summary.json", summary_);
  fmt::print(out_, "  status      {}\n", summary_["status"].get<std::string>());
  return kExitOk;
}

int Run::interrupt() {
  summary_["status"] = fmt::format("{} at t = {:.6g} s; continue with {}",
                                   io::run_status::kInterrupted, pop_.time(), resume_command(dir_));
  note_wall_time();
  write_json_file(dir_ / "summary.json", summary_);
  fmt::print(out_,
             "  status      {}\n  stopped     at t = {:.6g} s after the release, step {}; "
             "checkpoint.bin holds the run there\n  resume      {}\n",
             summary_["status"].get<std::string>(), pop_.time(), pop_.steps(),
             resume_command(dir_));
  return kExitInterrupted;
}

int Run::finish(const std::string& status) {
  snapshot();
  summary_["status"] = status;
  note_wall_time();
  summary_["steps"] = pop_.steps();
  const auto analysis = write_results(dir_, summary_, c_, series_, status, out_);
  if (io::run_status::capped(status)) {
    fmt::print(out_, "  continue    {} --end-time {:.4g}s goes on from the cap\n",
               resume_command(dir_), 2.0 * numerics_.end_time);
  }
  fmt::print(out_, "  files       {}/series.csv, summary.json, run.pvd ({} snapshots)\n",
             dir_.string(), pvd_.size());
  // The figures a reader looks at first: the Fig. 2(a) panels and cross-sections of the shell
  // before, at and after the transition. A missing gnuplot costs the figures, not the run.
  try {
    const auto series_fig = plot::plot_series(dir_, {});
    std::vector<double> times = {0.0};
    const double last = pop_.time();
    if (analysis.t_onset) {
      for (double t : {*analysis.t_onset - 0.1, *analysis.t_onset - 0.02, *analysis.t_onset}) {
        if (t > times.back() + 1e-3) times.push_back(t);
      }
      if (analysis.t_launch && *analysis.t_launch > times.back() + 1e-3)
        times.push_back(*analysis.t_launch);
    } else {
      for (double f : {0.25, 0.5, 0.75}) times.push_back(f * last);
    }
    if (last > times.back() + 1e-3) times.push_back(last);
    const auto sections_fig = plot::plot_sections(dir_, times, {});
    fmt::print(out_, "  figures     {}, {}\n", series_fig.figure.string(),
               sections_fig.figure.string());
  } catch (const std::exception& e) {
    fmt::print(out_, "  note        no figures: {}\n", e.what());
  }
  return io::run_status::failed(status) ? kExitFailure : kExitOk;
}

// A run started by a sweep ends with it (a sweep killed with -9 must not leave runs going on that
// its restart would start a second time).
void end_with_the_sweep() {
  if (const char* parent = std::getenv("SNAPJUMP_SWEEP_PARENT")) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (std::to_string(::getppid()) != parent) {
      throw std::runtime_error("the sweep that started this run has ended");
    }
  }
}

// The folder as given, and where it really is when links or ".." lead elsewhere.
std::string describe_folder(const fs::path& dir) {
  std::string where = dir.string();
  std::error_code ec;
  const auto real = fs::canonical(dir, ec);
  if (!ec && real != fs::absolute(dir).lexically_normal()) {
    where += fmt::format(" (that is {})", real.string());
  }
  return where;
}

// dir/case.toml: the case, a designer's mesh named by its copy in the folder (shell.msh).
void write_case_file(const fs::path& dir, config::Case c) {
  if (!c.shell.mesh.empty()) c.shell.mesh = "shell.msh";
  io::write_file_atomically(dir / "case.toml", config::to_toml(c));
}

// A new run's folder gets the case (and a designer's mesh, so that a resume or a rerun does not
// depend on a file that may change or move; case.toml names the copy) and a first summary.
void write_case(const fs::path& dir, const config::Case& c, const nlohmann::json& summary) {
  if (!c.shell.mesh.empty()) {
    fs::copy_file(c.shell.mesh, dir / "shell.msh", fs::copy_options::overwrite_existing);
  }
  write_case_file(dir, c);
  write_json_file(dir / "summary.json", summary);
}

}  // namespace

int run_simulation(const config::Case& case_in, const RunOptions& options, std::ostream& out,
                   std::ostream& err) {
  end_with_the_sweep();
  const bool resuming = !options.resume.empty();
  fs::path dir;
  config::Case c = case_in;
  if (resuming) {
    dir = options.resume;
    if (!fs::is_regular_file(dir / "case.toml")) {
      throw config::CaseError(
          fmt::format("--resume {}: not a snapjump run folder (no case.toml)", dir.string()));
    }
    c = config::load_case_file(dir / "case.toml");
  }
  if (options.end_time) {
    if (!(*options.end_time > 0.0 && std::isfinite(*options.end_time))) {
      throw config::CaseError(fmt::format("--end-time {} s: must be positive", *options.end_time));
    }
    c.numerics.end_time = *options.end_time;
  }
  popper::check_simulable(c);
  const auto numerics = popper::resolve_numerics(c);
  if (!resuming) dir = make_output_folder(c, options.output);
  // One process per run folder: a second resume of the same run is refused.
  const io::FolderLock lock(dir, "run.lock", "the run folder");
  fmt::print(out, "snapjump run: {}\n  output      {}{}\n",
             text::printable_line(c.title.empty() ? c.source : c.title), describe_folder(dir),
             resuming ? " (resumed)" : "");
  nlohmann::json summary = {{"case", io::case_to_json(c)}, {"status", io::run_status::kRunning}};
  if (!resuming) write_case(dir, c, summary);

  try {
    Run run(c, numerics, dir, options, summary, out, err);
    if (resuming) {
      run.resume();
      // The new cap, for a later resume of this one.
      if (options.end_time) write_case_file(dir, c);
    } else if (!run.prepare_and_release()) {
      return kExitNotPrepared;
    }
    const auto end = run.go_to_the_apex();
    switch (end.stop) {
      case Run::Stop::Pause:
        return run.pause();
      case Run::Stop::Interrupt:
        return run.interrupt();
      case Run::Stop::No:
        break;
    }
    return run.finish(end.status);
  } catch (const ResumeRefused&) {
    throw;  // nothing was changed: the summary keeps its status
  } catch (const StoppedInThePreparation& e) {
    summary["status"] = e.what();
    write_json_file(dir / "summary.json", summary);
    fmt::print(out, "  status      {}\n", e.what());
    return kExitInterrupted;
  } catch (const std::exception& e) {
    // Whatever stopped the run, its summary says so (a sweep reads "running" as alive).
    record_failure(dir, error_text(e, "running the simulation"));
    throw;
  }
}

SigintStop::SigintStop() {
  g_sigint = 0;
  // A process started with SIGINT ignored (a background job of a script) keeps it ignored.
  if (::sigaction(SIGINT, nullptr, &previous_) != 0 || previous_.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = note_sigint;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: a second Ctrl-C, while the run writes its checkpoint, say, ends the process.
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  installed_ = ::sigaction(SIGINT, &action, &previous_) == 0;
}

SigintStop::~SigintStop() {
  if (installed_) ::sigaction(SIGINT, &previous_, nullptr);
}

bool SigintStop::requested() const { return g_sigint != 0; }

int reanalyze_run(const std::filesystem::path& dir, std::ostream& out) {
  for (const char* name : {"case.toml", "summary.json", "series.csv"}) {
    if (!fs::is_regular_file(dir / name)) {
      throw config::CaseError(
          fmt::format("--reanalyze {}: not a snapjump run folder (no {})", dir.string(), name));
    }
  }
  const auto c = config::load_case_file(dir / "case.toml");
  nlohmann::json summary;
  try {
    std::ifstream in(dir / "summary.json");
    summary = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw config::CaseError(
        fmt::format("--reanalyze {}: summary.json cannot be read: {}", dir.string(), e.what()));
  }
  if (!summary.contains("measured") || !summary.contains("status")) {
    throw config::CaseError(fmt::format(
        "--reanalyze {}: the run has no results yet (status: {}); finish it with --resume first",
        dir.string(), summary.value("status", std::string("unknown"))));
  }
  const units::UnitParser parser;
  const auto series = measure::TimeSeries::read_csv_file(dir / "series.csv", &parser);
  fmt::print(out,
             "snapjump run --reanalyze: {}\n  series      {} samples, t = {:.6g} .. {:.6g} s\n",
             dir.string(), series.size(), series.empty() ? 0.0 : series.time().front(),
             series.empty() ? 0.0 : series.time().back());
  write_results(dir, summary, c, series, summary["status"].get<std::string>(), out);
  fmt::print(out, "  files       {}/summary.json rewritten\n", dir.string());
  return kExitOk;
}

}  // namespace snapjump::app
