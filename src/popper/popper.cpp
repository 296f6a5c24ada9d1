#include "popper/popper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "fem/explicit.hpp"
#include "theory/scaling.hpp"

namespace snapjump::popper {
namespace {

constexpr double kG = config::kStandardGravity;

}  // namespace

double grid_cells_per_thickness(config::Resolution r) {
  switch (r) {
    case config::Resolution::Coarse:
      return kCellsPerThicknessCoarse;
    case config::Resolution::Default:
      return kCellsPerThicknessDefault;
    case config::Resolution::Fine:
      return kCellsPerThicknessFine;
  }
  return kCellsPerThicknessDefault;
}

Numerics resolve_numerics(const config::Case& c) {
  Numerics n;
  n.cap = mesh::cap_spec(c);
  // The plate acts on a particle whose stencil holds a plate node, i.e. from up to 1.5 cells
  // away, and a shell pressed on it stands a fraction of a cell off (docs/validation.md,
  // "Standoff"): the cell is a fraction of the thickness h, which sets the scale of the
  // indentation e* = alpha_e h, never of R. No coarser than the elements either.
  n.dx =
      c.numerics.grid_spacing.value_or(c.shell.h / grid_cells_per_thickness(c.numerics.resolution));
  n.dx = std::min(n.dx, n.cap.element_size);
  if (c.numerics.end_time) n.end_time = *c.numerics.end_time;
  // Damping of the preparation phases: a third of the shell's membrane frequency sqrt(E/rho)/R.
  n.prep_damping = 0.3 * std::sqrt(c.material.E / c.material.rho) / c.shell.R;
  return n;
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

namespace {

std::unique_ptr<fem::Body> make_shell(const config::Case& c, const Numerics& n) {
  check_simulable(c);
  return std::make_unique<fem::Body>(
      mesh::make_cap_mesh(n.cap),
      fem::Material::from_young(c.material.E, c.material.nu, c.material.rho));
}

}  // namespace

Popper::Popper(const config::Case& c, const Numerics& n)
    : case_(c),
      numerics_(n),
      body_(make_shell(c, n)),
      // The paper's reference state: the undeformed popper filled with air at p0.
      gas_(c.gas.p0, c.gas.alpha_n, c.gas.beta_n,
           c.gas.container_volume + body_->cavity_volume(body_->mesh().nodes)) {
  shell_mass_ = body_->total_mass();
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
  const auto& X = body_->mesh().nodes;
  // The hole of the container is the inner rim circle, whose area the pressure on the inner faces
  // projects onto: pressure forces on shell and container then cancel exactly.
  double rim_r = 0.0;
  int count = 0;
  std::vector<char> outer(X.size(), 0), inner(X.size(), 0);
  for (int a : body_->mesh().outer) outer[a] = 1;
  for (const auto& f : body_->mesh().inner_faces) {
    for (int a : f) inner[a] = 1;
  }
  for (int a : body_->mesh().clamped) {
    if (inner[a]) {
      rim_r += std::hypot(X.x[a], X.y[a]);
      ++count;
    }
    if (outer[a]) outer_rim_.push_back(a);
  }
  hole_area_ = std::numbers::pi * std::pow(rim_r / count, 2);
  depth_outer_ = outer_rim_z(X) - X.z[body_->mesh().apex];

  forces_ =
      std::make_unique<mpm::BodyForces>(*body_, kG, [this](double) { return gas_.delta_p(); });
  // The grid bound assumes speeds up to 2 m/s (a jump of 20 cm); faster particles stop the run
  // with a StepError from the stepper's own CFL check.
  time_step_ = mpm::choose_time_step(body_->stable_time_step(n.cfl), n.dx, 2.0, 0.5);
  container_.mass = grounding_mass();
}

double Popper::outer_rim_z(const mesh::Points& x) const {
  double z = 0.0;
  for (int a : outer_rim_) z += x.z[a];
  return z / static_cast<double>(outer_rim_.size());
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
                             gas_.delta_p() * hole_area_ -
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

void Popper::advance_gas() {
  gas_.advance(stepper_->dt(),
               body_->cavity_volume(stepper_->particles().x) + case_.gas.container_volume);
}

Preparation Popper::prepare(const Progress& progress) {
  Preparation prep;
  const double pc =
      theory::zoelly_pressure(case_.material.E, case_.shell.h, case_.shell.R, case_.material.nu);
  const auto& mesh = body_->mesh();
  const auto inverted = [&](const mesh::Points& x) { return x.z[mesh.apex] > outer_rim_z(x); };

  // Phases 1 and 2, container held in the air: raise the suction past the buckling pressure
  // until the shell inverts, then bring it to delta_p_j and let it settle.
  const double p_buckle = 1.4 * pc;
  const double ramp = 0.02, max_wait = 0.1, down = 0.02, settle = 0.02;
  double p_now = 0.0;
  fem::ExplicitOptions eo;
  eo.cfl = numerics_.cfl;
  eo.damping = numerics_.prep_damping;
  eo.pressure = [&](double) { return p_now; };
  fem::ExplicitDriver d(*body_, eo);
  double t_inverted = -1.0;
  while (d.time() < ramp + max_wait) {
    p_now = p_buckle * std::min(1.0, d.time() / ramp);
    d.step();
    if (d.steps() % 200 == 0) {
      if (progress) progress("buckle", d.time(), -1.0);
      if (prep.buckling_pressure == 0.0 &&
          body_->cavity_volume(d.positions()) < 0.5 * body_->cavity_volume(mesh.nodes)) {
        prep.buckling_pressure = p_now;
      }
      if (inverted(d.positions()) && d.kinetic_energy() < 1e-3 * shell_mass_ * 1e-2) {
        t_inverted = d.time();
        break;
      }
    }
  }
  if (t_inverted < 0.0) {
    prep.message = fmt::format("the shell did not invert under {:.0f} Pa (1.4 p_c)", p_buckle);
    return prep;
  }
  prep.inverted = true;
  const double t0 = d.time();
  while (d.time() < t0 + down + settle) {
    const double f = std::min(1.0, (d.time() - t0) / down);
    p_now = p_buckle + f * (delta_p_j_ - p_buckle);
    d.step();
    if (progress && d.steps() % 200 == 0)
      progress("set delta_p_j", d.time() - t0, (d.time() - t0) / (down + settle));
  }
  if (!inverted(d.positions())) {
    prep.message =
        fmt::format("the inverted shell snapped back at delta_p_j = {:.0f} Pa ({:.2f} p_c)",
                    delta_p_j_, delta_p_j_ / pc);
    return prep;
  }
  prep.held = true;

  // Phase 3: ground. Lower the popper until its lowest point meets the plate's contact layer and
  // let the container go, damped, until the plate carries the net weight.
  auto x = d.positions();
  double lowest = std::numeric_limits<double>::infinity();
  for (double z : x.z) lowest = std::min(lowest, z);
  const double shift = 1.2 * numerics_.dx - lowest;
  for (auto& z : x.z) z += shift;
  auto particles = mpm::particles_of(*body_);
  particles.x = x;
  gas_.hold(delta_p_j_);
  build_stepper(std::move(particles), numerics_.prep_damping);
  container_.z = 0.0;
  container_.vz = 0.0;
  // Settle with a lighter damping (the container on the shell is a slower oscillator than the
  // shell alone) until the plate carries the net weight within 2 % over two 5 ms windows.
  const double ground_damping = numerics_.prep_damping / 3.0, window_length = 5e-3,
               max_ground_time = 0.2;
  stepper_->set_damping(ground_damping);
  double impulse = 0.0, window = 0.0;
  int good_windows = 0;
  while (stepper_->time() < max_ground_time) {
    update_container_force(ground_damping);
    stepper_->step();
    impulse += plate_->force() * stepper_->dt();
    window += stepper_->dt();
    if (window >= window_length) {
      prep.plate_force = impulse / window;
      const bool good = std::abs(prep.plate_force / case_.popper.net_weight - 1.0) < 0.02;
      good_windows = good ? good_windows + 1 : 0;
      impulse = window = 0.0;
      if (good_windows >= 2) break;
    }
    if (progress && stepper_->steps() % 200 == 0) {
      progress("ground", stepper_->time(), stepper_->time() / max_ground_time);
    }
  }
  prep.message = fmt::format(
      "inverted under {:.0f} Pa ({:.2f} p_c), held at delta_p_j = {:.0f} Pa ({:.2f} p_c), "
      "grounded in {:.0f} ms: plate force {:.3f} N for a net weight of {:.3f} N",
      p_buckle, p_buckle / pc, delta_p_j_, delta_p_j_ / pc, 1e3 * stepper_->time(),
      prep.plate_force, case_.popper.net_weight);
  return prep;
}

void Popper::build_stepper(mpm::Particles particles, double damping) {
  stepper_ = std::make_unique<mpm::Stepper>(
      std::move(particles), *forces_,
      mpm::StepperOptions{time_step_.dt, numerics_.dx, 0.5, damping});
  stepper_->add_rule(std::make_unique<mpm::ClampRule>(container_));
  plate_ = &dynamic_cast<mpm::PlateRule&>(
      stepper_->add_rule(std::make_unique<mpm::PlateRule>(case_.friction.mu)));
  stepper_->add_rigid_body(container_);
}

namespace {

// Version 2: J_n referred to the undeformed popper (version 1 referred it to the release).
constexpr char kStateMagic[] = "snapjump-popper-state-2";

template <typename T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
void get(std::istream& in, T& v) {
  in.read(reinterpret_cast<char*>(&v), sizeof v);
}
void put_vector(std::ostream& out, const std::vector<double>& v) {
  const std::uint64_t n = v.size();
  put(out, n);
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(n * sizeof(double)));
}
void get_vector(std::istream& in, std::vector<double>& v, std::size_t expected) {
  std::uint64_t n = 0;
  get(in, n);
  if (!in || n != expected)
    throw std::runtime_error("checkpoint does not match this popper's mesh");
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(double)));
}

}  // namespace

