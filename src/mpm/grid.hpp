// A background grid that exists only where particles are: blocks of 4 x 4 x 4 nodes found through
// a hash of their integer coordinates, so the domain is unbounded (the popper flies). The nodes'
// (m, p) records lie block after block, the blocks along a Morton curve.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/points.hpp"

namespace snapjump::mpm {

inline constexpr int kBlock = 4;  // nodes per block edge
inline constexpr int kBlockNodes = kBlock * kBlock * kBlock;

class SparseGrid {
 public:
  explicit SparseGrid(double dx);

  [[nodiscard]] double dx() const { return dx_; }

  // Makes the blocks around the particles at x, groups the particles by the block of their
  // stencil's first node (their home), finds the blocks their quadratic B-spline stencils reach
  // (live_blocks) and zeroes the node data. The blocks are made for every home within one block
  // of a particle's, so a particle that moves into a neighbouring block is only regrouped; they
  // are made again when a particle goes beyond them. The orders the transfers and rules sum in
  // are those of a fresh grid either way: results do not depend on the grid's history.
  void rebuild(const core::Points& x);

  // --- nodes ---------------------------------------------------------------------------------
  // Mass and momentum of a node, together: a transfer touches all four at once.
  struct Node {
    double m = 0.0, px = 0.0, py = 0.0, pz = 0.0;
  };
  [[nodiscard]] std::size_t num_nodes() const { return nodes.size(); }
  // Integer coordinates of node n (its position is dx times these).
  [[nodiscard]] std::array<std::int64_t, 3> coords(std::size_t n) const;
  std::vector<Node> nodes;
  std::vector<std::uint8_t> tags;        // OR of the tags of the particles that reached the node
  std::vector<std::uint8_t> block_tags;  // OR of the node tags of each block
  // Integer coordinates of block b (its nodes are kBlock times these plus 0..3).
  [[nodiscard]] const std::array<std::int64_t, 3>& block_coords(std::size_t b) const {
    return block_coords_[b];
  }

  // --- particles, as grouped by rebuild() ----------------------------------------------------
  // For particle p: its home (an index into the home slots, numbered along the Morton curve; see
  // neighbours_of_home) and the local index (0..3) of its stencil's first node in that block, per
  // axis. The slots are the blocks within one block of a particle's home at the last time the
  // blocks were made: many hold no particle now.
  [[nodiscard]] int home_of(std::size_t p) const { return home_[p]; }
  [[nodiscard]] const std::array<std::uint8_t, 3>& local_of(std::size_t p) const {
    return local_[p];
  }
  // Block ids of home slot h and of its neighbours: entry nb (bit 0: +x, bit 1: +y, bit 2: +z)
  // is the block that holds the stencil nodes whose local index overflows along those axes. All
  // eight exist for every slot.
  [[nodiscard]] const std::array<int, 8>& neighbours_of_home(int h) const { return neighbours_[h]; }
  // The cubes of 4 x 4 x 4 blocks that the scatter works in, those with home slots, in Morton
  // order (the slots' order). Cube q holds the home slots [first_home, end_home); its colour (0..7)
  // is the parity of its coordinates. A cube's stencils write into the cube and one block beyond on
  // its + sides, so two cubes share nodes only if they are adjacent (faces, edges or corners), and
  // adjacent cubes differ in colour: the scatter runs each cube whole, in one thread, and a node's
  // sums come in colour order whatever the threads are.
  struct Cube {
    int first_home = 0, end_home = 0;
    int colour = 0;
  };
  [[nodiscard]] std::span<const Cube> cubes() const { return cubes_; }
  // The cubes adjacent to cube q with a lower colour: those whose sums must come before q's.
  [[nodiscard]] std::span<const int> earlier_neighbours_of_cube(std::size_t q) const {
    return {cube_deps_.data() + cube_dep_start_[q], cube_deps_.data() + cube_dep_start_[q + 1]};
  }
  // Where thread t of `threads` starts in the cubes: the cubes are split into `threads` runs
  // along the curve with about equal particle counts (thread_first_cube(threads, threads) is the
  // number of cubes). The scatter, grid to particle and the zeroing split space here, so that a
  // thread finds the nodes it wrote in its own cache.
  [[nodiscard]] std::size_t thread_first_cube(int t, int threads) const;
  // Position in particles_in_home_order() of cube q's first particle (q = number of cubes: the
  // number of particles).
  [[nodiscard]] std::size_t first_particle_of_cube(std::size_t q) const {
    return static_cast<std::size_t>(start_[static_cast<std::size_t>(
        q < cubes_.size() ? cubes_[q].first_home : static_cast<int>(neighbours_.size()))]);
  }
  // The particles of cubes [first, end), in home order (a stretch of particles_in_home_order()).
  [[nodiscard]] std::span<const int> particles_of_cubes(std::size_t first, std::size_t end) const {
    return {order_.data() + first_particle_of_cube(first),
            order_.data() + first_particle_of_cube(end)};
  }
  // All particles, grouped by home, homes in Morton order.
  [[nodiscard]] std::span<const int> particles_in_home_order() const { return order_; }
  // Particles whose home is slot h (an index into the home slots; often none).
  [[nodiscard]] std::span<const int> particles_of(int h) const {
    return {order_.data() + start_[h], order_.data() + start_[h + 1]};
  }
  [[nodiscard]] std::size_t num_blocks() const { return block_coords_.size(); }
  // The blocks that the last rebuild's stencils reach, in memory order (the curve's). The nodes
  // of every other block are zero, and must stay so: a block kept from step to step may be
  // reached again later, and rebuild() zeroes only the blocks that were reached. A grid rule
  // writes to nodes of these blocks only (and sums in an order fixed by this one, so that a
  // fresh grid and a kept one give the same bits; see GridRule::apply).
  [[nodiscard]] std::span<const int> live_blocks() const { return live_; }
  // How many calls of rebuild() made the blocks again (the others kept them).
  [[nodiscard]] long full_rebuilds() const { return full_rebuilds_; }

