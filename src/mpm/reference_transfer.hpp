// The particle-grid transfers of the paper's "Contact analysis by MPM" written as plainly as
// possible: one particle at a time, one node at a time, the grid a map from node coordinates to
// sums. This is the specification the optimised transfers of mpm::Stepper (blocks, colours,
// separable stencils, Morton order, AVX2) are checked against (tests/mpm/test_transfers.cpp); it
// is slow and is not used in a run.
//
// With the quadratic B-spline N(r) per axis and d = x_a - x_i the offset of node a from
// particle i:
//   particle to grid   m_a = sum_i m_i N                  (paper, Eq. S15)
//                      p_a = sum_i m_i (v_i + C_i d) N    (paper, Eq. S14)
//   grid to particle   v_i = sum_a N p_a / m_a            (paper, Eq. S17)
//                      C_i = 4 / dx^2 sum_a N (p_a / m_a) d^T  (paper, Eq. S18)
//                      x_i <- x_i + dt v_i
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "mpm/stepper.hpp"

namespace snapjump::mpm::reference {

// The quadratic B-spline of the distance r from a node in units of dx: 3/4 - r^2 for |r| < 1/2,
// (3/2 - |r|)^2 / 2 for |r| < 3/2, 0 beyond.
double quadratic_bspline(double r);

// A node's integer coordinates: the node sits at dx times them.
using NodeKey = std::array<std::int64_t, 3>;

// A node's mass and momentum after the particle-to-grid transfer.
struct NodeSums {
  double m = 0.0, px = 0.0, py = 0.0, pz = 0.0;
};
using GridSums = std::map<NodeKey, NodeSums>;

// The particles' mass and APIC momentum on the nodes of a grid of spacing dx; only the nodes some
// particle's stencil reaches are in the map.
GridSums particle_to_grid(const Particles& particles, double dx);

// A particle's new velocity, affine matrix (row-major, 9 entries) and position.
struct ParticleUpdate {
  std::array<double, 3> v{};
  std::array<double, 9> C{};
  std::array<double, 3> x{};
};

// The grid's velocities p_a / m_a back onto each particle, and the particle moved by dt v_i.
// Nodes of zero mass contribute nothing. Throws std::out_of_range where a particle's stencil
// reaches a node the grid does not hold.
std::vector<ParticleUpdate> grid_to_particle(const Particles& particles, const GridSums& grid,
                                             double dx, double dt);

}  // namespace snapjump::mpm::reference
