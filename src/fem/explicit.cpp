#include "fem/explicit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace snapjump::fem {

ExplicitDriver::ExplicitDriver(const Body& body, ExplicitOptions options)
    : body_(body),
      options_(std::move(options)),
      tuner_(parallel::ThreadTuner::for_process(options_.tune_threads)) {
  dt_ = options_.dt > 0.0 ? options_.dt : body_.stable_time_step(options_.time_step_factor);
  if (!(dt_ > 0.0) || !std::isfinite(dt_))
    throw std::invalid_argument("explicit driver: bad time step");
  const std::size_t n = body_.num_nodes();
  x_ = body_.mesh().nodes;
  v_.x.assign(n, 0.0);
  v_.y.assign(n, 0.0);
  v_.z.assign(n, 0.0);
  clamped_.assign(n, 0);
  for (int a : body_.mesh().clamped) clamped_[a] = 1;
  if (options_.clamp_displacement) {
    for (int a : body_.mesh().clamped) clamp_offset_[a] = options_.clamp_displacement(a);
  }
}

void ExplicitDriver::step() {
  tuner_.run([this] { advance(); });
}

void ExplicitDriver::advance() {
  body_.internal_forces(x_, f_, scratch_);
  if (options_.pressure) body_.add_pressure_forces(x_, options_.pressure(time_), f_, scratch_);
  if (options_.gravity != 0.0) body_.add_gravity(options_.gravity, f_);
  const auto& m = body_.mass();
  const double c = options_.damping * dt_ * 0.5;
  const double a0 = (1.0 - c) / (1.0 + c), a1 = dt_ / (1.0 + c);
  const std::size_t n = x_.size();
  const double t_next = time_ + dt_;
  const double clamp_z = options_.clamp_z ? options_.clamp_z(t_next) : 0.0;
  const double clamp_vz = options_.clamp_vz ? options_.clamp_vz(t_next) : 0.0;
  const auto& X = body_.mesh().nodes;
  const core::ContainerFace* face = options_.container_face ? &*options_.container_face : nullptr;
  bool finite = true;
  int contacts = 0;
  double depth = 0.0;
#pragma omp parallel for schedule(static) reduction(&& : finite) reduction(+ : contacts) \
    reduction(max : depth)
  for (std::size_t a = 0; a < n; ++a) {
    if (clamped_[a]) {
      const auto it = clamp_offset_.find(static_cast<int>(a));
      const std::array<double, 3> u =
          it == clamp_offset_.end() ? std::array<double, 3>{0.0, 0.0, clamp_z} : it->second;
      v_.x[a] = 0.0;
      v_.y[a] = 0.0;
      v_.z[a] = it == clamp_offset_.end() ? clamp_vz : 0.0;
      x_.x[a] = X.x[a] + u[0];
      x_.y[a] = X.y[a] + u[1];
      x_.z[a] = X.z[a] + u[2];
      continue;
    }
    const double inv_m = 1.0 / m[a];
    v_.x[a] = a0 * v_.x[a] + a1 * f_.x[a] * inv_m;
    v_.y[a] = a0 * v_.y[a] + a1 * f_.y[a] * inv_m;
    v_.z[a] = a0 * v_.z[a] + a1 * f_.z[a] * inv_m;
    if (face != nullptr) {
      const double d = stop_at_face(*face, a, clamp_z);
      contacts += d > 0.0 ? 1 : 0;
      depth = std::max(depth, d);
    }
    x_.x[a] += dt_ * v_.x[a];
    x_.y[a] += dt_ * v_.y[a];
    x_.z[a] += dt_ * v_.z[a];
    finite = finite && std::isfinite(x_.x[a] + x_.y[a] + x_.z[a]);
  }
  if (!finite) throw std::runtime_error("explicit driver: a node position became non-finite");
  face_contacts_ = contacts;
  face_depth_ = depth;
  time_ = t_next;
  ++steps_;
}

double ExplicitDriver::stop_at_face(const core::ContainerFace& face, std::size_t a, double dz) {
  const double r = std::hypot(x_.x[a], x_.y[a]);
  if (!(r > 0.0)) return 0.0;  // the face never reaches the axis
  const double cx = x_.x[a] / r, cy = x_.y[a] / r;
  const double vr = v_.x[a] * cx + v_.y[a] * cy;
  const double dv = face.stop(r, x_.z[a], vr, v_.z[a], dt_, dz);
  if (!(dv > 0.0)) return 0.0;
  v_.x[a] -= dv * face.nr() * cx;
  v_.y[a] -= dv * face.nr() * cy;
  v_.z[a] -= dv * face.nz();
  return dv * dt_;
}

void ExplicitDriver::run_until(double t_end,
                               const std::function<void(const ExplicitDriver&)>& observe,
                               int every) {
  while (time_ < t_end) {
    step();
    if (observe && steps_ % every == 0) observe(*this);
  }
}

double ExplicitDriver::kinetic_energy() const {
  const auto& m = body_.mass();
  double k = 0.0;
  for (std::size_t a = 0; a < m.size(); ++a) {
    k += 0.5 * m[a] * (v_.x[a] * v_.x[a] + v_.y[a] * v_.y[a] + v_.z[a] * v_.z[a]);
  }
  return k;
}

}  // namespace snapjump::fem
