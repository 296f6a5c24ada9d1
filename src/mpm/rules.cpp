#include "mpm/rules.hpp"

#include <algorithm>
#include <cmath>

namespace snapjump::mpm {

void ClampRule::apply(SparseGrid& grid, const StepContext& ctx) {
  double impulse_z = 0.0;
  for (const int live : grid.live_blocks()) {
    const auto b = static_cast<std::size_t>(live);
    if ((grid.block_tags[b] & tag_) == 0) continue;
    for (std::size_t a = b * kBlockNodes; a < (b + 1) * kBlockNodes; ++a) {
      if ((grid.tags[a] & tag_) == 0 || grid.nodes[a].m <= 0.0) continue;
      const double target = grid.nodes[a].m * body_.vz;
      impulse_z += target - grid.nodes[a].pz;
      grid.nodes[a].px = 0.0;
      grid.nodes[a].py = 0.0;
      grid.nodes[a].pz = target;
    }
  }
  // The body pushed the shell by impulse_z; the shell pushes the body back.
  body_.clamp_force = -impulse_z / ctx.dt;
}

void PlateRule::apply(SparseGrid& grid, const StepContext& ctx) {
  double normal = 0.0, tangential = 0.0;
  loaded_.clear();
  for (const int live : grid.live_blocks()) {
    const auto b = static_cast<std::size_t>(live);
    // Only blocks that hold a node layer z = 0, -dx, ..., -(layers - 1) dx.
    const std::int64_t k0 = grid.block_coords(b)[2] * kBlock;
    if (k0 > 0 || k0 + kBlock - 1 <= -layers_) continue;
    for (std::size_t a = b * kBlockNodes; a < (b + 1) * kBlockNodes; ++a) {
      if (grid.nodes[a].m <= 0.0 || grid.nodes[a].pz >= 0.0) continue;
      const auto c = grid.coords(a);
      if (c[2] > 0 || c[2] <= -layers_) continue;
      const double dpn = -grid.nodes[a].pz;  // normal impulse given by the plate (upward)
      grid.nodes[a].pz = 0.0;
      loaded_.push_back(c);
      normal += dpn;
      const double pt = std::hypot(grid.nodes[a].px, grid.nodes[a].py);
      if (pt > 0.0 && mu_ > 0.0) {
        const double reduced = std::max(0.0, pt - mu_ * dpn);
        tangential += pt - reduced;
        grid.nodes[a].px *= reduced / pt;
        grid.nodes[a].py *= reduced / pt;
      }
    }
  }
  force_ = normal / ctx.dt;
  friction_ = tangential / ctx.dt;
  std::sort(loaded_.begin(), loaded_.end());
}

bool plate_carries(const PlateRule& plate, double dx, double x, double y, double z) {
  constexpr double kCarriedShare = 0.5;
  return z < 1.5 * dx && plate_share(plate.loaded_nodes(), dx, x, y, z) >= kCarriedShare;
}

double plate_share(const std::vector<std::array<std::int64_t, 3>>& loaded, double dx, double x,
                   double y, double z) {
  const auto wx = bspline_weights(x / dx), wy = bspline_weights(y / dx),
             wz = bspline_weights(z / dx);
  double share = 0.0;
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        const std::array<std::int64_t, 3> c{wx.base + i, wy.base + j, wz.base + k};
        if (std::binary_search(loaded.begin(), loaded.end(), c)) {
          share += wx.w[i] * wy.w[j] * wz.w[k];
        }
      }
    }
  }
  return share;
}

}  // namespace snapjump::mpm
