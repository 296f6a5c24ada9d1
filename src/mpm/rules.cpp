#include "mpm/rules.hpp"

#include <algorithm>
#include <cmath>

namespace snapjump::mpm {

// Both rules visit the live blocks in parallel, each block's sum apart, and add the blocks' sums
// in the blocks' order: the same bits at any thread count.

void ClampRule::apply(SparseGrid& grid, const StepContext& ctx) {
  const auto live = grid.live_blocks();
  const long nl = static_cast<long>(live.size());
  block_impulse_.assign(live.size(), 0.0);
#pragma omp parallel for schedule(static)
  for (long k = 0; k < nl; ++k) {
    const auto b = static_cast<std::size_t>(live[static_cast<std::size_t>(k)]);
    if ((grid.block_tags[b] & tag_) == 0) continue;
    double impulse_z = 0.0;
    for (std::size_t a = b * kBlockNodes; a < (b + 1) * kBlockNodes; ++a) {
      auto& g = grid.nodes[a];
      if ((grid.tags[a] & tag_) == 0 || g.m <= 0.0) continue;
      const double target = g.m * body_.vz;
      impulse_z += target - g.pz;
      g.px = 0.0;
      g.py = 0.0;
      g.pz = target;
    }
    block_impulse_[static_cast<std::size_t>(k)] = impulse_z;
  }
  double impulse_z = 0.0;
  for (const double i : block_impulse_) impulse_z += i;
  // The body pushed the shell by impulse_z; the shell pushes the body back.
  body_.clamp_force = -impulse_z / ctx.dt;
}

bool ContainerFaceRule::block_may_cross(const SparseGrid& grid, std::size_t b, double dz) const {
  // gap and along grow with r, and with z (gap) or -z (along): their largest values over the
  // block's box bound those at its nodes.
  const double dx = grid.dx();
  const auto& c = grid.block_coords(b);
  const auto far = [&](std::int64_t lo) {
    const double a = dx * static_cast<double>(lo * kBlock);
    return std::max(std::abs(a), std::abs(a + dx * (kBlock - 1)));
  };
  const double r_max = std::hypot(far(c[0]), far(c[1]));
  const double z_lo = dx * static_cast<double>(c[2] * kBlock), z_hi = z_lo + dx * (kBlock - 1);
  return face_.gap(r_max, z_hi, dz) > 0.0 && face_.along(r_max, z_lo, dz) >= face_.s_min;
}

void ContainerFaceRule::apply(SparseGrid& grid, const StepContext& ctx) {
  const auto live = grid.live_blocks();
  const long nl = static_cast<long>(live.size());
  block_impulse_.assign(live.size(), 0.0);
  block_contacts_.assign(live.size(), 0);
  const double dx = grid.dx(), dz = dz_, vb = body_.vz;
  const double nr = face_.nr(), nz = face_.nz();
#pragma omp parallel for schedule(static)
  for (long k = 0; k < nl; ++k) {
    const auto b = static_cast<std::size_t>(live[static_cast<std::size_t>(k)]);
    if (!block_may_cross(grid, b, dz)) continue;
    double impulse_z = 0.0;
    long contacts = 0;
    for (std::size_t a = b * kBlockNodes; a < (b + 1) * kBlockNodes; ++a) {
      if ((grid.tags[a] & kTagClamped) != 0) continue;  // the clamp drives it (one byte read)
      auto& g = grid.nodes[a];
      if (g.m <= 0.0) continue;
      const auto c = grid.coords(a);
      const double x = dx * static_cast<double>(c[0]), y = dx * static_cast<double>(c[1]);
      const double z = dx * static_cast<double>(c[2]);
      const double r = std::hypot(x, y);
      if (!(r > 0.0) || !face_.inside(r, z, dz)) continue;
      const double ex = nr * x / r, ey = nr * y / r;
      // Momentum into the container relative to the body (the body moves along z only).
      const double pn = g.px * ex + g.py * ey + (g.pz - g.m * vb) * nz;
      if (!(pn > 0.0)) continue;
      g.px -= pn * ex;
      g.py -= pn * ey;
      g.pz -= pn * nz;
      impulse_z -= pn * nz;
      ++contacts;
    }
    block_impulse_[static_cast<std::size_t>(k)] = impulse_z;
    block_contacts_[static_cast<std::size_t>(k)] = contacts;
  }
  double impulse_z = 0.0;
  long contacts = 0;
  for (std::size_t k = 0; k < live.size(); ++k) {
    impulse_z += block_impulse_[k];
    contacts += block_contacts_[k];
  }
  contacts_ = contacts;
  force_z_ = impulse_z / ctx.dt;
  body_.clamp_force -= force_z_;  // the shell pushes the body back
}

void PlateRule::apply(SparseGrid& grid, const StepContext& ctx) {
  const auto live = grid.live_blocks();
  const long nl = static_cast<long>(live.size());
  block_sums_.assign(2 * live.size(), 0.0);
  loaded_.clear();
#pragma omp parallel
  {
    std::vector<std::array<std::int64_t, 3>> loaded;  // this thread's
#pragma omp for schedule(static) nowait
    for (long k = 0; k < nl; ++k) {
      const auto b = static_cast<std::size_t>(live[static_cast<std::size_t>(k)]);
      // Only blocks that hold a node layer z = 0, -dx, ..., -(layers - 1) dx.
      const std::int64_t k0 = grid.block_coords(b)[2] * kBlock;
      if (k0 > 0 || k0 + kBlock - 1 <= -layers_) continue;
      // The block's nodes on those layers: local z from lz0 to lz1.
      const int lz0 = static_cast<int>(std::max<std::int64_t>(0, 1 - layers_ - k0));
      const int lz1 = static_cast<int>(std::min<std::int64_t>(kBlock - 1, -k0));
      double normal = 0.0, tangential = 0.0;
      for (int l = 0; l < kBlockNodes; ++l) {  // in memory order
        const int lz = l % kBlock;
        if (lz < lz0 || lz > lz1) continue;
        const std::size_t a = b * kBlockNodes + static_cast<std::size_t>(l);
        auto& g = grid.nodes[a];
        if (g.m <= 0.0 || g.pz >= 0.0) continue;
        // The normal impulse given by the plate (upward): p~ = p - (p . e_z) e_z (paper, Eq. S16).
        const double dpn = -g.pz;
        g.pz = 0.0;
        loaded.push_back(grid.coords(a));
        normal += dpn;
        const double pt = std::hypot(g.px, g.py);
        if (pt > 0.0 && mu_ > 0.0) {
          const double reduced = std::max(0.0, pt - mu_ * dpn);
          tangential += pt - reduced;
          g.px *= reduced / pt;
          g.py *= reduced / pt;
        }
      }
      block_sums_[2 * static_cast<std::size_t>(k)] = normal;
      block_sums_[2 * static_cast<std::size_t>(k) + 1] = tangential;
    }
#pragma omp critical(snapjump_plate_loaded)
    loaded_.insert(loaded_.end(), loaded.begin(), loaded.end());
  }
  loaded_sorted_ = false;  // (the threads' lists joined in any order: loaded_nodes() sorts)
  double normal = 0.0, tangential = 0.0;
  for (std::size_t k = 0; k < live.size(); ++k) {
    normal += block_sums_[2 * k];
    tangential += block_sums_[2 * k + 1];
  }
  force_ = normal / ctx.dt;
  friction_ = tangential / ctx.dt;
}

const std::vector<std::array<std::int64_t, 3>>& PlateRule::loaded_nodes() const {
  if (!loaded_sorted_) {
    std::sort(loaded_.begin(), loaded_.end());
    loaded_sorted_ = true;
  }
  return loaded_;
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