void Popper::save_state(std::ostream& out) const {
  if (!stepper_ || !gas_.valve_open()) throw std::logic_error("save_state() before release()");
  out.write(kStateMagic, sizeof kStateMagic);
  const auto& p = stepper_->particles();
  put(out, stepper_->time());
  put(out, stepper_->steps());
  for (const auto* v : {&p.x.x, &p.x.y, &p.x.z, &p.v.x, &p.v.y, &p.v.z, &p.C}) put_vector(out, *v);
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
  if (!in || std::string(magic) != kStateMagic)
    throw std::runtime_error("not a snapjump checkpoint");
  double time = 0.0;
  long steps = 0;
  get(in, time);
  get(in, steps);
  auto particles = mpm::particles_of(*body_);
  const std::size_t n = particles.size();
  for (auto* v : {&particles.x.x, &particles.x.y, &particles.x.z, &particles.v.x, &particles.v.y,
                  &particles.v.z}) {
    get_vector(in, *v, n);
  }
  get_vector(in, particles.C, 9 * n);
  build_stepper(std::move(particles), 0.0);
  stepper_->restore_clock(time, steps);
  get(in, container_.z);
  get(in, container_.vz);
  get(in, container_.clamp_force);
  set_apparatus_inertia();
  get(in, counterweight_.z);
  get(in, counterweight_.vz);
  double dp = 0, J_n = 0, J_n_rate = 0, V_ref = 0;
  get(in, dp);
  get(in, J_n);
  get(in, J_n_rate);
  get(in, V_ref);
  if (!(std::abs(V_ref / gas_.V_ref() - 1.0) < 1e-12)) {
    throw std::runtime_error(fmt::format(
        "the checkpoint's gas reference volume {:.6g} m^3 is not this popper's {:.6g} m^3", V_ref,
        gas_.V_ref()));
  }
  gas_.restore(dp, true, J_n, J_n_rate);
  get(in, z_release_);
  get(in, impulse_);
  get(in, impulse_time_);
  if (!in) throw std::runtime_error("the checkpoint is truncated");
}

