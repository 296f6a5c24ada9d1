// The popper: the shell (finite-element body on MPM particles), the rigid container it is glued
// to, the gas inside, and the plate. It runs the experimental protocol of the paper (buckle, set
// delta_p_j, ground, release) and measures what the experiment measures.
#pragma once

#include <array>
#include <functional>
#include <iosfwd>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "core/rigid_body.hpp"
#include "measure/time_series.hpp"
#include "mesh/cap_mesher.hpp"
#include "popper/gas.hpp"
#include "popper/shell_model.hpp"

namespace snapjump::popper {

// The 3D elastic time step factor (dt = factor * smallest node spacing / p-wave speed) when the
// case does not set numerics.time_step_factor: `build/cfl_scan coarse mpm` (the whole MPM step, the
// cap driven into the plate at 2 m/s) finds 0.6 stable and 0.7 unstable, as the finite elements
// alone do; 0.5 keeps a margin of one step of that scan (docs/performance.md).
inline constexpr double kTimeStepFactor = 0.5;

// Numerical settings resolved from the case's [numerics] table.
struct Numerics {
  config::Model model = config::Model::ThreeD;
  // The bulk energy at fewer points (numerics.bulk_integration; the model's own default).
  bool reduced_bulk = false;
  mesh::CapSpec cap;      // mesh of the shell (3D)
  std::string mesh_file;  // a designer's own shell (.msh) instead of the cap (3D)
  std::shared_ptr<const mesh::Mesh> user_mesh;  // that shell, read and placed (load_user_mesh)
  double dx = 0.0;                              // grid spacing [m] (3D)
  int axi_through = 0;                          // axisymmetric: elements through h
  int axi_along = 0;                            // axisymmetric: elements along the meridian
  double axi_crease_fan = 0.0;                  // axisymmetric: crease root from the rim [m]
  double axi_crease_fan_band = 0.0;             // axisymmetric: roots within this band [m]
  int axi_fan_layer = 0;  // axisymmetric: layers tiled so that every inner corner node is a root
  std::vector<double> axi_crease_seeds;  // axisymmetric: seeded creases' roots from the rim [m]
  double axi_crease_seed_depth = 0.0;    // axisymmetric: their notch [m]
  double time_step_factor = kTimeStepFactor;  // elastic time step factor (3D)
  double probe_interval = 1e-4;               // [s] between samples of the time series
  double snapshot_interval = 5e-3;            // [s] between VTU snapshots
  double checkpoint_interval = 0.02;          // [s] between checkpoints of a run
  // [s] after the release: the run ends at the apex of the flight, at the latest here (the
  // case's numerics.end_time, or default_end(case).cap).
  double end_time = 0.0;
  double prep_damping = 0.0;  // [1/s] mass-proportional damping of phases 1-3
};
// Also reads and places a designer's mesh (shell.mesh), once: throws mesh::MeshError for a defect
// and config::CaseError for a mesh with the axisymmetric model.
Numerics resolve_numerics(const config::Case& c);

// The cap on a run's simulated time when the case sets none (numerics.end_time). The run ends at
// the apex of the flight; what can come before it is the ring stage, whose length the air coming
// in sets (the theory's t_c, tens of milliseconds, is the snap's), and the flight. So the cap is
//   cap = kRefillsBeforeTheCap * refill + 2 * rise, at most kLongestDefaultEnd:
// refill: the valve's time, at the release's suction delta_p_j held, to let in the air of twice
// the cavity (what the inverted shell took from the container and gives back as it everts),
//   beta_n delta_p_j t + alpha_n delta_p_j t^2 / 2 = 2 V_cavity / V^0;
// rise: from the launch to the apex of the theory's highest H, the net weight mg decelerating the
// moving mass M (popper and counterweight): sqrt(2 H M / (m g)). The runs on record snap 1.1
// ((R, h) = (30, 2) mm) to 1.5 ((30, 1) mm) refills after the release, and their flights from
// the launch to the apex take less than one rise: four refills and two rises leave a margin of
// two and more.
struct DefaultEnd {
  double refill = 0.0;  // [s]
  double rise = 0.0;    // [s]
  double height = 0.0;  // the theory's highest H [m]
  double cap = 0.0;     // [s]
};
inline constexpr double kRefillsBeforeTheCap = 4.0;
// Bounds the cap where the formula has none (no suction at the release: nothing to refill).
inline constexpr double kLongestDefaultEnd = 60.0;  // [s]
DefaultEnd default_end(const config::Case& c);

// What the simulator needs beyond a valid case (nu < 1/2). Throws config::CaseError.
void check_simulable(const config::Case& c);

// One sample of what the experiment measures, plus energies.
struct Sample {
  // e: indentation (undeformed outer depth less the outer rim's height above the plate);
  // e_apex: apex displacement relative to the outer rim (e + w).
  double t = 0, z = 0, r = 0, w = 0, e = 0, e_apex = 0, F = 0, delta_p = 0, vz = 0;
  measure::ContactState contact = measure::ContactState::None;
  double kinetic = 0, elastic = 0, gravitational = 0;
};
// Column names of the time series, in the order of Sample (contact is the text column).
std::vector<std::string> sample_columns();
std::vector<double> sample_values(const Sample& s);

// The analysis's onset rule on an apex gap w [m] of a shell of radius R [m]: w / R below its
// onset ratio, the apex down on the plate.
bool apex_down(double w, double R);

// Watches the samples of a run for its end: the apex of the flight after the snap. The flight
// starts when the container leaves the plate going up (no contact, no plate force, rising) once
// the apex has come down (w / R below the analysis's onset ratio: the snap); a hop on the ring
// before it, or a shell pulled off the plate by the suction while it settles, is no flight. Its
// apex: off the plate for 5 ms and coming down.
struct FlightWatch {
  double R = 0.0;                // shell radius for w / R [m]
  bool snapped = false;          // the apex has come down
  double airborne_since = -1.0;  // start of the current flight [s], -1 on the plate
  // Takes the next sample; true at the flight's apex.
  bool apex_reached(const Sample& s);
  // Takes an apex gap w [m] (a sample's, or one recorded before a resume): the snap has begun
  // once w / R falls below the analysis's onset ratio.
  void see_apex_gap(double w);
};

struct Preparation {
  bool inverted = false;  // the shell inverted under the buckling pressure
  bool held = false;      // and stayed inverted at delta_p_j
  // It held at delta_p_j in the air, then snapped back on the plate as it was grounded.
  bool snapped_back_on_plate = false;
  // Pressure at the onset of the snap [Pa] (PreparationSettings: the onset rule); nothing when
  // the rule did not see one (no sample shrank the cavity onset_factor times faster than the
  // reference window's mean).
  std::optional<double> buckling_pressure;
  // Where phase 1 follows the pressure-volume branch (ShellModel::buckle_quasi_statically): the
  // buckling pressure is the branch's maximum, and these its lowest suction after it and the
  // lowest suction that holds the fully inverted shell [Pa].
  std::optional<double> reverse_pressure, hold_pressure;
  double plate_force = 0.0;  // after grounding, mean plate force over the settling's end [N]
  // The grounded shell's inner surface where it is compressed along itself most
  // (ShellModel::inner_surface_compression): the ratio of its principal stretches, and the
  // distance from the rim face [m] (NaN where nothing is compressed), and in how many places it
  // touches itself (closed creases); nothing where the model does not resolve it (3D).
  std::optional<double> surface_ratio;
  double surface_from_rim = std::numeric_limits<double>::quiet_NaN();
  int surface_closed_creases = 0;
  std::string message;  // what happened, in words
};

// The quasi-static phases' settings (only their end states matter, docs/popper.md; so these
// choose how to get there, not what the popper does after the release).
struct PreparationSettings {
  // Phase 1, buckle: the suction ramps to buckle_factor p_c (Zoelly's p_c of the case's R, h;
  // above 1 so that the perfect cap, which buckles near p_c, is sure to go) over ramp, then is
  // held at most max_wait for the shell to invert. Inverted: the apex above the outer rim and the
  // shell's kinetic energy below settled_energy per kg of shell.
  double buckle_factor = 1.4;
  // Phases 1-2, the shell held in the air, run with this multiple of the preparation damping:
  // less damped, the snap-through at 1.4 p_c focuses on the axis and inverts an element there
  // (the axisymmetric model at 6 and 8 elements through h, the 3D (25, 2.5) mm cap at the
  // default preset: measured). Only the end state of these phases matters; the onset of the
  // snap lags the suction more under more damping (docs/validation.md, "Shell body").
  double held_damping = 3.0;
  // The suction's equilibrium found by continuation where the model can (the axisymmetric
  // model: the phase is quasi-static in fact, with no dynamic snap to crease the fold), instead
  // of the ramp in time below.
  bool quasi_static = true;
  double ramp = 0.02;     // [s]
  double max_wait = 0.1;  // [s]
  // Optionally the ramp has a fast first leg: the suction reaches fast_to p_c in fast_ramp, then
  // rises evenly to buckle_factor p_c at ramp. 0 and 0 (the protocol's): one even ramp. A slow
  // ramp that measures the buckling pressure starts this way to skip the pressures where nothing
  // happens (the snap-through validation).
  double fast_to = 0.0;
  double fast_ramp = 0.0;        // [s]
  double settled_energy = 1e-5;  // [J/kg]
  // The buckling pressure is the suction at the onset of the snap (SnapOnset): the cavity volume,
  // sampled every onset_sample_every steps, shrinks faster than onset_factor times its mean rate
  // while the suction rose from reference_window[0] to reference_window[1] p_c (a window below
  // the onset of any cap the protocol expects to invert).
  int onset_sample_every = 20;
  double onset_factor = 5.0;
  std::array<double, 2> reference_window = {0.3, 0.6};
  // Phase 2, set: down to delta_p_j over down, then held for settle.
  double down = 0.02;    // [s]
  double settle = 0.02;  // [s]
  // Phase 3, ground: on the plate with the preparation damping divided by ground_damping_divisor
  // (the container on the shell is a slower oscillator than the shell alone), until the plate's
  // mean force over windows of window carries the net weight within weight_tolerance in
  // good_windows windows running, at most max_time.
  double ground_damping_divisor = 3.0;
  double window = 5e-3;  // [s]
  double weight_tolerance = 0.02;
  int good_windows = 2;
  double max_time = 0.2;  // [s]
  // Progress is reported (and stop requests seen) every this many steps.
  int progress_every = 200;
};

// How often the shell is checked for folds [s] in the preparation's stepped phases (besides at
// each one's end, so that a fold which comes and goes within a phase ends the run too) and in
// the series' samples: a check costs about as much as a few steps of the 3D default popper, a
// sample comes every probe interval (0.2 ms, 25 steps), and a fold at the clamp builds up over
// tens of milliseconds of suction (docs/axisymmetric.md).
inline constexpr double kFoldCheckInterval = 1e-3;

// When the shell's next fold check is due: at the first time at or after `first` [s], then every
// kFoldCheckInterval of simulated time.
class FoldSchedule {
 public:
  explicit FoldSchedule(double first = -std::numeric_limits<double>::infinity()) : next_(first) {}
  // Whether a check is due at time t; if it is, the next one is due kFoldCheckInterval later.
  bool due(double t) {
    if (t < next_) return false;
    next_ = t + kFoldCheckInterval;
    return true;
  }

