#include "mpm/stepper.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <span>
#include <thread>

#include "core/wide.hpp"

namespace snapjump::mpm {

namespace {

// Four doubles side by side, a node's (m, px, py, pz) (a compiler vector: two SSE2 registers on
// the baseline x86-64 build, one AVX2 register, NEON on arm64); each lane's arithmetic is the
// scalar's (nothing is contracted into a fused multiply-add: -ffp-contract=off, core/wide.hpp).
using Quad = double __attribute__((vector_size(4 * sizeof(double))));
static_assert(sizeof(SparseGrid::Node) == sizeof(Quad) && offsetof(SparseGrid::Node, m) == 0 &&
              offsetof(SparseGrid::Node, pz) == 3 * sizeof(double));

// The 27 grid nodes of a particle's quadratic B-spline stencil, axis by axis: the weight of each
// of the three nodes along an axis, its offset from the particle, and where it lies in the grid
// (which neighbour of the home block, and the offset within that block). A node's index is
// block * kBlockNodes + off[0][a] + off[1][b] + off[2][c], block = neighbours[nb[0][a] | nb[1][b]
// | nb[2][c]]: the index arithmetic is done once per axis, not once per node.
struct Stencil {
  double w[3][3];
  double d[3][3];
  int nb[3][3];
  int off[3][3];
  const std::array<int, 8>* neighbours;

  Stencil(const SparseGrid& grid, const core::Points& x, std::size_t i, double dx) {
    const double inv_dx = 1.0 / dx;
    const double xi[3] = {x.x[i], x.y[i], x.z[i]};
    const auto& local = grid.local_of(i);
    constexpr int kStride[3] = {kBlock * kBlock, kBlock, 1};
    for (int ax = 0; ax < 3; ++ax) {
      const auto wts = bspline_weights(xi[ax] * inv_dx);
      for (int a = 0; a < 3; ++a) {
        const int l = local[ax] + a;
        w[ax][a] = wts.w[a];
        d[ax][a] = static_cast<double>(wts.base + a) * dx - xi[ax];
        nb[ax][a] = l >= kBlock ? (1 << ax) : 0;
        off[ax][a] = (l & (kBlock - 1)) * kStride[ax];
      }
    }
    neighbours = &grid.neighbours_of_home(grid.home_of(i));
  }
  [[nodiscard]] std::size_t node(int a, int b, int c) const {
    const int block = (*neighbours)[nb[0][a] | nb[1][b] | nb[2][c]];
    return static_cast<std::size_t>(block) * kBlockNodes +
           static_cast<std::size_t>(off[0][a] + off[1][b] + off[2][c]);
  }
};

// Adds particle n's mass and APIC momentum to the 27 nodes of its stencil (and its tag):
// m_a += m N and p_a += m N (v + C (x_a - x_p)) (paper, Eqs. S14 and S15).
[[gnu::always_inline]] inline void scatter_particle(SparseGrid& grid, const Particles& p, double dx,
                                                    std::size_t n) {
  const Stencil st(grid, p.x, n, dx);
  const double m = p.mass[n];
  const double* C = &p.C[9 * n];
  const double v[3] = {p.v.x[n], p.v.y[n], p.v.z[n]};
  // The APIC velocity v + C (x_node - x_p), built up axis by axis. A node's (m, px, py, pz) is
  // updated as one vector, (1, u_x, u_y, u_z) times the weighted mass: each lane is the scalar
  // expression's product and sum (1 + 0 dz is 1 exactly), so the bits are the same.
  const Quad cz = {0.0, C[2], C[5], C[8]};
  for (int a = 0; a < 3; ++a) {
    const double dxa = st.d[0][a];
    const double ua[3] = {v[0] + C[0] * dxa, v[1] + C[3] * dxa, v[2] + C[6] * dxa};
    for (int b = 0; b < 3; ++b) {
      const double dyb = st.d[1][b];
      const Quad u = {1.0, ua[0] + C[1] * dyb, ua[1] + C[4] * dyb, ua[2] + C[7] * dyb};
      const double mab = m * st.w[0][a] * st.w[1][b];
      for (int c = 0; c < 3; ++c) {
        const double dzc = st.d[2][c];
        const double mw = mab * st.w[2][c];
        auto& g = grid.nodes[st.node(a, b, c)];
        Quad q;
        std::memcpy(&q, &g.m, sizeof q);
        q += mw * (u + cz * dzc);
        std::memcpy(&g.m, &q, sizeof q);
      }
    }
  }
  if (const std::uint8_t tag = p.tags[n]; tag != 0) {  // most particles carry none
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        for (int c = 0; c < 3; ++c) {
          const std::size_t node = st.node(a, b, c);
          grid.tags[node] |= tag;
          grid.block_tags[node / kBlockNodes] |= tag;
        }
      }
    }
  }
}

