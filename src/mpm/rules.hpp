// Grid rules: what happens to the grid momentum between particle-to-grid and grid-to-particle.
// Each is an object with apply(); the stepper runs them in order and does not know what they do,
// so a tilted or moving plate, or another obstacle, is a new class, not an edit of the step.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/container_face.hpp"
#include "core/rigid_body.hpp"
#include "mpm/grid.hpp"

namespace snapjump::mpm {

// The container that the rim is glued to (one vertical degree of freedom).
using RigidBody = core::RigidBody;

struct StepContext {
  double dt = 0.0;
  double time = 0.0;  // at the start of the step
};

class GridRule {
 public:
  virtual ~GridRule() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  // Changes the grid's momentum between the transfers. Writes only to the nodes of
  // grid.live_blocks() (see there). A sum over nodes must not depend on the thread count: the
  // rules here sum each block apart, in parallel, and add the blocks' sums in their order.
  virtual void apply(SparseGrid& grid, const StepContext& ctx) = 0;
};

// Particle tags.
inline constexpr std::uint8_t kTagClamped = 1;

// Dirichlet clamp to a rigid body: every node reached by a particle carrying `tag` gets the
// body's velocity along z (and none sideways), p_a = m_a v_z e_z (the paper's Dirichlet
// condition of step 2 of its contact analysis, stated in words there, not numbered). The momentum
// this removes is the force between shell and body; it is stored in body.clamp_force (force on the
// body).
class ClampRule final : public GridRule {
 public:
  ClampRule(RigidBody& body, std::uint8_t tag = kTagClamped) : body_(body), tag_(tag) {}
  [[nodiscard]] std::string_view name() const override { return "clamp"; }
  void apply(SparseGrid& grid, const StepContext& ctx) override;

 private:
  RigidBody& body_;
  std::uint8_t tag_;
  std::vector<double> block_impulse_;  // per live block, in their order
};

// The container's bottom face around the rim (core::ContainerFace): on every grid node across
// its rigid part, momentum moving into the container relative to the body loses its normal part
// (frictionless), and the body takes the reaction, added to the clamp's in body.clamp_force (so
// this rule runs after the ClampRule). The nodes that the clamp drives move with the body already
// and are left as they are. Where the face is, the owner says before each step (set_dz: its
// displacement from the cap's frame, the rim's), so that it follows the state alone and a resumed
// run places it as the straight one did.
class ContainerFaceRule final : public GridRule {
 public:
  ContainerFaceRule(RigidBody& body, core::ContainerFace face) : body_(body), face_(face) {}
  void set_dz(double dz) { dz_ = dz; }
  [[nodiscard]] std::string_view name() const override { return "container face"; }
  void apply(SparseGrid& grid, const StepContext& ctx) override;
  // How many nodes the face stopped in the last step, and its force on the shell along z [N].
  [[nodiscard]] long contacts() const { return contacts_; }
  [[nodiscard]] double force_z() const { return force_z_; }

 private:
  RigidBody& body_;
  core::ContainerFace face_;
  double dz_ = 0.0;
  long contacts_ = 0;
  double force_z_ = 0.0;
  std::vector<double> block_impulse_;  // per live block, in their order
  std::vector<long> block_contacts_;
  // Whether any node of block b can lie across the face's rigid part.
  [[nodiscard]] bool block_may_cross(const SparseGrid& grid, std::size_t b, double dz) const;
};

// The rigid plate with top surface z = 0: on the node layers z = 0, -dx, ..., -(layers - 1) dx
// (three by default), momentum moving into the plate (p_z < 0) loses its normal part (paper,
// Eq. S16), and Coulomb friction takes up to mu times that normal impulse from the tangential
// momentum, never reversing it. The plate's reaction force is the normal impulse per time step
// (the paper's F_norm, defined in the text after Eq. S16).
class PlateRule final : public GridRule {
 public:
  explicit PlateRule(double mu, int layers = 3) : mu_(mu), layers_(layers) {}
  [[nodiscard]] std::string_view name() const override { return "plate"; }
  void apply(SparseGrid& grid, const StepContext& ctx) override;
  // Reaction force on the body from the plate in the last step (up is positive) [N].
  [[nodiscard]] double force() const { return force_; }
  [[nodiscard]] double friction_force() const { return friction_; }
  // Grid coordinates of the nodes that took a normal impulse in the last step, sorted: where the
  // plate carries load. (Sorted when first asked for after a step: samples ask, steps do not. Not
  // to be called from two threads at once, nor plate_share / plate_carries on this rule.)
  [[nodiscard]] const std::vector<std::array<std::int64_t, 3>>& loaded_nodes() const;

 private:
  double mu_;
  int layers_;
  double force_ = 0.0;
  double friction_ = 0.0;
  mutable std::vector<std::array<std::int64_t, 3>> loaded_;
  mutable bool loaded_sorted_ = true;
  std::vector<double> block_sums_;  // per live block: normal, tangential impulse
};

// How much of a particle at x is held by the plate: the sum of its quadratic B-spline weights on
// the nodes `loaded` (PlateRule::loaded_nodes(), sorted), in [0, 1]; dx the grid spacing.
double plate_share(const std::vector<std::array<std::int64_t, 3>>& loaded, double dx, double x,
                   double y, double z);

// Whether the plate carried a particle at x in its last step: at least half of the particle's
// stencil weight on the loaded nodes (a particle 1.5 cells or more above z = 0 has none on the
// plate's layers). The contact patch as a camera sees it is made of these particles.
bool plate_carries(const PlateRule& plate, double dx, double x, double y, double z);

}  // namespace snapjump::mpm
