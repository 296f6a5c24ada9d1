// The particle-grid transfers: B-spline weights, conservation, the textbook's transfers, affine
// fields, angular momentum.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include "fem/body.hpp"
#include "mesh/cap_mesher.hpp"
#include "mesh/solid_mesher.hpp"
#include "mpm/grid.hpp"
#include "mpm/mpm_test_support.hpp"
#include "mpm/reference_transfer.hpp"
#include "mpm/stepper.hpp"

namespace snapjump::mpm {

namespace {

using namespace testing;  // mpm_test_support.hpp

TEST(Transfers, WeightsArePartitionOfUnityWithZeroFirstMoment) {
  for (double x : {0.0, 0.3, 0.5, 0.99, -1.7, 12.25}) {
    const auto w = bspline_weights(x);
    double sum = 0.0, moment = 0.0;
    for (int a = 0; a < 3; ++a) {
      sum += w.w[a];
      moment += w.w[a] * (static_cast<double>(w.base + a) - x);
    }
    EXPECT_NEAR(sum, 1.0, 1e-15);
    EXPECT_NEAR(moment, 0.0, 1e-14);
  }
}

TEST(Transfers, ParticleToGridConservesMassAndMomentum) {
  NoForces none;
  Stepper s(random_particles(500, 1), none, {1e-6, 0.002, 0.5});
  s.particle_to_grid();
  const auto& g = s.grid();
  const auto& p = s.particles();
  double M = 0, Px = 0, Py = 0, Pz = 0, m = 0, px = 0, py = 0, pz = 0;
  for (std::size_t a = 0; a < g.num_nodes(); ++a) {
    M += g.nodes[a].m;
    Px += g.nodes[a].px;
    Py += g.nodes[a].py;
    Pz += g.nodes[a].pz;
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    m += p.mass[i];
    px += p.mass[i] * p.v.x[i];
    py += p.mass[i] * p.v.y[i];
    pz += p.mass[i] * p.v.z[i];
  }
  EXPECT_NEAR(M, m, 1e-14 * m);
  EXPECT_NEAR(Px, px, 1e-12 * m);
  EXPECT_NEAR(Py, py, 1e-12 * m);
  EXPECT_NEAR(Pz, pz, 1e-12 * m);
  // and back: grid to particle conserves the momentum the grid holds
  s.grid_to_particle();
  double qx = 0, qy = 0, qz = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    qx += p.mass[i] * p.v.x[i];
    qy += p.mass[i] * p.v.y[i];
    qz += p.mass[i] * p.v.z[i];
  }
  EXPECT_NEAR(qx, Px, 1e-12 * m);
  EXPECT_NEAR(qy, Py, 1e-12 * m);
  EXPECT_NEAR(qz, Pz, 1e-12 * m);
}

// The optimised transfers (blocks, colours, separable stencils, Morton order) against the
// textbook's, mpm::reference (src/mpm/reference_transfer.hpp), which shares nothing with the
// stepper but the particles' layout.
TEST(Transfers, TheOptimisedTransfersAreTheTextbooks) {
  NoForces none;
  const double dx = 0.002, dt = 1e-6;
  Stepper s(random_particles(300, 7), none, {dt, dx, 0.5});
  // A first transfer leaves its sums on the grid; the second, from the same particles, keeps the
  // blocks and must start again from zero (the grid zeroes each block as a transfer claims it).
  s.particle_to_grid();
  const auto p = s.particles();  // before the transfers
  const auto book = reference::particle_to_grid(p, dx);
  s.particle_to_grid();
  const auto& g = s.grid();
  double m_max = 0, p_max = 0;
  for (const auto& [key, n] : book) {
    m_max = std::max(m_max, n.m);
    p_max = std::max({p_max, std::abs(n.px), std::abs(n.py), std::abs(n.pz)});
  }
  std::size_t matched = 0;
  for (std::size_t a = 0; a < g.num_nodes(); ++a) {
    const auto it = book.find(g.coords(a));
    if (it == book.end()) {
      EXPECT_EQ(g.nodes[a].m, 0.0) << "a node the textbook's stencils do not reach";
      continue;
    }
    ++matched;
    EXPECT_NEAR(g.nodes[a].m, it->second.m, 1e-13 * m_max);
    EXPECT_NEAR(g.nodes[a].px, it->second.px, 1e-12 * p_max);
    EXPECT_NEAR(g.nodes[a].py, it->second.py, 1e-12 * p_max);
    EXPECT_NEAR(g.nodes[a].pz, it->second.pz, 1e-12 * p_max);
  }
  EXPECT_EQ(matched, book.size());  // every node the textbook fills is on the grid
  // Grid to particle.
  s.grid_to_particle();
  const auto& q = s.particles();
  const auto want = reference::grid_to_particle(p, book, dx, dt);
  ASSERT_EQ(want.size(), q.size());
  double v_max = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& [v, C, x] = want[i];
    const double got_v[3] = {q.v.x[i], q.v.y[i], q.v.z[i]};
    const double got_x[3] = {q.x.x[i], q.x.y[i], q.x.z[i]};
    for (int r = 0; r < 3; ++r) {
      v_max = std::max(v_max, std::abs(v[r]));
      EXPECT_NEAR(got_v[r], v[r], 1e-12) << "particle " << i;
      EXPECT_NEAR(got_x[r], x[r], 1e-15) << "particle " << i;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(q.C[9 * i + 3 * r + c], C[3 * r + c], 1e-9 * (1.0 + std::abs(C[3 * r + c])))
            << "particle " << i;
      }
    }
  }
  EXPECT_GT(v_max, 0.1);  // the velocities are not trivially zero
}

