#include "popper/popper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "fem/body.hpp"
#include "measure/analysis.hpp"
#include "popper/axi_shell.hpp"
#include "popper/mpm_shell.hpp"
#include "popper/state_io.hpp"
#include "theory/scaling.hpp"

namespace snapjump::popper {
namespace {

constexpr double kG = config::kStandardGravity;

}  // namespace

Numerics resolve_numerics(const config::Case& c) {
  Numerics n;
  n.model = c.numerics.model;
  n.reduced_bulk = c.numerics.bulk_integration.value_or(n.model == config::Model::Axisymmetric
                                                            ? config::BulkIntegration::Reduced
                                                            : config::BulkIntegration::Full) ==
                   config::BulkIntegration::Reduced;
  n.cap = mesh::cap_spec(c);
  n.mesh_file = c.shell.mesh;
  if (!n.mesh_file.empty() && n.model == config::Model::Axisymmetric) {
    throw config::CaseError(fmt::format(
        "{}: shell.mesh ({}) is a 3D shape; the axisymmetric model meshes the spherical cap of "
        "R, h, phi itself: run it with numerics.model = \"3d\"",
        c.source, n.mesh_file));
  }
  // A designer's mesh is read here, before a run writes anything: a defect is an input error.
  if (!n.mesh_file.empty()) n.user_mesh = std::make_shared<const mesh::Mesh>(load_user_mesh(c));
  n.axi_through = c.numerics.elements_through_thickness.value_or(
      config::preset(c.numerics.resolution).axi_through);
  n.axi_along =
      c.numerics.element_size
          ? std::max(
                2, static_cast<int>(std::ceil(c.shell.R * c.shell.phi / *c.numerics.element_size)))
          : axi::elements_along(c.shell.R, c.shell.h, c.shell.phi, n.axi_through);
  if (c.numerics.crease_fan && n.model != config::Model::Axisymmetric) {
    throw config::CaseError(fmt::format(
        "{}: numerics.crease_fan places a crease's root in the axisymmetric mesh: run it with "
        "numerics.model = \"axisymmetric\"",
        c.source));
  }
  if (c.numerics.fan_layer.value_or(0) > 0 && n.model != config::Model::Axisymmetric) {
    throw config::CaseError(fmt::format(
        "{}: numerics.fan_layer tiles the axisymmetric mesh's first layers: run it with "
        "numerics.model = \"axisymmetric\"",
        c.source));
  }
  n.axi_fan_layer = c.numerics.fan_layer.value_or(0);
  if (n.axi_fan_layer > 0 && c.numerics.crease_fan) {
    throw config::CaseError(
        fmt::format("{}: numerics.fan_layer makes every inner corner node a crease's root: give no "
                    "numerics.crease_fan with it",
                    c.source));
  }
  if (c.numerics.crease_seed && n.model != config::Model::Axisymmetric) {
    throw config::CaseError(
        fmt::format("{}: numerics.crease_seed seeds a crease in the axisymmetric mesh: run it with "
                    "numerics.model = \"axisymmetric\"",
                    c.source));
  }
  if (c.protocol.inverted_snaps != config::InvertedSnaps::InTime &&
      n.model != config::Model::Axisymmetric) {
    throw config::CaseError(fmt::format(
        "{}: protocol.inverted_snaps = \"{}\" follows the axisymmetric model's pressure-volume "
        "branch: run it with numerics.model = \"axisymmetric\"",
        c.source, to_string(c.protocol.inverted_snaps)));
  }
  for (const auto& seed : {c.numerics.crease_seed, c.numerics.second_crease_seed}) {
    if (seed) n.axi_crease_seeds.push_back(*seed);
  }
  n.axi_crease_seed_depth = c.numerics.crease_seed_depth.value_or(0.0);
  n.axi_crease_fan = c.numerics.crease_fan.value_or(0.0);
  n.axi_crease_fan_band = c.numerics.crease_fan_band.value_or(0.0);
  // The plate acts on a particle whose stencil holds a plate node, i.e. from up to 1.5 cells
  // away, and a shell pressed on it stands a fraction of a cell off (docs/validation.md,
  // "Standoff"): the cell is a fraction of the thickness h, which sets the scale of the
  // indentation e* = alpha_e h, never of R. No coarser than the elements either.
  n.dx = c.numerics.grid_spacing.value_or(
      c.shell.h / config::preset(c.numerics.resolution).grid_cells_per_thickness);
  n.dx = std::min(n.dx, n.cap.element_size);
  n.end_time = c.numerics.end_time ? *c.numerics.end_time : default_end(c).cap;
  n.time_step_factor = c.numerics.time_step_factor.value_or(kTimeStepFactor);
  // Damping of the preparation phases: a third of the shell's membrane frequency sqrt(E/rho)/R.
  n.prep_damping = 0.3 * std::sqrt(c.material.E / c.material.rho) / c.shell.R;
  return n;
}

DefaultEnd default_end(const config::Case& c) {
  DefaultEnd d;
  const double dp = theory::jump_pressure(c);
  const double cavity = theory::cavity_volume(c.shell.R, c.shell.h, c.shell.phi);
  const double share = 2.0 * cavity / (c.gas.container_volume + cavity);
  const double a = c.gas.alpha_n * dp, b = c.gas.beta_n * dp;
  // The positive root of b t + a t^2 / 2 = share, in the form that stays exact for small a.
  d.refill = dp > 0.0 ? 2.0 * share / (b + std::sqrt(b * b + 2.0 * a * share))
                      : std::numeric_limits<double>::infinity();
  const auto p = theory::predict(c, theory::contact_constants());
  d.height = p.H.hi;
  const double mg = c.popper.net_weight;
  if (d.height > 0.0 && mg > 0.0) d.rise = std::sqrt(2.0 * d.height * c.popper.moving_mass() / mg);
  d.cap = kRefillsBeforeTheCap * d.refill + 2.0 * d.rise;
  if (!(d.cap < kLongestDefaultEnd)) d.cap = kLongestDefaultEnd;  // also where it is not finite
  return d;
}

bool FlightWatch::apex_reached(const Sample& s) {
  // The analysis's own onset and launch rules: the run stops where the analysis will find a
  // snap and a flight.
  see_apex_gap(s.w);
  if (snapped && s.contact == measure::ContactState::None && s.F == 0.0) {
    if (airborne_since < 0 && s.vz > 0.0) airborne_since = s.t;
  } else {
    airborne_since = -1.0;
  }
  return airborne_since >= 0 && s.t - airborne_since > measure::AnalysisOptions{}.min_flight_time &&
         s.vz < 0.0;
}

bool apex_down(double w, double R) { return w < measure::AnalysisOptions{}.onset_ratio * R; }

void FlightWatch::see_apex_gap(double w) {
  if (apex_down(w, R)) snapped = true;
}

std::vector<std::string> sample_columns() {
  return {"t", "z",       "r",  "w",       "e",       "e_apex",
          "F", "delta_p", "vz", "kinetic", "elastic", "gravitational"};
}

std::vector<double> sample_values(const Sample& s) {
  return {s.t, s.z,       s.r,  s.w,       s.e,       s.e_apex,
          s.F, s.delta_p, s.vz, s.kinetic, s.elastic, s.gravitational};
}

void check_simulable(const config::Case& c) {
  if (!(c.material.nu < 0.5)) {
    throw config::CaseError(
        "material.nu = 0.5 is incompressible: the simulator's compressible neo-Hookean body "
        "needs nu < 0.5 (use 0.49 for a nearly incompressible elastomer)");
  }
}

std::unique_ptr<ShellModel> make_shell_model(const config::Case& c, const Numerics& n,
                                             std::function<double()> delta_p) {
  check_simulable(c);
  if (n.model == config::Model::Axisymmetric) {
    return std::make_unique<AxiShell>(c, n, std::move(delta_p));
  }
  return std::make_unique<MpmShell>(c, n, std::move(delta_p));
}

Popper::Popper(const config::Case& c, const Numerics& n, const PreparationSettings& settings)
    : case_(c),
      numerics_(n),
      model_(make_shell_model(c, n, [this] { return gas_.delta_p(); })),
      // The paper's reference state: the undeformed popper filled with air at p0.
      gas_(c.gas.p0, c.gas.alpha_n, c.gas.beta_n,
           c.gas.container_volume + model_->undeformed_cavity_volume()),
      settings_(settings) {
  shell_mass_ = model_->shell_mass();
  if (c.popper.wire_stiffness && !(c.popper.counterweight() > 0.0)) {
    throw config::CaseError(
        "popper.wire_stiffness is set but there is no counterweight (popper.mass = net_weight / "
        "g): remove the wire or give a heavier popper.mass");
  }
  if (c.popper.mass <= shell_mass_) {
    throw config::CaseError(fmt::format(
        "popper.mass = {:.4g} kg is not more than the shell's own mass {:.4g} kg: the popper's "
        "mass is the shell's plus the container's and the rail's",
        c.popper.mass, shell_mass_));
  }
  delta_p_j_ = theory::jump_pressure(c);
  container_.mass = grounding_mass();
  const auto& st = settings_;
  if (!(st.buckle_factor > 0.0 && st.held_damping > 0.0 && st.ramp > 0.0 && st.max_wait >= 0.0 &&
        st.progress_every > 0 && st.fast_to >= 0.0 && st.fast_to < st.buckle_factor &&
        st.fast_ramp >= 0.0 && st.fast_ramp < st.ramp && st.onset_sample_every > 0 &&
        st.onset_factor > 1.0 && st.reference_window[0] >= 0.0 &&
        st.reference_window[1] > st.reference_window[0] &&
        st.reference_window[1] < st.buckle_factor)) {
    throw std::invalid_argument(
        "PreparationSettings: buckle_factor, held_damping and ramp must be positive, max_wait not "
        "negative, "
        "fast_to from 0 to below buckle_factor, fast_ramp from 0 to below ramp, "
        "progress_every and onset_sample_every at least 1, onset_factor above 1, the reference "
        "window an interval of pressures from 0 up that ends below buckle_factor");
  }
}

double Popper::grounding_mass() const {
  // The grounding is quasi-static (only its end state matters): the container's inertia is scaled
  // to its share of the net weight, so that it settles on the shell as fast whatever the
  // counterweight. release() gives it the apparatus's inertia.
  return std::max(case_.popper.net_weight / kG, 2.0 * shell_mass_) - shell_mass_;
}

void Popper::update_container_force(double damping) {
  // Its share of the net weight, the gas on the hole (inside minus outside pressure), damping,
  // and with an elastic wire the wire's tension beyond the counterweight's weight.
  container_.applied_force = -(case_.popper.net_weight - shell_mass_ * kG) -
                             gas_.delta_p() * model_->hole_area() -
                             damping * container_.mass * container_.vz + wire_tension();
}

void Popper::set_apparatus_inertia() {
  const bool elastic_wire = case_.popper.wire_stiffness.has_value();
  container_.mass = (elastic_wire ? case_.popper.mass : case_.popper.moving_mass()) - shell_mass_;
  counterweight_.mass = case_.popper.counterweight();
}

double Popper::wire_tension() const {
  if (!case_.popper.wire_stiffness || !gas_.valve_open()) return 0.0;
  return *case_.popper.wire_stiffness * (counterweight_.z - container_.z);
}

// The paper's coupling: the pressure from the current volume and amount of air (paper, Eqs. S12,
// S13), which the next step's forces apply to the shell (paper, Eq. S11).
void Popper::advance_gas() {
  gas_.advance(model_->dt(), model_->cavity_volume() + case_.gas.container_volume);
}

SnapOnset::SnapOnset(double p_low, double p_high, double factor)
    : p_low_(p_low), p_high_(p_high), factor_(factor) {}

void SnapOnset::sample(double t, double V, double p) {
  if (onset_) return;
  if (sampled_ && !(t > last_t_)) return;  // a sample no later than the last tells nothing
  const bool first = !sampled_;
  const double rate = first ? 0.0 : -(V - last_V_) / (t - last_t_);
  sampled_ = true;
  last_t_ = t;
  last_V_ = V;
  if (first) return;
  if (p >= p_low_ && p <= p_high_) {
    reference_sum_ += rate;
    ++reference_count_;
  } else if (p > p_high_ && reference_count_ > 0 && reference_sum_ > 0.0 &&
             rate > factor_ * reference_sum_ / reference_count_) {
    onset_ = p;
  }
}

double Popper::buckling_suction(double t, double pc) const {
  const auto& st = settings_;
  const double p_fast = st.fast_to * pc, p_buckle = st.buckle_factor * pc;
  if (t < st.fast_ramp) return p_fast * t / st.fast_ramp;
  return p_fast +
         (p_buckle - p_fast) * std::min(1.0, (t - st.fast_ramp) / (st.ramp - st.fast_ramp));
}

double Popper::zoelly_pc() const {
  return theory::zoelly_pressure(case_.material.E, case_.shell.h, case_.shell.R, case_.material.nu);
}

void Popper::begin_preparation(const char* call) {
  if (begun_) {
    throw std::logic_error(
        fmt::format("Popper::{}() on a popper that has already been prepared", call));
  }
  begun_ = true;
}

Preparation Popper::buckle(const Progress& progress) {
  begin_preparation("buckle");
  Preparation prep;
  (void)buckle(prep, progress, zoelly_pc());
  return prep;
}

std::string Popper::describe_onset(const Preparation& prep, double pc) const {
  if (!prep.buckling_pressure) {
    return "onset of the snap not seen (the cavity never shrank onset_factor times faster than "
           "while the suction crossed the reference window)";
  }
  // Under a fast ramp the onset lags the pressure: the words say which ramp it was.
  return fmt::format("snap onset at {:.0f} Pa ({:.3f} p_c, suction ramped over {:.0f} ms)",
                     *prep.buckling_pressure, *prep.buckling_pressure / pc, 1e3 * settings_.ramp);
}

Preparation Popper::prepare(const Progress& progress) {
  begin_preparation("prepare");
  Preparation prep;
  const double pc = zoelly_pc();
  const auto suction = buckle(prep, progress, pc);
  if (!suction) return prep;
  // A fold in phases 2-3 carries what phase 1 found (where the shell buckled, the state it was
  // left in) in its message, which the run's summary keeps as its status.
  try {
    if (!set_delta_p_j(prep, progress, pc, *suction)) return prep;
    if (!ground(prep, progress, pc)) return prep;
  } catch (const fem::FoldedElement& e) {
    throw fem::FoldedElement(fmt::format("after the shell {}", prep.message), e);
  }
  if (const auto s = model_->inner_surface_compression()) {
    prep.surface_ratio = s->ratio;
    prep.surface_from_rim = s->from_rim;
    prep.surface_closed_creases = s->closed_creases;
  }
  prep.message +=
      fmt::format(", {}, grounded in {:.0f} ms: plate force {:.3f} N for a net weight of {:.3f} N",
                  held_words(pc), 1e3 * model_->time(), prep.plate_force, case_.popper.net_weight);
  return prep;
}

std::string Popper::held_words(double pc) const {
  return fmt::format("held at delta_p_j = {:.0f} Pa ({:.2f} p_c)", delta_p_j_, delta_p_j_ / pc);
}

// Phase 1, container held in the air: raise the suction past the buckling pressure until the
// shell inverts. The syringe holds the pressure difference: the gas is held at it before each
// step. Where the model follows the pressure-volume branch instead (settings.quasi_static), the
// shell is put at rest in its equilibrium at delta_p_j on the inverted segment: the end state of
// phases 1 and 2 together. Returns the suction the shell is left under, or nothing.
std::optional<double> Popper::buckle(Preparation& prep, const Progress& progress, double pc) {
  const auto& st = settings_;
  auto& m = *model_;
  const double p_buckle = st.buckle_factor * pc;
  m.start_held(st.held_damping * numerics_.prep_damping);
  if (st.quasi_static) {
    // The run's progress (and its stop hook, which throws) at every point of the branch.
    const auto at_point = [&] {
      if (progress) progress("buckle (branch)", 0.0, 0.0);
    };
    if (const auto qs = m.buckle_quasi_statically(
            delta_p_j_, pc, case_.protocol.inverted_snaps == config::InvertedSnaps::AlongBranch,
            at_point)) {
      gas_.hold(qs->dp);
      if (!buckled_quasi_statically(prep, *qs, pc)) return std::nullopt;
      return qs->dp;
    }
  }
  SnapOnset onset(st.reference_window[0] * pc, st.reference_window[1] * pc, st.onset_factor);
  FoldSchedule folds(m.time() + kFoldCheckInterval);
  while (m.time() < st.ramp + st.max_wait) {
    const double p = buckling_suction(m.time(), pc);
    gas_.hold(p);
    m.step();
    if (folds.due(m.time())) m.check_folds();
    if (!onset.pressure() && m.steps() % st.onset_sample_every == 0) {
      onset.sample(m.time(), m.cavity_volume(), p);
      prep.buckling_pressure = onset.pressure();
    }
    if (m.steps() % st.progress_every == 0) {
      // At most ramp + max_wait: the fraction is of that bound.
      if (progress) progress("buckle", m.time(), m.time() / (st.ramp + st.max_wait));
      if (inverted() && m.kinetic_energy() < st.settled_energy * shell_mass_) {
        m.check_folds();
        prep.inverted = true;
        prep.message = fmt::format("inverted under {:.0f} Pa ({:.2f} p_c), {}", p_buckle,
                                   st.buckle_factor, describe_onset(prep, pc));
        return p_buckle;
      }
    }
  }
  prep.message = fmt::format("the shell did not invert under {:.0f} Pa ({:.1f} p_c)", p_buckle,
                             st.buckle_factor);
  return std::nullopt;
}

bool Popper::buckled_quasi_statically(Preparation& prep, const ShellModel::QuasiStaticBuckle& qs,
                                      double pc) {
  const auto known = [](double p) { return std::isfinite(p) ? std::optional(p) : std::nullopt; };
  prep.buckling_pressure = known(qs.p_c);
  prep.reverse_pressure = known(qs.p_minus);
  prep.hold_pressure = known(qs.p_hold);
  if (!std::isfinite(qs.p_c)) {
    prep.message = fmt::format(
        "the shell did not invert: its quasi-static branch ended before a buckling maximum: {}",
        qs.note);
    return false;
  }
  // At the foot of an inverted segment above delta_p_j (its minimum, p_hold, lies above it) the
  // state is a limit point's neighbour: the lowered suction of phase 2 decides what follows.
  // Where the segment turns down at a maximum below delta_p_j (a limit point: a subcritical
  // crease's nucleation), or where its equilibria stop being stable (a bifurcation), the shell
  // snaps under the suction there: phase 2's dynamics take it from that state, as the dynamics
  // take the natural state through buckling.
  const bool foot = qs.foot;
  if (!(qs.reached || qs.snaps) || !(qs.stable || foot || qs.snaps) || !inverted()) {
    prep.message = fmt::format(
        "the pressure-volume branch did not bring the shell to a stable inverted state under "
        "{:.0f} Pa ({:.2f} p_c){}{}",
        delta_p_j_, delta_p_j_ / pc, qs.note.empty() ? "" : ": ", qs.note);
    return false;
  }
  model_->check_folds();
  prep.inverted = true;
  const auto where =
      foot ? fmt::format(
                 "to the foot of its inverted segment at {:.0f} Pa ({:.3f} p_c), above "
                 "delta_p_j",
                 qs.dp, qs.dp / pc)
      : qs.snaps ? fmt::format(
                       "to the {} of its inverted segment at {:.0f} Pa ({:.3f} p_c), below "
                       "delta_p_j, to snap from there in time",
                       qs.loses_stability ? "last state stable under pressure control" : "maximum",
                       qs.dp, qs.dp / pc)
                 : fmt::format("to its inverted equilibrium at delta_p_j, {:.0f} Pa ({:.2f} p_c)",
                               qs.dp, qs.dp / pc);
  // Along the branch (protocol.inverted_snaps): the maxima it snapped past, and where it ended
  // before delta_p_j, why.
  std::string passed;
  for (const double p : qs.passed_maxima) {
    passed += fmt::format("{}{:.3f}", passed.empty() ? "" : ", ", p / pc);
  }
  if (!passed.empty()) {
    passed = fmt::format(
        " (snapped along the branch past the inverted segment's maxima at {} p_c{}{})", passed,
        qs.reached ? "" : "; the branch then ended: ", qs.reached ? "" : qs.note);
  }
  const auto hold =
      std::isfinite(qs.p_hold)
          ? fmt::format("holds fully inverted down to {:.0f} Pa ({:.3f} p_c)", qs.p_hold,
                        qs.p_hold / pc)
          : std::string("holds fully inverted down to a suction the branch did not reach");
  // The branch is followed through its maximum wherever it lies; the dynamic ramp would stop at
  // buckle_factor p_c, which a cap that buckles out of symmetry (the 3D model, a real shell) may
  // pass below.
  const auto beyond =
      qs.p_c > settings_.buckle_factor * pc
          ? fmt::format(
                " (above the {:.1f} p_c of the dynamic ramp: the suction is raised along the "
                "axisymmetric branch until the shell inverts)",
                settings_.buckle_factor)
          : std::string();
  prep.message = fmt::format(
      "inverted along the quasi-static pressure-volume branch {}{}: it buckles at {:.0f} Pa "
      "({:.3f} p_c){}, {} and has no buckled state below {:.0f} Pa ({:.3f} p_c)",
      where, passed, qs.p_c, qs.p_c / pc, beyond, hold, qs.p_minus, qs.p_minus / pc);
  return true;
}

// Phase 2, still in the air: bring the suction from phase 1's, `from` [Pa], to delta_p_j and let
// the shell settle (where phase 1 left it at delta_p_j already, this only checks in time that it
// stays).
bool Popper::set_delta_p_j(Preparation& prep, const Progress& progress, double pc, double from) {
  const auto& st = settings_;
  auto& m = *model_;
  const double t0 = m.time();
  FoldSchedule folds(m.time() + kFoldCheckInterval);
  while (m.time() < t0 + st.down + st.settle) {
    const double f = std::min(1.0, (m.time() - t0) / st.down);
    gas_.hold(from + f * (delta_p_j_ - from));
    m.step();
    if (folds.due(m.time())) m.check_folds();
    if (progress && m.steps() % st.progress_every == 0)
      progress("set delta_p_j", m.time() - t0, (m.time() - t0) / (st.down + st.settle));
  }
  m.check_folds();
  if (!inverted()) {
    prep.message =
        fmt::format("the inverted shell snapped back at delta_p_j = {:.0f} Pa ({:.2f} p_c)",
                    delta_p_j_, delta_p_j_ / pc);
    return false;
  }
  prep.held = true;
  return true;
}

// Phase 3, ground: lower the popper onto the plate and let the container go, damped, until the
// plate carries the net weight. A shell whose apex is then on the plate by the analysis's own
// onset rule (w / R below onset_ratio) has snapped back under the weight: the release would have
// no snap to measure, and the analysis would take its onset at the release's first sample.
bool Popper::ground(Preparation& prep, const Progress& progress, double pc) {
  const auto& st = settings_;
  auto& m = *model_;
  gas_.hold(delta_p_j_);
  container_.z = 0.0;
  container_.vz = 0.0;
  m.start_on_plate(container_, case_.friction.mu, numerics_.prep_damping);
  grounded_ = true;
  const double damping = numerics_.prep_damping / st.ground_damping_divisor;
  m.set_damping(damping);
  double impulse = 0.0, window = 0.0;
  int good_windows = 0;
  FoldSchedule folds(m.time() + kFoldCheckInterval);
  while (m.time() < st.max_time) {
    update_container_force(damping);
    m.step();
    if (folds.due(m.time())) m.check_folds();
    impulse += m.plate_force() * m.dt();
    window += m.dt();
    if (window >= st.window) {
      prep.plate_force = impulse / window;
      const bool good =
          std::abs(prep.plate_force / case_.popper.net_weight - 1.0) < st.weight_tolerance;
      good_windows = good ? good_windows + 1 : 0;
      impulse = window = 0.0;
      if (good_windows >= st.good_windows) break;
    }
    if (progress && m.steps() % st.progress_every == 0) {
      progress("ground", m.time(), m.time() / st.max_time);
    }
  }
  m.check_folds();
  if (apex_down(m.apex_z(), case_.shell.R)) {
    prep.held = false;
    prep.snapped_back_on_plate = true;
    grounded_ = false;  // nothing to release
    prep.message = fmt::format(
        "{}, {}, but it snapped back as it was grounded: after {:.0f} ms on the plate its apex "
        "stands {:.3g} mm above it (w / R = {:.3g}, below the onset's {}), so the release would "
        "have no snap",
        prep.message, held_words(pc), 1e3 * m.time(), 1e3 * m.apex_z(), m.apex_z() / case_.shell.R,
        measure::AnalysisOptions{}.onset_ratio);
    return false;
  }
  return true;
}

namespace {

// Version 2: J_n referred to the undeformed popper (version 1 referred it to the release).
// Version 3: the 3D shell's particles in the order of mesh::sort_along_curve, after a fingerprint
// of that order.
constexpr char kStateMagic[] = "snapjump-popper-state-3";

}  // namespace

void Popper::save_state(std::ostream& out) const {
  if (!gas_.valve_open()) throw std::logic_error("save_state() before release()");
  out.write(kStateMagic, sizeof kStateMagic);
  model_->save_state(out);
  put(out, container_.z);
  put(out, container_.vz);
  put(out, container_.clamp_force);
  put(out, counterweight_.z);
  put(out, counterweight_.vz);
  put(out, gas_.delta_p());
  put(out, gas_.J_n());
  put(out, gas_.J_n_rate());
  put(out, gas_.V_ref());
  put(out, z_release_);
  put(out, impulse_);
  put(out, impulse_time_);
  if (!out) throw std::runtime_error("writing the popper's state failed");
}

void Popper::load_state(std::istream& in) {
  char magic[sizeof kStateMagic] = {};
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kStateMagic, sizeof kStateMagic) != 0) {
    throw std::runtime_error("not a snapjump checkpoint of this version");
  }
  model_->load_state(in, container_, case_.friction.mu);
  grounded_ = true;
  begun_ = true;
  container_.z = get_finite(in, "container height");
  container_.vz = get_finite(in, "container velocity");
  container_.clamp_force = get_finite(in, "clamp force");
  set_apparatus_inertia();
  counterweight_.z = get_finite(in, "counterweight height");
  counterweight_.vz = get_finite(in, "counterweight velocity");
  const double dp = get_finite(in, "pressure difference");
  const double J_n = get_finite(in, "amount of air");
  const double J_n_rate = get_finite(in, "rate of inflow");
  const double V_ref = get_finite(in, "gas reference volume");
  if (!(std::abs(V_ref / gas_.V_ref() - 1.0) < 1e-12)) {
    throw std::runtime_error(fmt::format(
        "the checkpoint's gas reference volume {:.6g} m^3 is not this popper's {:.6g} m^3", V_ref,
        gas_.V_ref()));
  }
  if (!(J_n > 0.0)) throw std::runtime_error("the checkpoint's amount of air is not positive");
  gas_.restore(dp, true, J_n, J_n_rate);
  z_release_ = get_finite(in, "release height");
  impulse_ = get_finite(in, "plate impulse");
  impulse_time_ = get_finite(in, "impulse time");
  if (impulse_time_ < 0.0) throw std::runtime_error("the checkpoint's impulse time is negative");
}