 private:
  double next_;
};

// The onset of a snap under a rising suction, from samples of the cavity volume: the first
// sample past the reference window of pressures whose rate of shrinking exceeds factor times the
// window's mean rate. The snap is fast where the quasi-static shrinking is slow, so the rule
// needs no threshold of its own in m^3/s.
class SnapOnset {
 public:
  // The reference window's pressures [Pa], and the factor.
  SnapOnset(double p_low, double p_high, double factor);
  // The cavity volume V [m^3] at time t [s] under the suction p [Pa].
  void sample(double t, double V, double p);
  // The suction at the onset, once seen.
  [[nodiscard]] std::optional<double> pressure() const { return onset_; }

 private:
  double p_low_, p_high_, factor_;
  double reference_sum_ = 0.0;
  int reference_count_ = 0;
  // The last sample (plain values and a flag: GCC 12 takes an optional's value for
  // uninitialised here, -Wmaybe-uninitialized, in builds without -fPIC).
  bool sampled_ = false;
  double last_t_ = 0.0, last_V_ = 0.0;
  std::optional<double> onset_;
};

// Progress callback: phase name, simulated time in the phase, fraction done (0..1, or < 0 when
// unknown; for a phase that may end early, the fraction of its longest duration).
using Progress = std::function<void(const std::string& phase, double t, double fraction)>;

class Popper {
 public:
  Popper(const config::Case& c, const Numerics& n, const PreparationSettings& settings = {});
  // The shell model's rules and the gas's callbacks hold `this` and the container's address: a
  // popper stays where it was made.
  Popper(const Popper&) = delete;
  Popper& operator=(const Popper&) = delete;
  Popper(Popper&&) = delete;
  Popper& operator=(Popper&&) = delete;

