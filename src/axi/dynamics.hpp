// Explicit dynamics of the axisymmetric body: m a = f_ext + f_int (paper, Eq. S8) by central
// differences (kick, then drift) on lumped
// masses, with the rim either held in place or glued to the rigid container, and the plate z = 0
// acting exactly on the outer surface's nodes (no grid, no standoff).
//
// The plate (axi/plate.hpp) acts once the rim is glued to the container, on the outer surface's
// nodes after their kick, before the contacts at the rim.
//
// The container and the fold (axi/contact.hpp): a node whose step would take it across the rim
// face's cone, from the clamped face outwards, lands on the cone (frictionless, its normal
// velocity relative to the container taken out, the container given the opposite impulse in
// the same step); the inner surface cannot pass through itself (a penalty, with the internal
// forces).
#pragma once

#include <functional>
#include <iosfwd>
#include <optional>
#include <vector>

#include "axi/body.hpp"
#include "axi/contact.hpp"
#include "axi/plate.hpp"
#include "core/rigid_body.hpp"

namespace snapjump::axi {

class Dynamics {
 public:
  Dynamics(const Body& body, double dt);

  // Pressure difference (outside minus inside) on the inner surface, asked once per step.
  void set_pressure(std::function<double()> delta_p) { pressure_ = std::move(delta_p); }
  void set_gravity(double g) { gravity_ = g; }
  // Mass-proportional damping c [1/s]: m a = f - c m v.
  void set_damping(double c) { damping_ = c; }
  // The rim stays where it is (the container held in the air); no plate.
  void hold_rim();
  // From now on the rim moves with the container along z, at its reference height plus
  // rim_offset plus the container's z, and the plate acts with friction mu.
  void attach(core::RigidBody& container, double mu, double rim_offset);
  // The contacts at the rim (on by default; off only to measure what they do).
  void set_rim_contacts(bool on) { rim_contacts_ = on; }
  // The self-contact's penalty stiffness k [Pa/m] (default: default_contact_stiffness).
  void set_self_contact_stiffness(double k) { self_contact_ = InnerSelfContact(body_, k); }
  [[nodiscard]] const InnerSelfContact& self_contact() const { return self_contact_; }
  // The cone's impulse on the shell in the last step, along its normal [N s], and how many nodes
  // it stopped.
  [[nodiscard]] double cone_impulse() const { return cone_impulse_; }
  [[nodiscard]] int cone_nodes() const { return cone_nodes_; }
  // Moves every node by dz.
  void translate_z(double dz);
  void zero_velocities();

  // One step. Throws fem::InvertedElement; the state is then that of the failed step.
  void step();

  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] double dt() const { return dt_; }
  [[nodiscard]] long steps() const { return steps_; }
  void reset_time() { time_ = 0.0; }
  void restore_clock(double time, long steps) {
    time_ = time;
    steps_ = steps;
  }
  [[nodiscard]] const Points& positions() const { return x_; }
  [[nodiscard]] const Points& velocities() const { return v_; }
  Points& mutable_positions() { return x_; }
  Points& mutable_velocities() { return v_; }
  [[nodiscard]] const Body& body() const { return body_; }

  [[nodiscard]] double kinetic_energy() const;
  [[nodiscard]] double potential_energy(double g) const;  // of the shell's weight
  // The plate's reaction in the last step [N], and whether it pushed node a.
  [[nodiscard]] double plate_force() const { return plate_ ? plate_->force() : 0.0; }
  [[nodiscard]] bool loaded(int a) const {
    return plate_ && plate_->loaded(static_cast<std::size_t>(a));
  }

 private:
  void stop_at_cone(std::size_t a, double rim_dz);

  const Body& body_;
  double dt_;
  double time_ = 0.0;
  long steps_ = 0;
  double damping_ = 0.0;
  double gravity_ = 0.0;
  std::function<double()> pressure_;
  core::RigidBody* container_ = nullptr;
  Points x_, v_, f_;
  std::vector<char> rim_, axis_, outer_;
  double rim_offset_ = 0.0;
  std::optional<PlateRule> plate_;  // from attach() on
  bool rim_contacts_ = true;
  RimCone cone_;
  InnerSelfContact self_contact_;
  std::vector<char> surface_;  // inner or outer surface, off the rim
  double cone_impulse_ = 0.0;  // along the cone's normal, on the shell, last step [N s]
  int cone_nodes_ = 0;
};

}  // namespace snapjump::axi
