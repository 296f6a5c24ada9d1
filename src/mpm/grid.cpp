#include "mpm/grid.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace snapjump::mpm {
namespace {

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

constexpr std::int64_t kOffset = std::int64_t{1} << 20;  // 21 bits per axis

std::uint64_t key(std::int64_t bx, std::int64_t by, std::int64_t bz) {
  return (static_cast<std::uint64_t>(bx + kOffset) << 42) |
         (static_cast<std::uint64_t>(by + kOffset) << 21) |
         static_cast<std::uint64_t>(bz + kOffset);
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

void SparseGrid::rebuild(const mesh::Points& x) {
  const std::size_t np = x.size();
  const double inv_dx = 1.0 / dx_;
  auto& keys = scratch_keys_;
  auto& blocks = scratch_blocks_;
  keys.resize(np);
  blocks.resize(np);
  local_.resize(np);
  bool same = home_key_.size() == np && !block_coords_.empty();
  for (std::size_t p = 0; p < np; ++p) {
    const double gx = x.x[p] * inv_dx, gy = x.y[p] * inv_dx, gz = x.z[p] * inv_dx;
    if (!std::isfinite(gx + gy + gz)) {
      throw std::runtime_error(fmt::format("particle {} has a non-finite position", p));
    }
    const std::int64_t b[3] = {static_cast<std::int64_t>(std::floor(gx - 0.5)),
                               static_cast<std::int64_t>(std::floor(gy - 0.5)),
                               static_cast<std::int64_t>(std::floor(gz - 0.5))};
    for (int d = 0; d < 3; ++d) {
      blocks[p][d] = floor_div(b[d], kBlock);
      local_[p][d] = static_cast<std::uint8_t>(b[d] - blocks[p][d] * kBlock);
    }
    keys[p] = key(blocks[p][0], blocks[p][1], blocks[p][2]);
    same = same && keys[p] == home_key_[p];
  }
  if (!same) {
    block_index_.clear();
    block_coords_.clear();
    home_.resize(np);
    // Home blocks first, in order of first appearance.
    std::vector<int> home_block;  // home index -> block id
    std::unordered_map<int, int> home_of_block;
    for (std::size_t p = 0; p < np; ++p) {
      const int id = block_id(blocks[p][0], blocks[p][1], blocks[p][2]);
      const auto [it, inserted] =
          home_of_block.try_emplace(id, static_cast<int>(home_block.size()));
      if (inserted) home_block.push_back(id);
      home_[p] = it->second;
    }
    // The +x, +y, +z neighbours that stencils may reach.
    const std::size_t nh = home_block.size();
    neighbours_.resize(nh);
    for (auto& c : colour_homes_) c.clear();
    for (std::size_t h = 0; h < nh; ++h) {
      const auto b = block_coords_[home_block[h]];
      for (int nb = 0; nb < 8; ++nb) {
        neighbours_[h][nb] =
            block_id(b[0] + (nb & 1), b[1] + ((nb >> 1) & 1), b[2] + ((nb >> 2) & 1));
      }
      const int colour = static_cast<int>((b[0] & 1) | ((b[1] & 1) << 1) | ((b[2] & 1) << 2));
      colour_homes_[colour].push_back(static_cast<int>(h));
    }
    // Particles grouped by home block (counting sort).
    start_.assign(nh + 1, 0);
    for (std::size_t p = 0; p < np; ++p) ++start_[home_[p] + 1];
    for (std::size_t h = 0; h < nh; ++h) start_[h + 1] += start_[h];
    order_.resize(np);
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (std::size_t p = 0; p < np; ++p) order_[fill[home_[p]]++] = static_cast<int>(p);
    home_key_ = keys;
  }

  const std::size_t nn = block_coords_.size() * kBlockNodes;
  nodes.resize(nn);
  tags.resize(nn);
  block_tags.assign(block_coords_.size(), 0);
  Node* node = nodes.data();
  std::uint8_t* tag = tags.data();
  const long n = static_cast<long>(nn);
#pragma omp parallel for schedule(static)
  for (long a = 0; a < n; ++a) {
    node[a] = Node{};
    tag[a] = 0;
  }
}

}  // namespace snapjump::mpm
