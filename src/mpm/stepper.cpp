#include "mpm/stepper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace snapjump::mpm {

namespace {

// Calls visit(node, w, dx_a, dy_b, dz_c) for the 27 grid nodes of particle i's quadratic B-spline
// stencil: the node index, the weight and the node's offset from the particle.
template <typename Visit>
inline void for_each_stencil_node(const SparseGrid& grid, const mesh::Points& x, std::size_t i,
                                  double dx, Visit&& visit) {
  const double inv_dx = 1.0 / dx;
  const auto wx = bspline_weights(x.x[i] * inv_dx);
  const auto wy = bspline_weights(x.y[i] * inv_dx);
  const auto wz = bspline_weights(x.z[i] * inv_dx);
  for (int a = 0; a < 3; ++a) {
    const double dxa = (static_cast<double>(wx.base + a)) * dx - x.x[i];
    for (int b = 0; b < 3; ++b) {
      const double dyb = (static_cast<double>(wy.base + b)) * dx - x.y[i];
      const double wab = wx.w[a] * wy.w[b];
      for (int c = 0; c < 3; ++c) {
        const double dzc = (static_cast<double>(wz.base + c)) * dx - x.z[i];
        visit(grid.stencil_node(i, a, b, c), wab * wz.w[c], dxa, dyb, dzc);
      }
    }
  }
}

}  // namespace

TimeStep choose_time_step(double elastic_bound, double dx, double expected_speed, double cfl_grid) {
  TimeStep t;
  t.elastic = elastic_bound;
  t.grid = expected_speed > 0.0 ? cfl_grid * dx / expected_speed
                                : std::numeric_limits<double>::infinity();
  t.dt = std::min(t.elastic, t.grid);
  t.limiting = t.grid < t.elastic ? "grid CFL" : "elastic";
  if (!(t.dt > 0.0) || !std::isfinite(t.dt)) {
    throw std::invalid_argument("time step: bounds must be positive and finite");
  }
  return t;
}

Particles Particles::at_rest(const mesh::Points& positions, const std::vector<double>& masses) {
  Particles p;
  const std::size_t n = positions.size();
  p.x = positions;
  p.v.x.assign(n, 0.0);
  p.v.y.assign(n, 0.0);
  p.v.z.assign(n, 0.0);
  p.mass = masses;
  p.C.assign(9 * n, 0.0);
  p.tags.assign(n, 0);
  return p;
}

Stepper::Stepper(Particles particles, ForceProvider& forces, StepperOptions options)
    : p_(std::move(particles)), forces_(forces), options_(options), grid_(options.dx) {
  if (!(options_.dt > 0.0) || !(options_.dx > 0.0)) {
    throw std::invalid_argument("stepper needs a positive time step and grid spacing");
  }
  if (p_.mass.size() != p_.x.size() || p_.C.size() != 9 * p_.x.size() ||
      p_.tags.size() != p_.x.size() || p_.v.size() != p_.x.size()) {
    throw std::invalid_argument("particle arrays differ in length");
  }
  for (double m : p_.mass) {
    if (!(m > 0.0)) throw std::invalid_argument("every particle needs a positive mass");
  }
}

GridRule& Stepper::add_rule(std::unique_ptr<GridRule> rule) {
  rules_.push_back(std::move(rule));
  return *rules_.back();
}

void Stepper::step() {
  update_particle_velocities();
  particle_to_grid();
  apply_grid_rules();
  grid_to_particle();
  advance_rigid_bodies();
  time_ += options_.dt;
  ++steps_;
}

void Stepper::update_particle_velocities() {
  try {
    forces_.forces(p_.x, time_, f_);
  } catch (const std::exception& e) {
    throw StepError(fmt::format("t = {:.6g} s, step {}: {}", time_, steps_ + 1, e.what()));
  }
  const double dt = options_.dt;
  const double keep = 1.0 / (1.0 + options_.damping * dt);  // semi-implicit damping
  const std::size_t n = p_.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double s = dt / p_.mass[i];
    p_.v.x[i] = keep * (p_.v.x[i] + s * f_.x[i]);
    p_.v.y[i] = keep * (p_.v.y[i] + s * f_.y[i]);
    p_.v.z[i] = keep * (p_.v.z[i] + s * f_.z[i]);
  }
}