void Popper::release() {
  if (!grounded_) throw std::logic_error("release() before a successful prepare()");
  model_->set_damping(0.0);
  // Start the physical run from rest: the damped settling leaves tiny velocities.
  model_->zero_velocities();
  container_.vz = 0.0;
  // From here on the inertia is the apparatus's: with a rigid wire the counterweight moves with
  // the popper; with an elastic one it is a second body, at rest in its equilibrium.
  set_apparatus_inertia();
  counterweight_.z = container_.z;
  counterweight_.vz = 0.0;
  model_->reset_time();
  z_release_ = container_.z;
  gas_.open_valve(model_->cavity_volume() + case_.gas.container_volume);
  impulse_ = 0.0;
  impulse_time_ = 0.0;
}

void Popper::step() {
  update_container_force(0.0);
  const double tension = wire_tension();
  model_->step();
  const double dt = model_->dt();
  if (case_.popper.wire_stiffness) {
    // The counterweight, in the popper's frame (z up when the counterweight goes down), pulled
    // back by the wire's tension beyond its weight.
    counterweight_.vz += dt * -tension / counterweight_.mass;
    counterweight_.z += dt * counterweight_.vz;
  }
  advance_gas();
  impulse_ += model_->plate_force() * dt;
  impulse_time_ += dt;
}