  // Phases 1-3 (quasi-static, damped): buckle, set delta_p_j, ground. Returns what happened; the
  // popper is then ready for release() if prep.held.
  Preparation prepare(const Progress& progress = {});
  // Phase 1 alone: the rim held, the suction raised as prepare() raises it until the shell has
  // inverted and settled. The project's one buckling driver: the snap-through validation compares
  // its buckling pressure with Zoelly's p_c. A popper is prepared once, by prepare() or by
  // buckle() (a second call throws std::logic_error); after buckle() it cannot be released.
  Preparation buckle(const Progress& progress = {});
  [[nodiscard]] const PreparationSettings& preparation_settings() const { return settings_; }
  // The suction of phase 1 at time t [s] after it began, Zoelly's p_c given [Pa].
  [[nodiscard]] double buckling_suction(double t, double pc) const;
  // t = 0: opens the valve; from here on the run is physical (no damping).
  void release();
  // One physical step.
  void step();
  // Current sample (F is the mean plate force since the previous sample). Checks the shell for
  // folds (ShellModel::check_folds, throws fem::FoldedElement) at the first sample and then every
  // kFoldCheckInterval of simulated time.
  Sample sample();

  // The state after release() (the shell's, container, gas, clock), to continue a stopped run:
  // a popper built from the same case and numerics and given load_state() steps on exactly as
  // the saved one would have. Binary, for the same build on the same machine.
  void save_state(std::ostream& out) const;
  void load_state(std::istream& in);