 private:
  int block_id(std::int64_t bx, std::int64_t by, std::int64_t bz);
  bool regroup();      // the blocks kept, particles regrouped; false if blocks are missing
  void make_blocks();  // the blocks made again from scratch_keys_ and scratch_reach_
  // make_blocks' steps, in their order.
  std::size_t make_home_slots();
  void order_blocks_along_curve(std::size_t nh);
  std::vector<std::array<std::int64_t, 3>> make_cubes(std::size_t nh);
  void make_cube_dependencies(const std::vector<std::array<std::int64_t, 3>>& cube_coords);
  void group_particles();  // order_ and start_ from home_
  void find_live_blocks();
  void zero_live_blocks();

  double dx_;
  std::vector<std::uint64_t> home_key_;      // per particle: key of its home block, last rebuild
  std::vector<std::uint8_t> home_reach_;     // per particle: blocks its stencil crossed into
  std::vector<std::uint64_t> scratch_keys_;  // reused between calls
  std::vector<std::uint8_t> scratch_reach_;
  std::vector<std::array<std::int64_t, 3>> scratch_blocks_;
  std::unordered_map<std::uint64_t, int> block_index_;
  std::vector<std::array<std::int64_t, 3>> block_coords_;
  // Per home slot: block ids of itself and its +x, +y, +z... neighbours.
  std::vector<std::array<int, 8>> neighbours_;
  std::vector<int> home_;           // per particle
  std::vector<int> home_of_block_;  // per block: its home number, -1 if it is no home
  std::vector<std::array<std::uint8_t, 3>> local_;
  std::vector<int> order_, start_;       // particles sorted by home block
  std::vector<int> fill_;                // scratch of the sort
  std::vector<int> live_;                // blocks the stencils reach, ascending
  std::vector<std::uint8_t> live_mark_;  // scratch of find_live_blocks
  std::vector<Cube> cubes_;
  std::vector<int> cube_dep_start_, cube_deps_;  // earlier neighbours of each cube (CSR)
  long full_rebuilds_ = 0;
};

// Quadratic B-spline weights of a particle at x (in grid units) with respect to the nodes
// base, base + 1, base + 2, base = floor(x - 0.5): per axis, the basis N_alpha of the transfers
// (paper, Eqs. S14, S15, S17, S18).
struct Weights {
  std::int64_t base;
  std::array<double, 3> w;
};
inline Weights bspline_weights(double x_over_dx) {
  const double b = std::floor(x_over_dx - 0.5);
  const double fx = x_over_dx - b;  // in [0.5, 1.5)
  return {static_cast<std::int64_t>(b),
          {0.5 * (1.5 - fx) * (1.5 - fx), 0.75 - (fx - 1.0) * (fx - 1.0),
           0.5 * (fx - 0.5) * (fx - 0.5)}};
}

}  // namespace snapjump::mpm