// Particle i's velocity, affine matrix and position from the nodes of its stencil; returns its
// squared speed. v = sum N p_a / m_a (paper, Eq. S17), C = 4 / dx^2 sum N (p_a / m_a) d^T
// (paper, Eq. S18), x += dt v.
[[gnu::always_inline]] inline double gather_particle(const SparseGrid& grid, Particles& p,
                                                     double dx, double dt, std::size_t i) {
  const double inv_dx = 1.0 / dx;
  const double apic = 4.0 * inv_dx * inv_dx;
  const Stencil st(grid, p.x, i, dx);
  // v = sum w v_node; B = sum w v_node d^T, d = x_node - x_p, summed axis by axis: column z
  // per node, column y per (a, b) row, column x per a plane. A node's (m, px, py, pz) goes as
  // one vector: lanes 1 to 3 are the x, y and z rows, each the scalar sum in the same order
  // (lane 0 sums s m, which nothing uses).
  Quad vq = {0, 0, 0, 0}, bx = {0, 0, 0, 0}, by = {0, 0, 0, 0}, bz = {0, 0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    Quad sa = {0, 0, 0, 0};
    for (int b = 0; b < 3; ++b) {
      Quad sab = {0, 0, 0, 0};
      const double wab = st.w[0][a] * st.w[1][b];
      for (int c = 0; c < 3; ++c) {
        Quad g;
        std::memcpy(&g, &grid.nodes[st.node(a, b, c)], sizeof g);
        // A node of zero weight that no other particle reaches has no mass (and no momentum).
        const double s = g[0] > 0.0 ? wab * st.w[2][c] / g[0] : 0.0;
        const Quad q = s * g;
        sab += q;
        bz += q * st.d[2][c];
      }
      sa += sab;
      by += sab * st.d[1][b];
    }
    vq += sa;
    bx += sa * st.d[0][a];
  }
  const double v[3] = {vq[1], vq[2], vq[3]};
  const double B[9] = {bx[1], by[1], bz[1], bx[2], by[2], bz[2], bx[3], by[3], bz[3]};
  p.v.x[i] = v[0];
  p.v.y[i] = v[1];
  p.v.z[i] = v[2];
  double* C = &p.C[9 * i];
  for (int k = 0; k < 9; ++k) C[k] = apic * B[k];
  p.x.x[i] += dt * v[0];
  p.x.y[i] += dt * v[1];
  p.x.z[i] += dt * v[2];
  return v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
}

