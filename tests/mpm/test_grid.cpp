// The sparse grid's grouping of particles into blocks and colours.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/body.hpp"
#include "mesh/cap_mesher.hpp"
#include "mesh/solid_mesher.hpp"
#include "mpm/grid.hpp"
#include "mpm/mpm_test_support.hpp"
#include "mpm/stepper.hpp"

namespace snapjump::mpm {

namespace {

using namespace testing;  // mpm_test_support.hpp

// The nodes a particle's stencil touches, as integer coordinates, from the grid's grouping.
std::vector<std::array<std::int64_t, 3>> stencil_nodes(const SparseGrid& g, std::size_t p) {
  const auto& home =
      g.block_coords(static_cast<std::size_t>(g.neighbours_of_home(g.home_of(p))[0]));
  const auto& local = g.local_of(p);
  std::vector<std::array<std::int64_t, 3>> out;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      for (int c = 0; c < 3; ++c) {
        out.push_back({kBlock * home[0] + local[0] + a, kBlock * home[1] + local[1] + b,
                       kBlock * home[2] + local[2] + c});
      }
    }
  }
  return out;
}

// The grid's grouping: each particle's stencil starts where the B-spline says; two cubes that
// write a node differ in colour and the later one lists the earlier among its earlier neighbours
// (so the scatter can order their sums whatever thread runs each); the threads' runs of cubes
// cover the cubes in order with about equal particle counts; a rebuild after a small move groups
// the particles as a fresh grid does.
TEST(Grid, CubesSharingANodeAreOrderedAndARebuildEqualsAFreshBuild) {
  const double dx = 0.0005;  // the 20 mm cloud spans about three cubes of 16 cells a side
  auto p = random_particles(3000, 11);
  SparseGrid g(dx);
  g.rebuild(p.x);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto first = stencil_nodes(g, i).front();
    EXPECT_EQ(first[0], static_cast<std::int64_t>(std::floor(p.x.x[i] / dx - 0.5))) << i;
    EXPECT_EQ(first[1], static_cast<std::int64_t>(std::floor(p.x.y[i] / dx - 0.5))) << i;
    EXPECT_EQ(first[2], static_cast<std::int64_t>(std::floor(p.x.z[i] / dx - 0.5))) << i;
  }
  const auto cubes = g.cubes();
  ASSERT_GT(cubes.size(), 8U);
  std::map<std::array<std::int64_t, 3>, std::set<std::size_t>> writers;  // node -> cubes
  std::size_t grouped = 0;
  for (std::size_t q = 0; q < cubes.size(); ++q) {
    EXPECT_EQ(g.first_particle_of_cube(q), grouped);
    for (int h = cubes[q].first_home; h < cubes[q].end_home; ++h) {
      for (const int i : g.particles_of(h)) {
        ++grouped;
        for (const auto& node : stencil_nodes(g, static_cast<std::size_t>(i)))
          writers[node].insert(q);
      }
    }
  }
  EXPECT_EQ(grouped, p.size());
  EXPECT_EQ(g.first_particle_of_cube(cubes.size()), p.size());
  std::size_t shared = 0;
  for (const auto& [node, qs] : writers) {
    for (const std::size_t a : qs) {
      for (const std::size_t b : qs) {
        if (a == b) continue;
        ++shared;
        ASSERT_NE(cubes[a].colour, cubes[b].colour) << "cubes " << a << " and " << b;
        const std::size_t later = cubes[a].colour > cubes[b].colour ? a : b;
        const std::size_t earlier = later == a ? b : a;
        const auto deps = g.earlier_neighbours_of_cube(later);
        EXPECT_NE(std::find(deps.begin(), deps.end(), static_cast<int>(earlier)), deps.end())
            << "cube " << later << " does not wait for cube " << earlier;
      }
    }
  }
  EXPECT_GT(shared, 0U);  // the random cloud has cubes that share nodes
  // A thread's share differs from an even one by at most the largest cube's.
  double largest = 0.0;
  for (std::size_t q = 0; q < cubes.size(); ++q) {
    largest = std::max(largest, static_cast<double>(g.first_particle_of_cube(q + 1) -
                                                    g.first_particle_of_cube(q)) /
                                    static_cast<double>(p.size()));
  }
  for (const int threads : {1, 2, 3, 4}) {
    EXPECT_EQ(g.thread_first_cube(0, threads), 0U);
    EXPECT_EQ(g.thread_first_cube(threads, threads), cubes.size());
    for (int t = 0; t < threads; ++t) {
      const std::size_t a = g.thread_first_cube(t, threads),
                        b = g.thread_first_cube(t + 1, threads);
      ASSERT_LE(a, b);
      const double share =
          static_cast<double>(g.first_particle_of_cube(b) - g.first_particle_of_cube(a)) /
          static_cast<double>(p.size());
      EXPECT_LE(std::abs(share - 1.0 / threads), largest) << t << " of " << threads;
    }
  }
  // Move every particle by a tenth of a cell and rebuild; a fresh grid on the same positions
  // groups them alike.
  for (std::size_t i = 0; i < p.size(); ++i)
    p.x.x[i] += 0.1 * dx * std::sin(static_cast<double>(i));
  g.rebuild(p.x);
  SparseGrid fresh(dx);
  fresh.rebuild(p.x);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(stencil_nodes(g, i), stencil_nodes(fresh, i)) << "particle " << i;
  }
}