  [[nodiscard]] double time() const { return model_->time(); }
  [[nodiscard]] double dt() const { return model_->dt(); }
  [[nodiscard]] long steps() const { return model_->steps(); }
  // The discretisation of the shell.
  [[nodiscard]] const ShellModel& model() const { return *model_; }
  [[nodiscard]] const core::RigidBody& container() const { return container_; }
  [[nodiscard]] const core::RigidBody& counterweight() const { return counterweight_; }
  [[nodiscard]] const Gas& gas() const { return gas_; }
  [[nodiscard]] const config::Case& input() const { return case_; }
  [[nodiscard]] const Numerics& numerics() const { return numerics_; }
  [[nodiscard]] double delta_p_j() const { return delta_p_j_; }
  [[nodiscard]] double hole_area() const { return model_->hole_area(); }

 private:
  void update_container_force(double damping);
  [[nodiscard]] double grounding_mass() const;
  // The container's mass from the release on (with the counterweight's with a rigid wire).
  void set_apparatus_inertia();
  // Tension of an elastic wire beyond the counterweight's weight, on the container [N].
  [[nodiscard]] double wire_tension() const;
  void advance_gas();
  // The phases of prepare(): each returns false, with prep.message saying why, when the popper
  // cannot go on to the next. buckle() puts the words of its outcome in prep.message on success
  // too, and prepare() adds those of the later phases.
  // buckle() returns the suction it leaves the shell under [Pa] (nothing: it did not invert).
  std::optional<double> buckle(Preparation& prep, const Progress& progress, double pc);
  bool buckled_quasi_statically(Preparation& prep, const ShellModel::QuasiStaticBuckle& qs,
                                double pc);
  bool set_delta_p_j(Preparation& prep, const Progress& progress, double pc, double from);
  bool ground(Preparation& prep, const Progress& progress, double pc);
  // "held at delta_p_j = ... Pa (... p_c)", for the preparation's message.
  [[nodiscard]] std::string held_words(double pc) const;
  // The protocol's one test of "inverted": the apex above the outer rim.
  [[nodiscard]] bool inverted() const { return model_->apex_z() > model_->outer_rim_z(); }
  // The buckling pressure in words, with the ramp it was measured under.
  [[nodiscard]] std::string describe_onset(const Preparation& prep, double pc) const;
  // Zoelly's p_c of the case's shell [Pa].
  [[nodiscard]] double zoelly_pc() const;
  // Marks the preparation begun; throws std::logic_error when it had begun already (or a state
  // was loaded).
  void begin_preparation(const char* call);

  config::Case case_;
  Numerics numerics_;
  // Built before the gas, whose reference volume holds the undeformed cavity.
  std::unique_ptr<ShellModel> model_;
  Gas gas_;
  core::RigidBody container_;
  // With an elastic wire: the counterweight, its z being how far the popper would have risen
  // with a rigid wire (its own fall); unused with a rigid wire.
  core::RigidBody counterweight_;
  double delta_p_j_ = 0.0;
  PreparationSettings settings_;
  bool begun_ = false;     // prepare() or buckle() has run, or a state was loaded
  bool grounded_ = false;  // on the plate, ready for release()
  double shell_mass_ = 0.0;
  double z_release_ = 0.0;  // container z at t = 0
  double impulse_ = 0.0;    // plate impulse since the last sample
  double impulse_time_ = 0.0;
  FoldSchedule sample_folds_;  // sample()'s, from the first sample on
};

}  // namespace snapjump::popper