// The particles of a run of the home order scattered, or gathered (with the largest squared speed
// and the lowest-numbered particle whose speed is not finite, the largest long if none). Each is
// compiled twice on x86-64 (core/wide.hpp); the particle's code is inlined into both.
struct Gathered {
  double vmax2 = 0.0;
  long bad = std::numeric_limits<long>::max();
};
[[gnu::always_inline]] inline Gathered gather_particles(const SparseGrid& grid, Particles& p,
                                                        double dx, double dt,
                                                        std::span<const int> run) {
  Gathered out;
  for (const int i : run) {
    const double s2 = gather_particle(grid, p, dx, dt, static_cast<std::size_t>(i));
    if (std::isfinite(s2)) {
      out.vmax2 = std::max(out.vmax2, s2);
    } else {
      out.bad = std::min(out.bad, static_cast<long>(i));
    }
  }
  return out;
}
void scatter_run(SparseGrid& grid, const Particles& p, double dx, std::span<const int> run) {
  for (const int i : run) scatter_particle(grid, p, dx, static_cast<std::size_t>(i));
}
SNAPJUMP_AVX2 void scatter_run_wide(SparseGrid& grid, const Particles& p, double dx,
                                    std::span<const int> run) {
  for (const int i : run) scatter_particle(grid, p, dx, static_cast<std::size_t>(i));
}
Gathered gather_run(const SparseGrid& grid, Particles& p, double dx, double dt,
                    std::span<const int> run) {
  return gather_particles(grid, p, dx, dt, run);
}
SNAPJUMP_AVX2 Gathered gather_run_wide(const SparseGrid& grid, Particles& p, double dx, double dt,
                                       std::span<const int> run) {
  return gather_particles(grid, p, dx, dt, run);
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

Particles Particles::at_rest(const core::Points& positions, const std::vector<double>& masses) {
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
    : p_(std::move(particles)),
      forces_(forces),
      options_(options),
      grid_(options.dx),
      tuner_(parallel::ThreadTuner::for_process(options.tune_threads)) {
  wide_ = options_.wide_vectors && core::has_avx2();
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
  tuner_.run([this] {
    update_particle_velocities();
    particle_to_grid();
    apply_grid_rules();
    grid_to_particle();
    advance_rigid_bodies();
  });
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
  // The particle's equation of motion m a = f (paper, Eq. S8) by an explicit step, with the
  // quasi-static phases' mass-proportional damping taken semi-implicitly.
  const double keep = 1.0 / (1.0 + options_.damping * dt);
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
  rebuild_grid();
  scatter_to_grid();
}

void Stepper::rebuild_grid() { grid_.rebuild(p_.x); }

// One parallel region, no barrier: each thread takes its run of cubes (thread_first_cube) and
// goes through them colour by colour. Two cubes that share nodes are adjacent and differ in
// colour; the one of lower colour must add its sums first. Within a thread that is the order it
// goes in; across threads, a cube waits until its earlier neighbours of other threads are marked
// done for this step (an acquire load that sees the other thread's release store). A wait is
// always for a lower colour, which its thread reaches before any wait of a higher one: the waits
// end. Each node's sums come in the order a single thread gives, whatever the threads.
void Stepper::scatter_to_grid() {
  const auto cubes = grid_.cubes();
  if (cube_done_.size() != cubes.size()) cube_done_.assign(cubes.size(), 0);
  const std::uint64_t epoch = ++scatter_epoch_;
#pragma omp parallel
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
    const std::size_t first = grid_.thread_first_cube(t, threads),
                      end = grid_.thread_first_cube(t + 1, threads);
    for (int colour = 0; colour < 8; ++colour) {
      for (std::size_t q = first; q < end; ++q) {
        if (cubes[q].colour != colour) continue;
        if (threads > 1) {
          for (const int d : grid_.earlier_neighbours_of_cube(q)) {
            const auto ds = static_cast<std::size_t>(d);
            if (ds >= first && ds < end) continue;  // this thread's own: done
            std::atomic_ref<std::uint64_t> done(cube_done_[ds]);
            for (int spins = 0; done.load(std::memory_order_acquire) != epoch;) {
              if (spins < 1000) {
                ++spins;
              } else {
                std::this_thread::yield();
              }
            }
          }
        }
        const auto run = grid_.particles_of_cubes(q, q + 1);
        if (wide_) {
          scatter_run_wide(grid_, p_, options_.dx, run);
        } else {
          scatter_run(grid_, p_, options_.dx, run);
        }
        if (threads > 1) {
          std::atomic_ref<std::uint64_t>(cube_done_[q]).store(epoch, std::memory_order_release);
        }
      }
    }
  }
}

void Stepper::apply_grid_rules() {
  const StepContext ctx{options_.dt, time_};
  for (auto& rule : rules_) rule->apply(grid_, ctx);
}

void Stepper::grid_to_particle() {
  double vmax2 = 0.0;
  // The lowest-numbered particle whose velocity is not finite (none: the particle count), the
  // same at any thread count.
  const long none = static_cast<long>(p_.size());
  long bad = none;
  // In the grid's home order: particles that share nodes come one after another. Each thread
  // takes the particles of the cubes it scattered (their nodes are in its cache).
#pragma omp parallel reduction(max : vmax2) reduction(min : bad)
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
    const auto run = grid_.particles_of_cubes(grid_.thread_first_cube(t, threads),
                                              grid_.thread_first_cube(t + 1, threads));
    const Gathered g = wide_ ? gather_run_wide(grid_, p_, options_.dx, options_.dt, run)
                             : gather_run(grid_, p_, options_.dx, options_.dt, run);
    vmax2 = std::max(vmax2, g.vmax2);
    bad = std::min(bad, g.bad);
  }
  const double t = time_ + options_.dt;
  if (const long i = bad; i < none) {
    throw StepError(fmt::format("t = {:.6g} s, step {}: particle {} has a non-finite velocity", t,
                                steps_ + 1, i));
  }
  max_speed_ = std::sqrt(vmax2);
  if (cfl() > options_.max_cfl) {
    throw StepError(fmt::format(
        "t = {:.6g} s, step {}: a particle moves {:.3g} grid cells per step (speed {:.3g} m/s), "
        "more than the allowed {}: the popper's time step assumes speeds up to 2 m/s "
        "(docs/popper.md); a larger numerics.grid_spacing allows faster ones",
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
