// The axisymmetric discretisation of the shell (numerics.model = "axisymmetric"): the meridian
// section with 9-node elements (axi::Body), explicit dynamics with the plate acting exactly on the
// outer surface's nodes (axi::Dynamics). Independent of the MPM grid: a reference for the 3D
// model, and fast enough for sweeps.
#pragma once

#include <memory>

#include "axi/body.hpp"
#include "axi/dynamics.hpp"
#include "popper/popper.hpp"
#include "popper/shell_model.hpp"

namespace snapjump::popper {

class AxiShell final : public ShellModel, public ShellReport {
 public:
  AxiShell(const config::Case& c, const Numerics& n, std::function<double()> delta_p);

  [[nodiscard]] const ShellReport& report() const override { return *this; }
  [[nodiscard]] std::string describe() const override;
  [[nodiscard]] nlohmann::json numerics_json() const override;
  void write_snapshot(const std::filesystem::path& path, double t) const override;
  [[nodiscard]] double shell_mass() const override { return body_.total_mass(); }
  [[nodiscard]] double undeformed_cavity_volume() const override {
    return body_.cavity_volume(body_.nodes());
  }
  [[nodiscard]] double hole_area() const override { return hole_area_; }
  [[nodiscard]] double undeformed_depth() const override { return depth_outer_; }
  [[nodiscard]] double time_step() const override { return dynamics_.dt(); }

  void start_held(double damping) override;
  std::optional<QuasiStaticBuckle> buckle_quasi_statically(
      double dp, double p_ref, bool through_snaps, const std::function<void()>& at_point) override;
  void start_on_plate(core::RigidBody& container, double mu, double damping) override;
  void set_damping(double c) override { dynamics_.set_damping(c); }
  void step() override { dynamics_.step(); }
  [[nodiscard]] double time() const override { return dynamics_.time(); }
  [[nodiscard]] double dt() const override { return dynamics_.dt(); }
  [[nodiscard]] long steps() const override { return dynamics_.steps(); }
  void reset_time() override { dynamics_.reset_time(); }
  void zero_velocities() override { dynamics_.zero_velocities(); }

  [[nodiscard]] double kinetic_energy() const override { return dynamics_.kinetic_energy(); }
  void check_folds() const override { body_.check_folds(dynamics_.positions()); }
  [[nodiscard]] std::optional<SurfaceCompression> inner_surface_compression() const override;
  [[nodiscard]] double strain_energy() const override {
    return body_.strain_energy(dynamics_.positions());
  }
  [[nodiscard]] double potential_energy(double g) const override {
    return dynamics_.potential_energy(g);
  }
  [[nodiscard]] double cavity_volume() const override {
    return body_.cavity_volume(dynamics_.positions());
  }
  [[nodiscard]] double apex_z() const override { return dynamics_.positions().z[body_.apex()]; }
  [[nodiscard]] double outer_rim_z() const override {
    return dynamics_.positions().z[body_.outer().back()];
  }
  [[nodiscard]] double plate_force() const override { return dynamics_.plate_force(); }
  [[nodiscard]] Contact contact() const override;

  void save_state(std::ostream& out) const override;
  void load_state(std::istream& in, core::RigidBody& container, double mu) override;
  [[nodiscard]] double outer_rim_radius() const override {
    return body_.nodes().r[static_cast<std::size_t>(body_.outer().back())];
  }

  [[nodiscard]] const axi::Body& body() const { return body_; }
  [[nodiscard]] const axi::Dynamics& dynamics() const { return dynamics_; }

 private:
  // On the plate, the rim glued to the container at rim_offset_, gravity on, the clock set.
  void glue_to(core::RigidBody& container, double mu, double damping, double time, long steps);

  axi::Body body_;
  double omega_max_ = 0.0;  // the undeformed body's highest frequency [rad/s]
  axi::Dynamics dynamics_;
  double hole_area_ = 0.0;
  double depth_outer_ = 0.0;
  double rim_offset_ = 0.0;  // the grounding's shift of the whole shell
};

// The time step of the axisymmetric model: this fraction of the stability limit 2 / omega_max of
// central differences, omega_max the undeformed body's highest frequency.
inline constexpr double kAxiStabilityFraction = 0.3;

}  // namespace snapjump::popper