// The blocks are made around the particles' homes (every block within one block of one) and kept
// while the particles stay among them, regrouped when one moves into another block; they are
// made again when a particle goes further. Kept or made again, the grouping and the blocks the
// stencils reach (in the order the rules visit them) are a fresh grid's.
TEST(Grid, KeepsItsBlocksWhileTheParticlesStayAmongThem) {
  const double dx = 0.001;
  core::Points x;
  x.push_back(0.0101, 0.0101, 0.0101);  // grid units 10.1: stencil from node 9 (block 2, local 1)
  x.push_back(0.0205, 0.0101, 0.0101);  // 20.5: from node 20 (block 5, local 0)
  SparseGrid g(dx);
  const auto live_coords = [](const SparseGrid& grid) {
    std::vector<std::array<std::int64_t, 3>> out;
    for (const int b : grid.live_blocks())
      out.push_back(grid.block_coords(static_cast<std::size_t>(b)));
    return out;
  };
  const auto as_fresh = [&] {
    SparseGrid fresh(dx);
    fresh.rebuild(x);
    for (std::size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(stencil_nodes(g, i), stencil_nodes(fresh, i)) << "particle " << i;
      const auto mine = g.particles_of(g.home_of(i)), theirs = fresh.particles_of(fresh.home_of(i));
      EXPECT_EQ(std::vector<int>(mine.begin(), mine.end()),
                std::vector<int>(theirs.begin(), theirs.end()));
    }
    EXPECT_EQ(live_coords(g), live_coords(fresh));
  };
  g.rebuild(x);
  EXPECT_EQ(g.full_rebuilds(), 1);
  x.x[0] += 0.1 * dx;  // within its block and reach
  g.rebuild(x);
  EXPECT_EQ(g.full_rebuilds(), 1);
  as_fresh();
  x.x[0] = 0.0206;  // into particle 1's block
  g.rebuild(x);
  EXPECT_EQ(g.full_rebuilds(), 1);
  EXPECT_EQ(g.home_of(0), g.home_of(1));
  as_fresh();
  x.x[0] = 0.0227;  // 22.7: local index 2, reaching into block 6
  g.rebuild(x);
  EXPECT_EQ(g.full_rebuilds(), 1);
  as_fresh();
  x.x[0] = 0.0101;  // back to block 2, where no particle is now
  g.rebuild(x);
  EXPECT_EQ(g.full_rebuilds(), 1);
  as_fresh();
  x.x[1] = 0.0305;  // 30.5: block 7, two blocks from every home of the last build
  g.rebuild(x);
  EXPECT_EQ(g.full_rebuilds(), 2);
  as_fresh();
  x.x[1] = 0.0245;  // block 6, next to the new home
  g.rebuild(x);
  EXPECT_EQ(g.full_rebuilds(), 2);
  as_fresh();
}

// A particle beyond the grid's range (about 2^20 blocks from the origin) is refused with a
// message, and the grid goes on afterwards as a fresh one would.
TEST(Grid, AParticleOutOfRangeIsRefusedAndTheGridRecovers) {
  const double dx = 0.001;
  core::Points x;
  x.push_back(0.0101, 0.0101, 0.0101);
  x.push_back(0.0305, 0.0101, 0.0101);
  SparseGrid g(dx);
  g.rebuild(x);
  x.x[1] = 1.0e4;  // 10 km: 2.5 million blocks out
  try {
    g.rebuild(x);
    FAIL() << "no error for a particle out of range";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("left the grid's range"), std::string::npos) << e.what();
  }
  x.x[1] = 0.0111;  // into particle 0's block
  g.rebuild(x);
  SparseGrid fresh(dx);
  fresh.rebuild(x);
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(stencil_nodes(g, i), stencil_nodes(fresh, i)) << "particle " << i;
  }
  EXPECT_EQ(g.live_blocks().size(), fresh.live_blocks().size());
}

// Blocks that no stencil reaches hold zeros, whatever the last steps wrote into the blocks that
// were reached then: the transfers add into nodes they expect at zero.
TEST(Grid, EveryNodeIsZeroAfterARebuildWhateverTheLastStepWrote) {
  const double dx = 0.002;
  auto p = random_particles(500, 5);
  SparseGrid g(dx);
  const auto fill_reached = [&] {  // what a step's transfer and rules leave behind
    for (const int b : g.live_blocks()) {
      for (std::size_t a = static_cast<std::size_t>(b) * kBlockNodes;
           a < static_cast<std::size_t>(b + 1) * kBlockNodes; ++a) {
        g.nodes[a] = {1.0, 2.0, 3.0, 4.0};
        g.tags[a] = 1;
      }
      g.block_tags[static_cast<std::size_t>(b)] = 1;
    }
  };
  const auto all_zero = [&] {
    for (std::size_t a = 0; a < g.num_nodes(); ++a) {
      if (g.nodes[a].m != 0.0 || g.nodes[a].px != 0.0 || g.nodes[a].py != 0.0 ||
          g.nodes[a].pz != 0.0 || g.tags[a] != 0) {
        return false;
      }
    }
    return std::all_of(g.block_tags.begin(), g.block_tags.end(), [](auto t) { return t == 0; });
  };
  g.rebuild(p.x);
  const long made = g.full_rebuilds();
  for (int step = 0; step < 6; ++step) {
    fill_reached();
    // Every particle a quarter cell along x: some change block (regrouped), the blocks kept.
    for (std::size_t i = 0; i < p.size(); ++i) p.x.x[i] += 0.25 * dx;
    g.rebuild(p.x);
    EXPECT_TRUE(all_zero()) << "step " << step;
  }
  EXPECT_EQ(g.full_rebuilds(), made) << "the blocks were made again: the test would not cover "
                                        "kept blocks";
}

}  // namespace
}  // namespace snapjump::mpm
