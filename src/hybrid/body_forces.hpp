// The paper's hybrid: the finite-element body as a force provider for the MPM engine: internal
// forces, the pressure follower load and gravity, at the particles' current positions.
#pragma once

#include <functional>

#include "fem/body.hpp"
#include "mpm/stepper.hpp"

namespace snapjump::hybrid {

using mpm::ForceProvider;
using mpm::Particles;

class BodyForces final : public ForceProvider {
 public:
  // pressure(t): pressure difference on the inner faces (empty: none); gravity along -z.
  BodyForces(const fem::Body& body, double gravity, std::function<double(double)> pressure = {})
      : body_(body), gravity_(gravity), pressure_(std::move(pressure)) {}

  void forces(const mesh::Points& x, double t, mesh::Points& f) override {
    body_.internal_forces(x, f, scratch_);
    if (pressure_) body_.add_pressure_forces(x, pressure_(t), f, scratch_);
    if (gravity_ != 0.0) body_.add_gravity(gravity_, f);
  }

 private:
  const fem::Body& body_;
  double gravity_;
  std::function<double(double)> pressure_;
  fem::Body::ForceScratch scratch_;
};

// Particles for a body: its reference nodes with its lumped masses; clamped nodes carry
// kTagClamped.
Particles particles_of(const fem::Body& body);

}  // namespace snapjump::hybrid