void Popper::release() {
  if (!stepper_) throw std::logic_error("release() before a successful prepare()");
  stepper_->set_damping(0.0);
  // Start the physical run from rest: the damped settling leaves tiny velocities.
  auto& p = stepper_->particles();
  std::fill(p.v.x.begin(), p.v.x.end(), 0.0);
  std::fill(p.v.y.begin(), p.v.y.end(), 0.0);
  std::fill(p.v.z.begin(), p.v.z.end(), 0.0);
  std::fill(p.C.begin(), p.C.end(), 0.0);
  container_.vz = 0.0;
  // From here on the inertia is the apparatus's: with a rigid wire the counterweight moves with
  // the popper; with an elastic one it is a second body, at rest in its equilibrium.
  set_apparatus_inertia();
  counterweight_.z = container_.z;
  counterweight_.vz = 0.0;
  stepper_->reset_time();
  z_release_ = container_.z;
  gas_.open_valve(body_->cavity_volume(p.x) + case_.gas.container_volume);
  impulse_ = 0.0;
  impulse_time_ = 0.0;
}

void Popper::step() {
  update_container_force(0.0);
  const double tension = wire_tension();
  stepper_->step();
  if (case_.popper.wire_stiffness) {
    // The counterweight, in the popper's frame (z up when the counterweight goes down), pulled
    // back by the wire's tension beyond its weight.
    counterweight_.vz += stepper_->dt() * -tension / counterweight_.mass;
    counterweight_.z += stepper_->dt() * counterweight_.vz;
  }
  advance_gas();
  impulse_ += plate_->force() * stepper_->dt();
  impulse_time_ += stepper_->dt();
}

