#include "popper/mpm_shell.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "io/vtu.hpp"
#include "mesh/msh_reader.hpp"
#include "parallel/threads.hpp"
#include "popper/material.hpp"
#include "popper/state_io.hpp"

namespace snapjump::popper {
namespace {

constexpr double kG = config::kStandardGravity;

std::unique_ptr<fem::Body> make_body(const config::Case& c, const Numerics& n) {
  auto m = n.user_mesh ? *n.user_mesh : mesh::make_cap_mesh(n.cap);
  // Particles in space order: the transfers' threads then share fewer cache lines.
  mesh::sort_along_curve(m);
  return std::make_unique<fem::Body>(
      std::move(m), body_material(c.material),
      n.reduced_bulk ? fem::BulkRule::centroid : fem::BulkRule::full);
}

}  // namespace

mesh::Mesh load_user_mesh(const config::Case& c) {
  auto m = mesh::read_msh(c.shell.mesh);
  const auto& X = m.nodes;
  double cx = 0.0, cy = 0.0, rim_z = 0.0;
  for (int a : m.clamped) {
    cx += X.x[a];
    cy += X.y[a];
    rim_z += X.z[a];
  }
  const double k = 1.0 / static_cast<double>(m.clamped.size());
  cx *= k;
  cy *= k;
  rim_z *= k;
  if (!(rim_z > X.z[m.apex])) {
    throw mesh::MeshError(fmt::format(
        "{}: the clamped rim (mean z = {:.4g} mm) does not stand above the apex (z = {:.4g} mm): "
        "the shell must open upward, its apex pointing down to the plate",
        m.description, 1e3 * rim_z, 1e3 * X.z[m.apex]));
  }
  const double dz = -(c.shell.R + 0.5 * c.shell.h) - X.z[m.apex];
  for (std::size_t a = 0; a < m.nodes.size(); ++a) {
    m.nodes.x[a] -= cx;
    m.nodes.y[a] -= cy;
    m.nodes.z[a] += dz;
  }
  return m;
}

MpmShell::MpmShell(const config::Case& c, const Numerics& n, std::function<double()> delta_p)
    : numerics_(n), body_(make_body(c, n)), delta_p_(std::move(delta_p)) {
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
  // The particles' forces: internal, gravity, and the gas's pressure on the inner faces as the
  // surface force of the external forces (paper, Eq. S11).
  forces_ = std::make_unique<hybrid::BodyForces>(*body_, kG, [this](double) { return delta_p_(); });
  // The grid bound assumes speeds up to 2 m/s (a jump of 20 cm); faster particles stop the run
  // with a StepError from the stepper's own CFL check.
  time_step_ = mpm::choose_time_step(body_->stable_time_step(n.time_step_factor), n.dx, 2.0, 0.5);
}

std::string MpmShell::describe() const {
  const auto& n = numerics_;
  const std::string mesh =
      n.mesh_file.empty()
          ? fmt::format(
                "{} ten-node tetrahedra, {} particles (element size {:.3g} mm{}, {} layers)",
                body_->num_elements(), body_->num_nodes(), 1e3 * n.cap.element_size,
                mesh::grading_summary(n.cap), n.cap.layers)
          : fmt::format("{} ten-node tetrahedra, {} particles, read from {}", body_->num_elements(),
                        body_->num_nodes(), n.mesh_file);
  return fmt::format(
      "  model       3D MPM (quadratic tetrahedra on particles, the plate through the grid)\n"
      "  mesh        {}\n  bulk energy {}\n  grid        {:.3g} mm cells (h / {:.3g})\n"
      "  time step   {:.3g} us (elastic bound {:.3g} us, grid bound {:.3g} us at 2 m/s; {} "
      "limits)\n",
      mesh,
      n.reduced_bulk ? "at each element's centroid (numerics.bulk_integration = \"reduced\")"
                     : "at the four quadrature points, as the rest (the paper's element)",
      1e3 * n.dx, n.cap.h / n.dx, 1e6 * time_step_.dt, 1e6 * time_step_.elastic,
      1e6 * time_step_.grid, time_step_.limiting);
}

nlohmann::json MpmShell::numerics_json() const {
  return {{"model", "3d"},
          {"bulk_integration", numerics_.reduced_bulk ? "reduced" : "full"},
          {"mesh_file", numerics_.mesh_file},
          {"elements", body_->num_elements()},
          {"particles", body_->num_nodes()},
          {"element_size", numerics_.cap.element_size},
          {"layers", numerics_.cap.layers},
          {"dx", numerics_.dx},
          {"dt", time_step_.dt},
          {"dt_elastic", time_step_.elastic},
          {"dt_grid", time_step_.grid},
          {"end_time", numerics_.end_time}};
}

double MpmShell::outer_rim_z(const mesh::Points& x) const {
  double z = 0.0;
  for (int a : outer_rim_) z += x.z[a];
  return z / static_cast<double>(outer_rim_.size());
}

const MpmShell::OnPlate& MpmShell::on_plate(const char* method) const {
  if (const auto* p = std::get_if<OnPlate>(&phase_)) return *p;
  throw std::logic_error(fmt::format(
      "MpmShell::{}: only the shell on the plate has this (call start_on_plate or load_state "
      "first)",
      method));
}

MpmShell::OnPlate& MpmShell::on_plate(const char* method) {
  return const_cast<OnPlate&>(std::as_const(*this).on_plate(method));
}

const mpm::Stepper& MpmShell::stepper() const { return *on_plate("stepper").stepper; }

const mesh::Points& MpmShell::positions() const {
  if (const auto* p = std::get_if<OnPlate>(&phase_)) return p->stepper->particles().x;
  if (const auto* h = std::get_if<Held>(&phase_)) return h->driver->positions();
  return body_->mesh().nodes;
}

void MpmShell::start_held(double damping) {
  fem::ExplicitOptions eo;
  eo.time_step_factor = numerics_.time_step_factor;
  eo.damping = damping;
  eo.pressure = [this](double) { return delta_p_(); };
  eo.container_face = container_face();
  phase_ = Held{std::make_unique<fem::ExplicitDriver>(*body_, eo)};
}

void MpmShell::start_on_plate(core::RigidBody& container, double mu, double damping) {
  // Lower the shell until its lowest point is just inside the plate's reach (the plate acts on
  // the nodes at z <= 0, a particle's stencil reaches 1.5 cells).
  auto x = positions();
  double lowest = std::numeric_limits<double>::infinity();
  for (double z : x.z) lowest = std::min(lowest, z);
  const double shift = 1.2 * numerics_.dx - lowest;
  for (auto& z : x.z) z += shift;
  auto particles = hybrid::particles_of(*body_);
  particles.x = x;
  build_stepper(std::move(particles), container, mu, damping);
}

void MpmShell::build_stepper(mpm::Particles particles, core::RigidBody& container, double mu,
                             double damping) {
  OnPlate p;
  p.stepper = std::make_unique<mpm::Stepper>(
      std::move(particles), *forces_,
      mpm::StepperOptions{time_step_.dt, numerics_.dx, 0.5, damping});
  p.stepper->add_rule(std::make_unique<mpm::ClampRule>(container));
  if (const auto face = container_face()) {
    p.face = &dynamic_cast<mpm::ContainerFaceRule&>(
        p.stepper->add_rule(std::make_unique<mpm::ContainerFaceRule>(container, *face)));
  }
  p.plate =
      &dynamic_cast<mpm::PlateRule&>(p.stepper->add_rule(std::make_unique<mpm::PlateRule>(mu)));
  p.stepper->add_rigid_body(container);
  phase_ = std::move(p);
}

std::optional<core::ContainerFace> MpmShell::container_face() const {
  // A designer's own shell (shell.mesh) has no cone of its own to take the face from.
  if (numerics_.user_mesh) return std::nullopt;
  return core::container_face(numerics_.cap.R, numerics_.cap.h, numerics_.cap.phi);
}

void MpmShell::set_damping(double c) { on_plate("set_damping").stepper->set_damping(c); }

// The rim's displacement from the cap's frame: the clamped particles' mean, which the container
// carries.
double MpmShell::rim_dz(const mpm::Stepper& stepper) const {
  const auto& X = body_->mesh().nodes;
  const auto& x = stepper.particles().x;
  double dz = 0.0;
  for (int a : body_->mesh().clamped) dz += x.z[a] - X.z[a];
  return dz / static_cast<double>(body_->mesh().clamped.size());
}

void MpmShell::step() {
  if (auto* p = std::get_if<OnPlate>(&phase_)) {
    if (p->face != nullptr) p->face->set_dz(rim_dz(*p->stepper));
    p->stepper->step();
  } else if (auto* h = std::get_if<Held>(&phase_)) {
    h->driver->step();
  } else {
    throw std::logic_error("MpmShell::step: no phase started (call start_held or start_on_plate)");
  }
}

// Before either phase the shell is at rest in its reference state at t = 0.
double MpmShell::time() const {
  return stepping([](const auto& s) { return s.time(); }, 0.0);
}
double MpmShell::dt() const {
  return stepping([](const auto& s) { return s.dt(); }, time_step_.dt);
}
long MpmShell::steps() const {
  return stepping([](const auto& s) { return s.steps(); }, 0L);
}
void MpmShell::reset_time() { on_plate("reset_time").stepper->reset_time(); }

void MpmShell::zero_velocities() {
  auto& p = on_plate("zero_velocities").stepper->particles();
  std::fill(p.v.x.begin(), p.v.x.end(), 0.0);
  std::fill(p.v.y.begin(), p.v.y.end(), 0.0);
  std::fill(p.v.z.begin(), p.v.z.end(), 0.0);
  std::fill(p.C.begin(), p.C.end(), 0.0);
}

double MpmShell::kinetic_energy() const {
  return stepping([](const auto& s) { return s.kinetic_energy(); }, 0.0);
}
// The step's chosen thread count, for the parallel loops between steps (a sample's strain energy,
// the gas's cavity volume): under load a region at two threads waits for a descheduled thread,
// as a step would (parallel::ThreadTuner).
int MpmShell::chosen_threads() const {
  return stepping([](const auto& s) { return s.thread_tuner().chosen(); }, parallel::max_threads());
}

void MpmShell::check_folds() const {
  const parallel::ScopedThreadCount threads(chosen_threads());
  body_->check_folds(positions());
}

double MpmShell::strain_energy() const {
  const parallel::ScopedThreadCount threads(chosen_threads());
  return body_->strain_energy(positions());
}
double MpmShell::potential_energy(double g) const {
  const auto& p = on_plate("potential_energy").stepper->particles();
  double pot = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) pot += p.mass[i] * g * p.x.z[i];
  return pot;
}
double MpmShell::cavity_volume() const {
  const parallel::ScopedThreadCount threads(chosen_threads());
  return body_->cavity_volume(positions());
}
double MpmShell::apex_z() const { return positions().z[body_->mesh().apex]; }
double MpmShell::outer_rim_z() const { return outer_rim_z(positions()); }

