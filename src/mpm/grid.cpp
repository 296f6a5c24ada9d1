#include "mpm/grid.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "core/morton.hpp"

namespace snapjump::mpm {
namespace {

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

constexpr std::int64_t kOffset = std::int64_t{1} << 20;  // 21 bits per axis
// How far from the origin, in cells, a particle may be: its home's slots and their neighbours
// (two blocks beyond the home on the + side, one on the - side) stay inside the keys' range.
constexpr double kReach = static_cast<double>(kBlock * (kOffset - 4));
// kSubsets[r]: bit nb set for every nb whose axis bits are among those of r.
constexpr std::array<std::uint8_t, 8> kSubsets = [] {
  std::array<std::uint8_t, 8> t{};
  for (int r = 0; r < 8; ++r) {
    for (int nb = 0; nb < 8; ++nb) {
      if ((nb & ~r) == 0) t[r] = static_cast<std::uint8_t>(t[r] | (1 << nb));
    }
  }
  return t;
}();
constexpr int kCubeShift = 2;  // a cube is 2^kCubeShift blocks on a side

std::uint64_t key(std::int64_t bx, std::int64_t by, std::int64_t bz) {
  return (static_cast<std::uint64_t>(bx + kOffset) << 42) |
         (static_cast<std::uint64_t>(by + kOffset) << 21) |
         static_cast<std::uint64_t>(bz + kOffset);
}

// The blocks' place on the Morton curve (coordinates offset to be non-negative).
std::uint64_t morton_key(const std::array<std::int64_t, 3>& b) {
  return core::morton_key(static_cast<std::uint64_t>(b[0] + kOffset),
                          static_cast<std::uint64_t>(b[1] + kOffset),
                          static_cast<std::uint64_t>(b[2] + kOffset));
}

}  // namespace

SparseGrid::SparseGrid(double dx) : dx_(dx) {
  if (!(dx > 0.0)) throw std::invalid_argument("grid spacing must be positive");
}

int SparseGrid::block_id(std::int64_t bx, std::int64_t by, std::int64_t bz) {
  if (bx <= -kOffset || bx >= kOffset || by <= -kOffset || by >= kOffset || bz <= -kOffset ||
      bz >= kOffset) {
    throw std::runtime_error(
        fmt::format("a particle left the grid's range (block ({}, {}, {}), grid spacing {} m)", bx,
                    by, bz, dx_));
  }
  const auto [it, inserted] =
      block_index_.try_emplace(key(bx, by, bz), static_cast<int>(block_coords_.size()));
  if (inserted) block_coords_.push_back({bx, by, bz});
  return it->second;
}

std::array<std::int64_t, 3> SparseGrid::coords(std::size_t n) const {
  const auto& b = block_coords_[n / kBlockNodes];
  const int l = static_cast<int>(n % kBlockNodes);
  return {b[0] * kBlock + l / (kBlock * kBlock), b[1] * kBlock + (l / kBlock) % kBlock,
          b[2] * kBlock + l % kBlock};
}

void SparseGrid::rebuild(const core::Points& x) {
  const std::size_t np = x.size();
  const double inv_dx = 1.0 / dx_;
  auto& keys = scratch_keys_;
  auto& blocks = scratch_blocks_;
  auto& reach = scratch_reach_;
  keys.resize(np);
  blocks.resize(np);
  reach.resize(np);
  local_.resize(np);
  const bool had_blocks = home_key_.size() == np && !block_coords_.empty();
  bool same = had_blocks;
  const long n = static_cast<long>(np);
  long bad = n;  // the lowest particle outside the grid's range or not finite (n: none)
#pragma omp parallel for schedule(static) reduction(&& : same) reduction(min : bad)
  for (long i = 0; i < n; ++i) {
    const auto p = static_cast<std::size_t>(i);
    const double gx = x.x[p] * inv_dx, gy = x.y[p] * inv_dx, gz = x.z[p] * inv_dx;
    if (!(std::abs(gx) < kReach && std::abs(gy) < kReach && std::abs(gz) < kReach)) {
      bad = std::min(bad, i);
      same = false;
      continue;
    }
    const std::int64_t b[3] = {static_cast<std::int64_t>(std::floor(gx - 0.5)),
                               static_cast<std::int64_t>(std::floor(gy - 0.5)),
                               static_cast<std::int64_t>(std::floor(gz - 0.5))};
    for (int d = 0; d < 3; ++d) {
      blocks[p][d] = floor_div(b[d], kBlock);
      local_[p][d] = static_cast<std::uint8_t>(b[d] - blocks[p][d] * kBlock);
    }
    keys[p] = key(blocks[p][0], blocks[p][1], blocks[p][2]);
    // Bit d set: the stencil reaches into the next block along axis d (local index 2 or 3).
    reach[p] = static_cast<std::uint8_t>((local_[p][0] >= kBlock - 2 ? 1 : 0) |
                                         (local_[p][1] >= kBlock - 2 ? 2 : 0) |
                                         (local_[p][2] >= kBlock - 2 ? 4 : 0));
    // (Each thread's `same` starts true: had_blocks guards the last build's arrays.)
    same = same && had_blocks && keys[p] == home_key_[p] && reach[p] == home_reach_[p];
  }
  if (bad < n) {
    const auto p = static_cast<std::size_t>(bad);
    if (!std::isfinite(x.x[p] + x.y[p] + x.z[p])) {
      throw std::runtime_error(fmt::format("particle {} has a non-finite position", bad));
    }
    throw std::runtime_error(fmt::format(
        "particle {} left the grid's range: at ({:.6g}, {:.6g}, {:.6g}) m, the grid reaches {:.6g} "
        "m from the origin along each axis (grid spacing {} m)",
        bad, x.x[p], x.y[p], x.z[p], kReach * dx_, dx_));
  }
  if (!same && had_blocks && regroup()) {
    zero_live_blocks();  // the last step's sums, in the blocks they were made in
    find_live_blocks();
  } else if (!same) {
    try {
      make_blocks();  // every node zero
    } catch (...) {
      // No half-made blocks for a later call to keep: the grid starts afresh.
      const long made = full_rebuilds_;
      *this = SparseGrid(dx_);
      full_rebuilds_ = made;
      throw;
    }
    find_live_blocks();
  } else {
    zero_live_blocks();  // the same blocks are live again
  }
}

// Particles that moved into another block that is a home slot are regrouped; the blocks stay.
// Every order the transfers and rules sum in is then the one a fresh build would give: homes
// along the curve (empty slots add nothing), particles by number within a home, live blocks in
// memory along the curve. False: a particle moved beyond the slots, so the blocks must be made
// again.
bool SparseGrid::regroup() {
  const std::size_t np = home_key_.size();
  for (std::size_t p = 0; p < np; ++p) {
    if (scratch_keys_[p] == home_key_[p] && scratch_reach_[p] == home_reach_[p]) continue;
    if (scratch_keys_[p] != home_key_[p]) {
      const auto it = block_index_.find(scratch_keys_[p]);
      if (it == block_index_.end()) return false;
      const int h = home_of_block_[static_cast<std::size_t>(it->second)];
      if (h < 0) return false;
      home_[p] = h;
    }
    home_key_[p] = scratch_keys_[p];
    home_reach_[p] = scratch_reach_[p];
  }
  group_particles();
  return true;
}

// Every particle's home block and the slots around the homes; returns how many slots (the
// first block ids).
std::size_t SparseGrid::make_home_slots() {
  const std::size_t np = scratch_keys_.size();
  const auto& keys = scratch_keys_;
  const auto& blocks = scratch_blocks_;
  home_.resize(np);
  // Home blocks, in order of first appearance: the first blocks made, so until the Morton
  // renumbering below a home's number is its block id. A particle in the same block as the one
  // before needs no lookup.
  std::uint64_t last_key = 0;
  int last_id = -1;
  for (std::size_t p = 0; p < np; ++p) {
    if (last_id < 0 || keys[p] != last_key) {
      last_id = block_id(blocks[p][0], blocks[p][1], blocks[p][2]);
      last_key = keys[p];
    }
    home_[p] = last_id;
  }
  // Home slots: every block within one block of a particle's home, so that a particle that
  // moves into a neighbouring block finds a home there and the blocks are kept (regroup()).
  const std::size_t particle_homes = block_coords_.size();
  for (std::size_t h = 0; h < particle_homes; ++h) {
    const auto b = block_coords_[h];
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        for (int k = -1; k <= 1; ++k) (void)block_id(b[0] + i, b[1] + j, b[2] + k);
      }
    }
  }
  // The +x, +y, +z neighbours of every slot (blocks made here get the next ids), so that any
  // stencil from any slot finds its nodes.
  const std::size_t nh = block_coords_.size();
  for (std::size_t h = 0; h < nh; ++h) {
    const auto b = block_coords_[h];
    for (int nb = 1; nb < 8; ++nb) {
      (void)block_id(b[0] + (nb & 1), b[1] + ((nb >> 1) & 1), b[2] + ((nb >> 2) & 1));
    }
  }
  return nh;
}