// The textbook's B-spline at the points where its pieces meet and beyond its support, and its
// stencil's 27 weights summing to one.
TEST(Transfers, TheTextbooksSplineIsTheQuadraticBSpline) {
  EXPECT_DOUBLE_EQ(reference::quadratic_bspline(0.0), 0.75);
  EXPECT_DOUBLE_EQ(reference::quadratic_bspline(0.5), 0.5);
  EXPECT_DOUBLE_EQ(reference::quadratic_bspline(-0.5), 0.5);
  EXPECT_DOUBLE_EQ(reference::quadratic_bspline(1.0), 0.125);
  EXPECT_DOUBLE_EQ(reference::quadratic_bspline(1.5), 0.0);
  EXPECT_DOUBLE_EQ(reference::quadratic_bspline(-2.0), 0.0);
  core::Points at;
  at.push_back(0.0031, -0.0017, 0.0109);
  const auto one = Particles::at_rest(at, {2.0});
  const auto grid = reference::particle_to_grid(one, 0.002);
  double m = 0.0;
  for (const auto& [key, n] : grid) m += n.m;
  EXPECT_EQ(grid.size(), 27u);
  EXPECT_NEAR(m, 2.0, 1e-15);
}

// The transfers update a node's four values and a particle's rows two lanes at a time: every
// value must be the plain scalar expression's, bit for bit, summed in the order the code
// documents (z per node, y per row, x per plane). Particles far apart, so that each node holds
// one particle's share and the expected sums can be written down here.
TEST(Transfers, TheTransfersGiveTheScalarExpressionsBits) {
  NoForces none;
  const double dx = 0.002, dt = 1e-6;
  auto particles = random_particles(4, 11);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.x.x[i] += 0.1 * static_cast<double>(i);  // 50 cells apart
  }
  const auto p = particles;
  Stepper s(std::move(particles), none, {dt, dx, 0.5});
  s.particle_to_grid();
  const auto& g = s.grid();
  std::map<std::array<std::int64_t, 3>, SparseGrid::Node> grid;
  for (std::size_t a = 0; a < g.num_nodes(); ++a) {
    if (g.nodes[a].m != 0.0) grid[g.coords(a)] = g.nodes[a];
  }
  EXPECT_EQ(grid.size(), 27 * p.size());  // the stencils do not overlap
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  const double inv_dx = 1.0 / dx;
  // The weights w, offsets d = x_node - x_p and first node of a particle at xi, per axis.
  struct Spline {
    std::array<std::array<double, 3>, 3> w, d;
    std::array<std::int64_t, 3> base;
  };
  const auto spline = [&](const double* xi) {
    Spline out;
    for (int ax = 0; ax < 3; ++ax) {
      const auto wts = bspline_weights(xi[ax] * inv_dx);
      out.base[ax] = wts.base;
      for (int a = 0; a < 3; ++a) {
        out.w[ax][a] = wts.w[a];
        out.d[ax][a] = static_cast<double>(wts.base + a) * dx - xi[ax];
      }
    }
    return out;
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double xi[3] = {p.x.x[i], p.x.y[i], p.x.z[i]};
    const auto [w, d, base] = spline(xi);
    const double* C = &p.C[9 * i];
    const double v[3] = {p.v.x[i], p.v.y[i], p.v.z[i]};
    // Particle to grid: m w and m w (v + C d), C d summed x, y, z.
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        for (int c = 0; c < 3; ++c) {
          const double mw = p.mass[i] * w[0][a] * w[1][b] * w[2][c];
          double u[3];
          for (int r = 0; r < 3; ++r) {
            u[r] = v[r] + C[3 * r] * d[0][a] + C[3 * r + 1] * d[1][b] + C[3 * r + 2] * d[2][c];
          }
          const auto& n = grid.at({base[0] + a, base[1] + b, base[2] + c});
          EXPECT_EQ(bits(n.m), bits(mw)) << "particle " << i;
          EXPECT_EQ(bits(n.px), bits(mw * u[0])) << "particle " << i;
          EXPECT_EQ(bits(n.py), bits(mw * u[1])) << "particle " << i;
          EXPECT_EQ(bits(n.pz), bits(mw * u[2])) << "particle " << i;
        }
      }
    }
  }
  s.grid_to_particle();
  const auto& q = s.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double xi[3] = {p.x.x[i], p.x.y[i], p.x.z[i]};
    const auto [w, d, base] = spline(xi);
    double v[3] = {}, B[9] = {};
    for (int a = 0; a < 3; ++a) {
      double sa[3] = {};
      for (int b = 0; b < 3; ++b) {
        double sab[3] = {};
        for (int c = 0; c < 3; ++c) {
          const auto& n = grid.at({base[0] + a, base[1] + b, base[2] + c});
          const double share = w[0][a] * w[1][b] * w[2][c] / n.m;
          const double pn[3] = {n.px, n.py, n.pz};
          for (int r = 0; r < 3; ++r) {
            sab[r] += share * pn[r];
            B[3 * r + 2] += share * pn[r] * d[2][c];
          }
        }
        for (int r = 0; r < 3; ++r) {
          sa[r] += sab[r];
          B[3 * r + 1] += sab[r] * d[1][b];
        }
      }
      for (int r = 0; r < 3; ++r) {
        v[r] += sa[r];
        B[3 * r] += sa[r] * d[0][a];
      }
    }
    EXPECT_EQ(bits(q.v.x[i]), bits(v[0])) << "particle " << i;
    EXPECT_EQ(bits(q.v.y[i]), bits(v[1])) << "particle " << i;
    EXPECT_EQ(bits(q.v.z[i]), bits(v[2])) << "particle " << i;
    for (int k = 0; k < 9; ++k) {
      EXPECT_EQ(bits(q.C[9 * i + k]), bits(4.0 * inv_dx * inv_dx * B[k]))
          << "particle " << i << ", entry " << k;
    }
    EXPECT_EQ(bits(q.x.x[i]), bits(xi[0] + dt * v[0])) << "particle " << i;
    EXPECT_EQ(bits(q.x.y[i]), bits(xi[1] + dt * v[1])) << "particle " << i;
    EXPECT_EQ(bits(q.x.z[i]), bits(xi[2] + dt * v[2])) << "particle " << i;
  }
}