void Stepper::particle_to_grid() {
  grid_.rebuild(p_.x);
  const double dx = options_.dx;
  for (int colour = 0; colour < 8; ++colour) {
    const auto& homes = grid_.homes_of_colour(colour);
    const int nh = static_cast<int>(homes.size());
#pragma omp parallel for schedule(dynamic, 4)
    for (int k = 0; k < nh; ++k) {
      for (const int i : grid_.particles_of(homes[k])) {
        const double m = p_.mass[i];
        const double* C = &p_.C[9 * static_cast<std::size_t>(i)];
        const double vx = p_.v.x[i], vy = p_.v.y[i], vz = p_.v.z[i];
        const std::uint8_t tag = p_.tags[i];
        for_each_stencil_node(grid_, p_.x, static_cast<std::size_t>(i), dx,
                              [&](std::size_t node, double w, double dxa, double dyb, double dzc) {
                                const double mw = m * w;
                                auto& g = grid_.nodes[node];
                                g.m += mw;
                                g.px += mw * (vx + C[0] * dxa + C[1] * dyb + C[2] * dzc);
                                g.py += mw * (vy + C[3] * dxa + C[4] * dyb + C[5] * dzc);
                                g.pz += mw * (vz + C[6] * dxa + C[7] * dyb + C[8] * dzc);
                                if (tag != 0) {  // most particles carry none
                                  grid_.tags[node] |= tag;
                                  grid_.block_tags[node / kBlockNodes] |= tag;
                                }
                              });
      }
    }
  }
}

void Stepper::apply_grid_rules() {
  const StepContext ctx{options_.dt, time_};
  for (auto& rule : rules_) rule->apply(grid_, ctx);
}

void Stepper::grid_to_particle() {
  const double inv_dx = 1.0 / options_.dx, dx = options_.dx, dt = options_.dt;
  const double apic = 4.0 * inv_dx * inv_dx;
  const std::size_t n = p_.size();
  double vmax2 = 0.0;
  std::atomic<long> bad{-1};
#pragma omp parallel for schedule(static) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i) {
    double v[3] = {0, 0, 0};
    double B[9] = {};
    for_each_stencil_node(grid_, p_.x, i, dx,
                          [&](std::size_t node, double w, double dxa, double dyb, double dzc) {
                            const auto& g = grid_.nodes[node];
                            const double inv_m = 1.0 / g.m;
                            const double gv[3] = {g.px * inv_m, g.py * inv_m, g.pz * inv_m};
                            const double d[3] = {dxa, dyb, dzc};
                            for (int r = 0; r < 3; ++r) {
                              v[r] += w * gv[r];
                              for (int c = 0; c < 3; ++c) B[3 * r + c] += w * gv[r] * d[c];
                            }
                          });
    p_.v.x[i] = v[0];
    p_.v.y[i] = v[1];
    p_.v.z[i] = v[2];
    double* C = &p_.C[9 * i];
    for (int k = 0; k < 9; ++k) C[k] = apic * B[k];
    p_.x.x[i] += dt * v[0];
    p_.x.y[i] += dt * v[1];
    p_.x.z[i] += dt * v[2];
    const double s2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (!std::isfinite(s2)) {
      long expected = -1;
      bad.compare_exchange_strong(expected, static_cast<long>(i));
    } else {
      vmax2 = std::max(vmax2, s2);
    }
  }
  const double t = time_ + options_.dt;
  if (const long i = bad.load(); i >= 0) {
    throw StepError(fmt::format("t = {:.6g} s, step {}: particle {} has a non-finite velocity", t,
                                steps_ + 1, i));
  }
  max_speed_ = std::sqrt(vmax2);
  if (cfl() > options_.max_cfl) {
    throw StepError(fmt::format(
        "t = {:.6g} s, step {}: a particle moves {:.3g} grid cells per step (speed {:.3g} m/s), "
        "more than the allowed {}; reduce the time step",
        t, steps_ + 1, cfl(), max_speed_, options_.max_cfl));
  }
}

void Stepper::advance_rigid_bodies() {
  for (auto* b : bodies_) b->advance(options_.dt);
}

double Stepper::kinetic_energy() const {
  double k = 0.0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    k += 0.5 * p_.mass[i] * (p_.v.x[i] * p_.v.x[i] + p_.v.y[i] * p_.v.y[i] + p_.v.z[i] * p_.v.z[i]);
  }
  return k;
}

}  // namespace snapjump::mpm