// The blocks renumbered along the Morton curve, and the homes numbered in that order.
void SparseGrid::order_blocks_along_curve(std::size_t nh) {
  const std::size_t np = scratch_keys_.size();
  // Every block laid out in memory along a Morton curve of their coordinates, and the slots
  // numbered in that order: homes near each other in space are near each other in the order of
  // the transfers (and share cached nodes), a thread given a stretch of the curve (cubes, homes,
  // the zeroing) works on a stretch of memory, and the reached blocks' order (the rules' sums)
  // depends on the set of blocks only.
  const std::size_t nb_all = block_coords_.size();
  std::vector<std::pair<std::uint64_t, int>> by_curve(nb_all);
  for (std::size_t b = 0; b < nb_all; ++b) {
    by_curve[b] = {morton_key(block_coords_[b]), static_cast<int>(b)};
  }
  std::sort(by_curve.begin(), by_curve.end());
  std::vector<int> place(nb_all);    // block id -> its place in memory
  std::vector<int> slot_number(nh);  // block id of a slot -> its home number
  std::vector<std::array<std::int64_t, 3>> coords(nb_all);
  home_of_block_.assign(nb_all, -1);
  int homes_numbered = 0;
  for (std::size_t k = 0; k < nb_all; ++k) {
    const auto b = static_cast<std::size_t>(by_curve[k].second);
    place[b] = static_cast<int>(k);
    coords[k] = block_coords_[b];
    if (b < nh) {  // a slot (the slots got the first ids)
      slot_number[b] = homes_numbered;
      home_of_block_[k] = homes_numbered++;
    }
  }
  block_coords_ = std::move(coords);
  for (auto& entry : block_index_) entry.second = place[static_cast<std::size_t>(entry.second)];
  for (std::size_t p = 0; p < np; ++p) home_[p] = slot_number[home_[p]];
}