ShellModel::Contact MpmShell::contact() const {
  // The outer particles that the plate carries, i.e. that have at least half of their stencil
  // weight on the nodes the plate pushed in the last step. r is the outermost; the contact is a
  // disk when the apex is among them.
  const auto& phase = on_plate("contact");
  const auto& p = phase.stepper->particles();
  const double dx = phase.stepper->dx();
  const auto touching = [&](int a) {
    return mpm::plate_carries(*phase.plate, dx, p.x.x[a], p.x.y[a], p.x.z[a]);
  };
  Contact c;
  for (int a : body_->mesh().outer) {
    if (touching(a)) {
      c.any = true;
      c.r = std::max(c.r, std::hypot(p.x.x[a], p.x.y[a]));
    }
  }
  c.apex = c.any && touching(body_->mesh().apex);
  return c;
}

// The reference positions in the body's node order: a checkpoint's particle arrays belong to
// this numbering and no other.
std::uint64_t MpmShell::node_order_fingerprint() const {
  const auto& X = body_->mesh().nodes;
  std::uint64_t h = fnv1a64({});
  for (const auto* v : {&X.x, &X.y, &X.z}) {
    h = fnv1a64({reinterpret_cast<const char*>(v->data()), v->size() * sizeof(double)}, h);
  }
  return h;
}