Sample Popper::sample() {
  const auto& p = stepper_->particles();
  const auto& mesh = body_->mesh();
  Sample s;
  s.t = stepper_->time();
  s.z = container_.z - z_release_;
  s.vz = container_.vz;
  s.delta_p = gas_.delta_p();
  s.F = impulse_time_ > 0.0 ? impulse_ / impulse_time_ : plate_->force();
  impulse_ = 0.0;
  impulse_time_ = 0.0;
  // Contact, as the camera sees it: the outer particles that the plate carries, i.e. that have at
  // least half of their stencil weight on the nodes the plate pushed in the last step. r is the
  // outermost; the contact is a disk when the apex is among them.
  const double dx = stepper_->dx();
  const auto touching = [&](int a) {
    return mpm::plate_carries(*plate_, dx, p.x.x[a], p.x.y[a], p.x.z[a]);
  };
  bool any = false;
  for (int a : mesh.outer) {
    if (touching(a)) {
      any = true;
      s.r = std::max(s.r, std::hypot(p.x.x[a], p.x.y[a]));
    }
  }
  const int apex = mesh.apex;
  s.w = p.x.z[apex];
  s.contact = !any ? measure::ContactState::None
                   : (touching(apex) ? measure::ContactState::Disk : measure::ContactState::Ring);
  const double rim = outer_rim_z(p.x);
  s.e = depth_outer_ - rim;
  s.e_apex = depth_outer_ - (rim - p.x.z[apex]);
  s.kinetic = stepper_->kinetic_energy() + 0.5 * container_.mass * container_.vz * container_.vz;
  if (case_.popper.wire_stiffness) {
    s.kinetic += 0.5 * counterweight_.mass * counterweight_.vz * counterweight_.vz;
  }
  s.elastic = body_->strain_energy(p.x);
  double pot = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) pot += p.mass[i] * kG * p.x.z[i];
  // The counterweight's weight is the popper's less mg; an elastic wire adds its stretch's
  // energy beyond the static one.
  s.gravitational = pot + (case_.popper.net_weight - shell_mass_ * kG) * container_.z;
  if (case_.popper.wire_stiffness) {
    const double stretch = counterweight_.z - container_.z;
    s.gravitational += 0.5 * *case_.popper.wire_stiffness * stretch * stretch;
  }
  return s;
}

}  // namespace snapjump::popper