// Each home's +x, +y, +z neighbours and the coloured cubes of homes; returns the cubes'
// coordinates, in the order of cubes_.
std::vector<std::array<std::int64_t, 3>> SparseGrid::make_cubes(std::size_t nh) {
  const std::size_t nb_all = block_coords_.size();
  // Each home's neighbours, and the cubes of 4 x 4 x 4 home blocks that the parallel scatter
  // runs whole, coloured by the parity of the cube's coordinates. A cube's stencils write into
  // the cube and one block beyond on the + sides, so only adjacent cubes (which differ in colour)
  // share nodes. Cubes of 4 blocks rather than single blocks: most nodes are then written within
  // one cube, while cached.
  neighbours_.resize(nh);
  cubes_.clear();
  std::vector<std::array<std::int64_t, 3>> cube_coords;
  for (std::size_t k = 0; k < nb_all; ++k) {
    const int h = home_of_block_[k];
    if (h < 0) continue;
    const auto b = block_coords_[k];
    for (int nb = 0; nb < 8; ++nb) {
      neighbours_[static_cast<std::size_t>(h)][nb] =
          block_id(b[0] + (nb & 1), b[1] + ((nb >> 1) & 1), b[2] + ((nb >> 2) & 1));
    }
    const std::array<std::int64_t, 3> cube = {b[0] >> kCubeShift, b[1] >> kCubeShift,
                                              b[2] >> kCubeShift};
    // The homes of one cube are consecutive on the Morton curve.
    if (cubes_.empty() || cube != cube_coords.back()) {
      const int colour =
          static_cast<int>((cube[0] & 1) | ((cube[1] & 1) << 1) | ((cube[2] & 1) << 2));
      cubes_.push_back({h, h, colour});
      cube_coords.push_back(cube);
    }
    cubes_.back().end_home = h + 1;
  }
  return cube_coords;
}

// For each cube, the adjacent cubes of a lower colour, which its scatter waits for.
void SparseGrid::make_cube_dependencies(
    const std::vector<std::array<std::int64_t, 3>>& cube_coords) {
  std::unordered_map<std::uint64_t, int> cube_index;
  for (std::size_t q = 0; q < cubes_.size(); ++q) {
    cube_index.emplace(key(cube_coords[q][0], cube_coords[q][1], cube_coords[q][2]),
                       static_cast<int>(q));
  }
  cube_dep_start_.assign(1, 0);
  cube_deps_.clear();
  for (std::size_t q = 0; q < cubes_.size(); ++q) {
    const auto& c = cube_coords[q];
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        for (int k = -1; k <= 1; ++k) {
          const auto it = cube_index.find(key(c[0] + i, c[1] + j, c[2] + k));
          if (it != cube_index.end() &&
              cubes_[static_cast<std::size_t>(it->second)].colour < cubes_[q].colour) {
            cube_deps_.push_back(it->second);
          }
        }
      }
    }
    cube_dep_start_.push_back(static_cast<int>(cube_deps_.size()));
  }
}

