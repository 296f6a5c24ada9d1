#include "mesh/mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/morton.hpp"
#include "mesh/tet10.hpp"

namespace snapjump::mesh {
namespace {

// det of dX/d(r,s,t) for element e at reference point (r, s, t).
double jacobian_det(const Mesh& m, const std::array<int, 10>& tet, double r, double s, double t) {
  const auto G = tet10_shape_gradients(r, s, t);
  double J[3][3] = {};
  for (int a = 0; a < 10; ++a) {
    const double X[3] = {m.nodes.x[tet[a]], m.nodes.y[tet[a]], m.nodes.z[tet[a]]};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) J[i][j] += X[i] * G[a][j];
    }
  }
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

std::string where(const Mesh& m, int e) {
  const int a = m.tets[e][0];
  return fmt::format("element {} (first corner node {} at ({:.4g}, {:.4g}, {:.4g}) m)", e, a,
                     m.nodes.x[a], m.nodes.y[a], m.nodes.z[a]);
}

}  // namespace

void check_mesh(const Mesh& m) {
  const int n = static_cast<int>(m.nodes.size());
  if (m.nodes.y.size() != m.nodes.x.size() || m.nodes.z.size() != m.nodes.x.size()) {
    throw MeshError("mesh node arrays differ in length");
  }
  if (m.tets.empty()) throw MeshError("mesh has no 10-node tetrahedra");
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    for (int a : m.tets[e]) {
      if (a < 0 || a >= n)
        throw MeshError(fmt::format("element {} refers to node {} of {}", e, a, n));
    }
  }
  // Reference points where the Jacobian must be positive: the ten nodes and the quadrature points.
  constexpr double nodes_rst[10][3] = {{0, 0, 0},   {1, 0, 0},   {0, 1, 0},  {0, 0, 1},
                                       {.5, 0, 0},  {.5, .5, 0}, {0, .5, 0}, {0, 0, .5},
                                       {0, .5, .5}, {.5, 0, .5}};
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const auto& tet = m.tets[e];
    // Scale: longest corner edge, for a relative degeneracy test.
    double longest = 0.0;
    for (const auto& ed : kTetEdges) {
      const int a = tet[ed[0]], b = tet[ed[1]];
      longest =
          std::max(longest, std::hypot(m.nodes.x[a] - m.nodes.x[b], m.nodes.y[a] - m.nodes.y[b],
                                       m.nodes.z[a] - m.nodes.z[b]));
    }
    const double tiny = 1e-10 * longest * longest * longest;
    const double center = jacobian_det(m, tet, 0.25, 0.25, 0.25);
    if (std::abs(center) <= tiny) {
      throw MeshError(fmt::format("{} is degenerate (zero volume)", where(m, static_cast<int>(e))));
    }
    if (center < 0) {
      throw MeshError(fmt::format("{} is inverted (negative volume: corner order reversed)",
                                  where(m, static_cast<int>(e))));
    }
    for (const auto& p : nodes_rst) {
      if (jacobian_det(m, tet, p[0], p[1], p[2]) <= tiny) {
        throw MeshError(
            fmt::format("{} is distorted: its Jacobian is not positive at reference "
                        "point ({}, {}, {}) (misplaced edge node?)",
                        where(m, static_cast<int>(e)), p[0], p[1], p[2]));
      }
    }
    for (const auto& q : tet_rule_degree2()) {
      if (jacobian_det(m, tet, q.r, q.s, q.t) <= tiny) {
        throw MeshError(
            fmt::format("{} is distorted: its Jacobian is not positive at a quadrature "
                        "point",
                        where(m, static_cast<int>(e))));
      }
    }
  }
  for (const auto* set : {&m.clamped, &m.outer}) {
    for (int a : *set) {
      if (a < 0 || a >= n) throw MeshError(fmt::format("node set refers to node {} of {}", a, n));
    }
  }
  for (const auto& f : m.inner_faces) {
    for (int a : f) {
      if (a < 0 || a >= n) throw MeshError(fmt::format("inner face refers to node {} of {}", a, n));
    }
  }
  if (m.apex >= n) throw MeshError(fmt::format("apex node {} of {}", m.apex, n));
}

