#include "mpm/reference_transfer.hpp"

#include <cmath>

namespace snapjump::mpm::reference {

double quadratic_bspline(double r) {
  r = std::abs(r);
  if (r < 0.5) return 0.75 - r * r;
  if (r < 1.5) return 0.5 * (1.5 - r) * (1.5 - r);
  return 0.0;
}

namespace {

// Calls visit(key, N, d) for the 27 nodes of particle i's stencil: the node's coordinates, the
// product of the three B-splines and the offset d = x_node - x_i.
template <typename Visit>
void for_each_stencil_node(const Particles& p, std::size_t i, double dx, const Visit& visit) {
  const double x[3] = {p.x.x[i], p.x.y[i], p.x.z[i]};
  std::int64_t first[3];
  for (int k = 0; k < 3; ++k) first[k] = static_cast<std::int64_t>(std::floor(x[k] / dx - 0.5));
  for (std::int64_t a = first[0]; a < first[0] + 3; ++a) {
    for (std::int64_t b = first[1]; b < first[1] + 3; ++b) {
      for (std::int64_t c = first[2]; c < first[2] + 3; ++c) {
        const NodeKey key{a, b, c};
        double N = 1.0;
        double d[3];
        for (int k = 0; k < 3; ++k) {
          const double node = static_cast<double>(key[k]) * dx;
          N *= quadratic_bspline((x[k] - node) / dx);
          d[k] = node - x[k];
        }
        visit(key, N, d);
      }
    }
  }
}

}  // namespace

GridSums particle_to_grid(const Particles& p, double dx) {
  GridSums grid;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double v[3] = {p.v.x[i], p.v.y[i], p.v.z[i]};
    const double* C = &p.C[9 * i];
    for_each_stencil_node(p, i, dx, [&](const NodeKey& key, double N, const double* d) {
      double u[3];  // v_i + C_i d (paper, Eq. S14)
      for (int r = 0; r < 3; ++r) {
        u[r] = v[r] + C[3 * r] * d[0] + C[3 * r + 1] * d[1] + C[3 * r + 2] * d[2];
      }
      const double mN = p.mass[i] * N;
      auto& node = grid[key];
      node.m += mN;  // (paper, Eq. S15)
      node.px += mN * u[0];
      node.py += mN * u[1];
      node.pz += mN * u[2];
    });
  }
  return grid;
}

std::vector<ParticleUpdate> grid_to_particle(const Particles& p, const GridSums& grid, double dx,
                                             double dt) {
  std::vector<ParticleUpdate> out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    auto& q = out[i];
    for_each_stencil_node(p, i, dx, [&](const NodeKey& key, double N, const double* d) {
      const auto& node = grid.at(key);
      if (node.m <= 0.0) return;
      const double u[3] = {node.px / node.m, node.py / node.m, node.pz / node.m};
      for (int r = 0; r < 3; ++r) {
        q.v[r] += N * u[r];  // (paper, Eq. S17)
        // (paper, Eq. S18)
        for (int c = 0; c < 3; ++c) q.C[3 * r + c] += 4.0 / (dx * dx) * N * u[r] * d[c];
      }
    });
    q.x = {p.x.x[i] + dt * q.v[0], p.x.y[i] + dt * q.v[1], p.x.z[i] + dt * q.v[2]};
  }
  return out;
}

}  // namespace snapjump::mpm::reference