void MpmShell::save_state(std::ostream& out) const {
  const auto& stepper = *on_plate("save_state").stepper;
  const auto& p = stepper.particles();
  put(out, node_order_fingerprint());
  put(out, stepper.time());
  put(out, stepper.steps());
  for (const auto* v : {&p.x.x, &p.x.y, &p.x.z, &p.v.x, &p.v.y, &p.v.z, &p.C}) put_vector(out, *v);
}

void MpmShell::load_state(std::istream& in, core::RigidBody& container, double mu) {
  std::uint64_t fingerprint = 0;
  get(in, fingerprint);
  if (!in) throw std::runtime_error("the checkpoint is truncated");
  if (fingerprint != node_order_fingerprint()) {
    throw std::runtime_error(
        "the checkpoint's particles belong to another mesh or another numbering of its nodes "
        "than this popper's");
  }
  double time = 0.0;
  long steps = 0;
  get_clock(in, time, steps);
  auto particles = hybrid::particles_of(*body_);
  const std::size_t n = particles.size();
  for (auto* v : {&particles.x.x, &particles.x.y, &particles.x.z, &particles.v.x, &particles.v.y,
                  &particles.v.z}) {
    get_vector(in, *v, n);
  }
  get_vector(in, particles.C, 9 * n);
  build_stepper(std::move(particles), container, mu, 0.0);
  on_plate("load_state").stepper->restore_clock(time, steps);
}

void MpmShell::write_snapshot(const std::filesystem::path& path, double t) const {
  const auto& p = on_plate("write_snapshot").stepper->particles();
  io::write_vtu(path, *body_, p.x, p.v, t);
}

double MpmShell::plate_force() const { return on_plate("plate_force").plate->force(); }

double MpmShell::outer_rim_radius() const {
  const auto& X = body_->mesh().nodes;
  double r = 0.0;
  for (int a : outer_rim_) r += std::hypot(X.x[a], X.y[a]);
  return outer_rim_.empty() ? 0.0 : r / static_cast<double>(outer_rim_.size());
}

}  // namespace snapjump::popper