void check_shell_sets(const Mesh& m) {
  if (m.clamped.empty()) throw MeshError("mesh has no clamped nodes");
  if (m.outer.empty()) throw MeshError("mesh has no outer-surface nodes");
  if (m.inner_faces.empty()) throw MeshError("mesh has no inner (pressurised) faces");
  if (m.apex < 0) throw MeshError("mesh has no apex node");
}

void translate_z(Mesh& m, double dz) {
  for (auto& z : m.nodes.z) z += dz;
}

namespace {

// Orders the items (each a list of node numbers) by their lowest node; ties keep their order.
template <typename Item>
void sort_by_lowest_node(std::vector<Item>& items) {
  std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return *std::min_element(a.begin(), a.end()) < *std::min_element(b.begin(), b.end());
  });
}

}  // namespace

void sort_along_curve(Mesh& m) {
  const std::size_t n = m.nodes.size();
  if (n == 0) return;
  const auto [x0, x1] = std::minmax_element(m.nodes.x.begin(), m.nodes.x.end());
  const auto [y0, y1] = std::minmax_element(m.nodes.y.begin(), m.nodes.y.end());
  const auto [z0, z1] = std::minmax_element(m.nodes.z.begin(), m.nodes.z.end());
  // One cell size on all three axes (the curve's cells are cubes), 2^20 cells across the widest.
  constexpr double kCells = 1048575.0;
  const double extent = std::max({*x1 - *x0, *y1 - *y0, *z1 - *z0});
  const double scale = extent > 0.0 ? kCells / extent : 0.0;
  const auto cell = [scale](double v, double lo) {
    return static_cast<std::uint64_t>(std::floor((v - lo) * scale));
  };
  std::vector<std::pair<std::uint64_t, int>> by_curve(n);
  for (std::size_t a = 0; a < n; ++a) {
    by_curve[a] = {
        core::morton_key(cell(m.nodes.x[a], *x0), cell(m.nodes.y[a], *y0), cell(m.nodes.z[a], *z0)),
        static_cast<int>(a)};
  }
  std::sort(by_curve.begin(), by_curve.end());  // (key, old number): ties in their old order
  std::vector<int> renumber(n);
  Points nodes;
  for (std::size_t i = 0; i < n; ++i) {
    const auto a = static_cast<std::size_t>(by_curve[i].second);
    renumber[a] = static_cast<int>(i);
    nodes.push_back(m.nodes.x[a], m.nodes.y[a], m.nodes.z[a]);
  }
  m.nodes = std::move(nodes);
  for (auto& tet : m.tets) {
    for (int& a : tet) a = renumber[static_cast<std::size_t>(a)];
  }
  for (auto& face : m.inner_faces) {
    for (int& a : face) a = renumber[static_cast<std::size_t>(a)];
  }
  for (auto* set : {&m.clamped, &m.outer}) {
    for (int& a : *set) a = renumber[static_cast<std::size_t>(a)];
    std::sort(set->begin(), set->end());
  }
  if (m.apex >= 0) m.apex = renumber[static_cast<std::size_t>(m.apex)];
  sort_by_lowest_node(m.tets);
  sort_by_lowest_node(m.inner_faces);
}

std::vector<std::array<int, 6>> boundary_faces(const Mesh& m) {
  // Local faces of a positively oriented tetrahedron, outward, as (corners, edge nodes) in the
  // 6-node triangle order: corners c0 c1 c2, then edges (c0,c1), (c1,c2), (c0,c2).
  constexpr int faces[4][6] = {
      {0, 2, 1, 6, 5, 4}, {0, 1, 3, 4, 9, 7}, {0, 3, 2, 7, 8, 6}, {1, 2, 3, 5, 8, 9}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 6>>> seen;
  for (const auto& tet : m.tets) {
    for (const auto& f : faces) {
      std::array<int, 6> tri{};
      for (int k = 0; k < 6; ++k) tri[k] = tet[f[k]];
      std::array<int, 3> key{tri[0], tri[1], tri[2]};
      std::sort(key.begin(), key.end());
      auto& entry = seen[key];
      ++entry.first;
      entry.second = tri;
    }
  }
  std::vector<std::array<int, 6>> out;
  for (const auto& [key, entry] : seen) {
    if (entry.first == 1) out.push_back(entry.second);
  }
  return out;
}

}  // namespace snapjump::mesh
