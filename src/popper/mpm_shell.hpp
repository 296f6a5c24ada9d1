// The 3D discretisation of the shell, the paper's: Total Lagrangian quadratic tetrahedra whose
// nodes are MPM particles; the rim's clamp and the plate act through the background grid.
// Phases 1-2 run the finite elements alone (fem::ExplicitDriver), since the grid has nothing to
// do there; from the grounding on, the MPM stepper.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <variant>

#include "fem/body.hpp"
#include "fem/explicit.hpp"
#include "hybrid/body_forces.hpp"
#include "mpm/rules.hpp"
#include "mpm/stepper.hpp"
#include "popper/popper.hpp"
#include "popper/shell_model.hpp"

namespace snapjump::popper {

// The case's own shell (shell.mesh), placed as the generated cap is: the rim's centre on the z
// axis, the apex (the lowest outer point) at z = -(R + h/2). Throws MeshError for a file
// read_msh refuses and for a shell that does not open upward (its rim must stand above its
// apex).
mesh::Mesh load_user_mesh(const config::Case& c);

// Phases 1-2 and the phases from the grounding on are types of their own (Held, OnPlate); what
// only the shell on the plate has (the plate's force and contact, the state a checkpoint keeps,
// the potential energy that the series reports from the grounding on) throws std::logic_error,
// naming the method, when asked for before start_on_plate.
class MpmShell final : public ShellModel, public ShellReport {
 public:
  MpmShell(const config::Case& c, const Numerics& n, std::function<double()> delta_p);

  [[nodiscard]] const ShellReport& report() const override { return *this; }
  [[nodiscard]] std::string describe() const override;
  [[nodiscard]] nlohmann::json numerics_json() const override;
  void write_snapshot(const std::filesystem::path& path, double t) const override;

  [[nodiscard]] double shell_mass() const override { return body_->total_mass(); }
  [[nodiscard]] double undeformed_cavity_volume() const override {
    return body_->cavity_volume(body_->mesh().nodes);
  }
  [[nodiscard]] double hole_area() const override { return hole_area_; }
  [[nodiscard]] double undeformed_depth() const override { return depth_outer_; }
  [[nodiscard]] double time_step() const override { return time_step_.dt; }

  void start_held(double damping) override;
  void start_on_plate(core::RigidBody& container, double mu, double damping) override;
  void set_damping(double c) override;
  void step() override;
  [[nodiscard]] double time() const override;
  [[nodiscard]] double dt() const override;
  [[nodiscard]] long steps() const override;
  void reset_time() override;
  void zero_velocities() override;

  [[nodiscard]] double kinetic_energy() const override;
  [[nodiscard]] double strain_energy() const override;
  void check_folds() const override;
  [[nodiscard]] std::optional<SurfaceCompression> inner_surface_compression() const override {
    return std::nullopt;
  }
  [[nodiscard]] double potential_energy(double g) const override;
  [[nodiscard]] double cavity_volume() const override;
  [[nodiscard]] double apex_z() const override;
  [[nodiscard]] double outer_rim_z() const override;
  [[nodiscard]] double plate_force() const override;
  [[nodiscard]] Contact contact() const override;

  void save_state(std::ostream& out) const override;
  void load_state(std::istream& in, core::RigidBody& container, double mu) override;
  [[nodiscard]] std::uint64_t node_order_fingerprint() const;
  [[nodiscard]] double outer_rim_radius() const override;

  [[nodiscard]] const fem::Body& body() const { return *body_; }
  // The MPM stepper (throws std::logic_error before start_on_plate).
  [[nodiscard]] const mpm::Stepper& stepper() const;

 private:
  // Phases 1-2: the finite elements alone, the rim held; the grid has nothing to do there.
  struct Held {
    std::unique_ptr<fem::ExplicitDriver> driver;
  };
  // From the grounding on: the MPM stepper with the clamp, the container's face and the plate.
  struct OnPlate {
    std::unique_ptr<mpm::Stepper> stepper;
    mpm::PlateRule* plate = nullptr;
    mpm::ContainerFaceRule* face = nullptr;  // absent for a designer's own shell
  };
  // Built and at rest, neither phase started yet.
  struct Unstarted {};

  // f applied to the phase's integrator (the MPM stepper or the finite-element driver, which
  // share time, dt, steps, kinetic_energy and thread_tuner), or at_rest before either phase.
  template <typename F, typename T>
  T stepping(F f, T at_rest) const {
    if (const auto* p = std::get_if<OnPlate>(&phase_)) return f(*p->stepper);
    if (const auto* h = std::get_if<Held>(&phase_)) return f(*h->driver);
    return at_rest;
  }
  // The shell on the plate, or std::logic_error naming `method` in any other phase.
  [[nodiscard]] const OnPlate& on_plate(const char* method) const;
  [[nodiscard]] OnPlate& on_plate(const char* method);
  [[nodiscard]] const mesh::Points& positions() const;
  [[nodiscard]] int chosen_threads() const;
  [[nodiscard]] double outer_rim_z(const mesh::Points& x) const;
  // The container's face around the rim, for the generated cap (core::ContainerFace).
  [[nodiscard]] std::optional<core::ContainerFace> container_face() const;
  [[nodiscard]] double rim_dz(const mpm::Stepper& stepper) const;
  void build_stepper(mpm::Particles particles, core::RigidBody& container, double mu,
                     double damping);

  Numerics numerics_;
  std::unique_ptr<fem::Body> body_;
  std::unique_ptr<hybrid::BodyForces> forces_;
  std::function<double()> delta_p_;
  std::variant<Unstarted, Held, OnPlate> phase_;
  mpm::TimeStep time_step_;
  double hole_area_ = 0.0;
  double depth_outer_ = 0.0;
  std::vector<int> outer_rim_;  // clamped nodes of the outer surface
};

}  // namespace snapjump::popper