void SparseGrid::make_blocks() {
  block_index_.clear();
  block_coords_.clear();
  const std::size_t nh = make_home_slots();
  order_blocks_along_curve(nh);
  make_cube_dependencies(make_cubes(nh));
  home_key_ = scratch_keys_;
  home_reach_ = scratch_reach_;
  group_particles();
  const std::size_t nn = block_coords_.size() * kBlockNodes;
  nodes.assign(nn, Node{});
  tags.assign(nn, 0);
  block_tags.assign(block_coords_.size(), 0);
  ++full_rebuilds_;
}

// The blocks that this step's stencils reach: of every home with particles, the neighbours their
// stencils cross into. In memory order (the curve's), which depends on the particles only.
void SparseGrid::find_live_blocks() {
  auto& mark = live_mark_;
  mark.assign(block_coords_.size(), 0);
  const long nh = static_cast<long>(neighbours_.size());
#pragma omp parallel for schedule(static)
  for (long h = 0; h < nh; ++h) {
    const auto hs = static_cast<std::size_t>(h);
    std::uint8_t reaches = 0;
    for (int i = start_[hs]; i < start_[hs + 1]; ++i) reaches |= kSubsets[home_reach_[order_[i]]];
    for (int nb = 0; nb < 8; ++nb) {
      if ((reaches >> nb & 1) != 0) {
        // Homes of two threads may share a neighbour: the mark is an atomic store of the same 1.
        std::atomic_ref<std::uint8_t>(mark[static_cast<std::size_t>(neighbours_[hs][nb])])
            .store(1, std::memory_order_relaxed);
      }
    }
  }
  live_.clear();
  for (std::size_t b = 0; b < mark.size(); ++b) {
    if (mark[b] != 0) live_.push_back(static_cast<int>(b));
  }
}

// Particles grouped by home block (counting sort: by number within a home).
void SparseGrid::group_particles() {
  const std::size_t np = home_.size(), nh = neighbours_.size();
  start_.assign(nh + 1, 0);
  for (std::size_t p = 0; p < np; ++p) ++start_[home_[p] + 1];
  for (std::size_t h = 0; h < nh; ++h) start_[h + 1] += start_[h];
  order_.resize(np);
  fill_.assign(start_.begin(), start_.end() - 1);
  for (std::size_t p = 0; p < np; ++p) order_[fill_[home_[p]]++] = static_cast<int>(p);
}

std::size_t SparseGrid::thread_first_cube(int t, int threads) const {
  const std::size_t nq = cubes_.size();
  if (t <= 0) return 0;
  if (t >= threads) return nq;
  // The first cube whose first particle is at or beyond the thread's share.
  const std::size_t target =
      order_.size() * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
  std::size_t lo = 0, hi = nq;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (first_particle_of_cube(mid) < target) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo;
}

// Zeroes the live blocks of the last step; every other block is zero already. The live blocks
// lie mostly in runs along memory: each run is cleared with one memset, which the C library does
// with the widest stores the processor has (a Node of zero bytes is Node{}: +0.0 four times).
void SparseGrid::zero_live_blocks() {
  static_assert(std::is_trivially_copyable_v<Node>);
#pragma omp parallel
  {
    // Each thread the live blocks of its run of cubes (from its first cube's first block): the
    // blocks it wrote and read last.
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
    const auto first_block = [&](int thread) {
      if (thread == 0) return 0L;
      const std::size_t q = thread_first_cube(thread, threads);
      const int b = q < cubes_.size()
                        ? neighbours_[static_cast<std::size_t>(cubes_[q].first_home)][0]
                        : static_cast<int>(block_coords_.size());
      return static_cast<long>(std::lower_bound(live_.begin(), live_.end(), b) - live_.begin());
    };
    const long first = first_block(t), end = first_block(t + 1);
    for (long k = first; k < end;) {
      const auto b = static_cast<std::size_t>(live_[static_cast<std::size_t>(k)]);
      std::size_t run = 1;
      while (k + static_cast<long>(run) < end &&
             live_[static_cast<std::size_t>(k) + run] == static_cast<int>(b + run)) {
        ++run;
      }
      std::memset(static_cast<void*>(nodes.data() + b * kBlockNodes), 0,
                  run * kBlockNodes * sizeof(Node));
      std::memset(tags.data() + b * kBlockNodes, 0, run * kBlockNodes);
      std::memset(block_tags.data() + b, 0, run);
      k += static_cast<long>(run);
    }
  }
}

}  // namespace snapjump::mpm
