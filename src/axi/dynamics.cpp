#include "axi/dynamics.hpp"

#include <cmath>
#include <stdexcept>

namespace snapjump::axi {

Dynamics::Dynamics(const Body& body, double dt)
    : body_(body),
      dt_(dt),
      cone_(rim_cone(body.spec())),
      self_contact_(body, default_contact_stiffness(body)) {
  if (!(dt > 0.0)) throw std::invalid_argument("the time step must be positive");
  x_ = body.nodes();
  const std::size_t n = x_.size();
  v_.r.assign(n, 0.0);
  v_.z.assign(n, 0.0);
  rim_.assign(n, 0);
  axis_.assign(n, 0);
  outer_.assign(n, 0);
  for (int a : body.rim()) rim_[a] = 1;
  for (int a : body.axis()) axis_[a] = 1;
  for (int a : body.outer()) outer_[a] = 1;
  surface_.assign(n, 0);
  for (const auto* set : {&body.inner(), &body.outer()}) {
    for (int a : *set) surface_[a] = rim_[a] ? 0 : 1;
  }
}

void Dynamics::hold_rim() {
  container_ = nullptr;
  plate_.reset();
}

void Dynamics::attach(core::RigidBody& container, double mu, double rim_offset) {
  container_ = &container;
  plate_.emplace(x_.size(), mu);
  rim_offset_ = rim_offset;
}

void Dynamics::translate_z(double dz) {
  for (auto& z : x_.z) z += dz;
}

void Dynamics::zero_velocities() {
  std::fill(v_.r.begin(), v_.r.end(), 0.0);
  std::fill(v_.z.begin(), v_.z.end(), 0.0);
}

void Dynamics::step() {
  body_.internal_forces(x_, f_);
  if (rim_contacts_) self_contact_.add_forces(x_, f_);
  if (pressure_) body_.add_pressure_forces(x_, pressure_(), f_);
  const auto& m = body_.mass();
  const std::size_t n = x_.size();
  if (gravity_ != 0.0) {
    for (std::size_t a = 0; a < n; ++a) f_.z[a] -= gravity_ * m[a];
  }
  // The container and the rim move as one body: the rim nodes' forces act on it, and the clamp
  // force is what the shell exerts on the container itself.
  double m_rim = 0.0;
  if (container_) {
    double f_rim = 0.0;
    for (int a : body_.rim()) {
      f_rim += f_.z[a];
      m_rim += m[a];
    }
    auto& c = *container_;
    const double acc = (c.applied_force + f_rim) / (c.mass + m_rim);
    c.clamp_force = f_rim - m_rim * acc;
    c.advance(dt_);
  }
  cone_impulse_ = 0.0;
  cone_nodes_ = 0;
  // Where the rim (and the container's face with it) is at the end of this step.
  const double rim_dz = container_ ? rim_offset_ + container_->z : 0.0;
  const double cd = 0.5 * damping_ * dt_;
  const double a0 = (1.0 - cd) / (1.0 + cd), a1 = dt_ / (1.0 + cd);
  if (plate_) plate_->begin_step();
  for (std::size_t a = 0; a < n; ++a) {
    if (rim_[a]) {
      v_.r[a] = 0.0;
      if (container_) {
        v_.z[a] = container_->vz;
        x_.z[a] = body_.nodes().z[a] + rim_offset_ + container_->z;
      } else {
        v_.z[a] = 0.0;
      }
      continue;
    }
    const double inv_m = 1.0 / m[a];
    v_.r[a] = axis_[a] ? 0.0 : a0 * v_.r[a] + a1 * f_.r[a] * inv_m;
    v_.z[a] = a0 * v_.z[a] + a1 * f_.z[a] * inv_m;
    if (plate_ && outer_[a]) plate_->apply(a, m[a], x_.z[a], v_.r[a], v_.z[a], dt_);
    if (rim_contacts_ && surface_[a]) stop_at_cone(a, rim_dz);
    x_.r[a] += dt_ * v_.r[a];
    x_.z[a] += dt_ * v_.z[a];
    if (!std::isfinite(x_.r[a]) || !std::isfinite(x_.z[a])) {
      throw fem::InvertedElement(-1, x_.r[a], 0.0, x_.z[a]);
    }
  }
  // What the cone took from the shell along z pushes the container (and the rim with it) the
  // other way, from the next step on.
  if (container_ && cone_impulse_ != 0.0) {
    container_->vz += cone_impulse_ * cone_.nz() / (container_->mass + m_rim);
  }
  if (plate_) plate_->end_step(dt_);
  time_ += dt_;
  ++steps_;
}

// A node whose step would end across the cone, from the clamped face outwards, ends on it: the
// normal velocity that would carry it across is taken out (frictionless). The container takes
// the opposite impulse.
void Dynamics::stop_at_cone(std::size_t a, double rim_dz) {
  const double dv = cone_.stop(x_.r[a], x_.z[a], v_.r[a], v_.z[a], dt_, rim_dz);
  if (dv == 0.0) return;
  v_.r[a] -= dv * cone_.nr();
  v_.z[a] -= dv * cone_.nz();
  const double m = body_.mass()[a];
  cone_impulse_ += m * dv;
  ++cone_nodes_;
}

double Dynamics::kinetic_energy() const {
  const auto& m = body_.mass();
  double k = 0.0;
  for (std::size_t a = 0; a < x_.size(); ++a)
    k += 0.5 * m[a] * (v_.r[a] * v_.r[a] + v_.z[a] * v_.z[a]);
  return k;
}

double Dynamics::potential_energy(double g) const {
  const auto& m = body_.mass();
  double p = 0.0;
  for (std::size_t a = 0; a < x_.size(); ++a) p += m[a] * g * x_.z[a];
  return p;
}

}  // namespace snapjump::axi