// APIC transfers reproduce any affine velocity field v = A x + b exactly, with C = A.
TEST(Transfers, AffineVelocityFieldIsReproducedExactly) {
  NoForces none;
  auto particles = random_particles(800, 2);
  const double A[9] = {0.3, -1.2, 0.4, 1.1, 0.2, -0.5, -0.7, 0.6, -0.1};
  const double b[3] = {0.1, -0.2, 0.05};
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double x[3] = {particles.x.x[i], particles.x.y[i], particles.x.z[i]};
    particles.v.x[i] = A[0] * x[0] + A[1] * x[1] + A[2] * x[2] + b[0];
    particles.v.y[i] = A[3] * x[0] + A[4] * x[1] + A[5] * x[2] + b[1];
    particles.v.z[i] = A[6] * x[0] + A[7] * x[1] + A[8] * x[2] + b[2];
    for (int k = 0; k < 9; ++k) particles.C[9 * i + k] = A[k];
  }
  const auto before = particles;
  Stepper s(std::move(particles), none, {1e-9, 0.002, 0.5});
  s.particle_to_grid();
  s.grid_to_particle();
  const auto& p = s.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR(p.v.x[i], before.v.x[i], 1e-12);
    EXPECT_NEAR(p.v.y[i], before.v.y[i], 1e-12);
    EXPECT_NEAR(p.v.z[i], before.v.z[i], 1e-12);
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(p.C[9 * i + k], A[k], 1e-9);
  }
}

double grid_angular_momentum_z(const SparseGrid& g) {
  double L = 0.0;
  for (std::size_t a = 0; a < g.num_nodes(); ++a) {
    const auto c = g.coords(a);
    L += static_cast<double>(c[0]) * g.dx() * g.nodes[a].py -
         static_cast<double>(c[1]) * g.dx() * g.nodes[a].px;
  }
  return L;
}

// A free elastic ball spinning about z: the angular momentum the grid carries stays constant.
TEST(Transfers, SpinningBodyKeepsItsAngularMomentum) {
  const fem::Body ball(mesh::make_ball_mesh(0.01, 0.05, 0.004),
                       fem::Material::from_young(1.2e6, 0.3, 1160.0));
  auto p = particles_of(ball);
  const double omega = 20.0;  // rad/s
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v.x[i] = -omega * p.x.y[i];
    p.v.y[i] = omega * p.x.x[i];
    const double C[9] = {0, -omega, 0, omega, 0, 0, 0, 0, 0};
    for (int k = 0; k < 9; ++k) p.C[9 * i + k] = C[k];
  }
  BodyForces forces(ball, 0.0);
  Stepper s(std::move(p), forces, {0.3 * ball.stable_time_step(1.0), 0.002, 0.5});
  s.update_particle_velocities();
  s.particle_to_grid();
  const double L0 = grid_angular_momentum_z(s.grid());
  s.apply_grid_rules();
  s.grid_to_particle();
  for (int k = 0; k < 300; ++k) s.step();
  s.update_particle_velocities();
  s.particle_to_grid();
  const double L1 = grid_angular_momentum_z(s.grid());
  EXPECT_GT(std::abs(L0), 0.0);
  EXPECT_NEAR(L1 / L0, 1.0, 1e-6) << "after " << s.steps() << " steps";
}

// Free fall of the clamped shell with its container: z(t) = -g t^2 / 2 within 0.1 %.
}  // namespace
}  // namespace snapjump::mpm