Sample Popper::sample() {
  Sample s;
  s.t = model_->time();
  s.z = container_.z - z_release_;
  s.vz = container_.vz;
  s.delta_p = gas_.delta_p();
  s.F = impulse_time_ > 0.0 ? impulse_ / impulse_time_ : model_->plate_force();
  impulse_ = 0.0;
  impulse_time_ = 0.0;
  const auto contact = model_->contact();
  s.r = contact.r;
  s.w = model_->apex_z();
  s.contact = !contact.any
                  ? measure::ContactState::None
                  : (contact.apex ? measure::ContactState::Disk : measure::ContactState::Ring);
  const double rim = model_->outer_rim_z();
  const double depth = model_->undeformed_depth();
  s.e = depth - rim;
  s.e_apex = depth - (rim - s.w);
  s.kinetic = model_->kinetic_energy() + 0.5 * container_.mass * container_.vz * container_.vz;
  if (case_.popper.wire_stiffness) {
    s.kinetic += 0.5 * counterweight_.mass * counterweight_.vz * counterweight_.vz;
  }
  if (sample_folds_.due(s.t)) model_->check_folds();
  s.elastic = model_->strain_energy();
  // The counterweight's weight is the popper's less mg; an elastic wire adds its stretch's
  // energy beyond the static one.
  s.gravitational =
      model_->potential_energy(kG) + (case_.popper.net_weight - shell_mass_ * kG) * container_.z;
  if (case_.popper.wire_stiffness) {
    const double stretch = counterweight_.z - container_.z;
    s.gravitational += 0.5 * *case_.popper.wire_stiffness * stretch * stretch;
  }
  return s;
}

}  // namespace snapjump::popper
