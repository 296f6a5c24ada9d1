#include "axi/body.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>

#include "axi/quadratic.hpp"
#include "fem/fold_check.hpp"

namespace snapjump::axi {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// F at one quadrature point of an element with node coordinates xr, xz: the meridian block and
// the hoop stretch rho / rho_0, from the point's N, dN/dR, dN/dZ (nine each) and rho_0.
struct PointDeformation {
  double F11, F12, F21, F22, F33;
};
PointDeformation deformation_at(const double* N, const double* dR, const double* dZ, double rho0,
                                const double* xr, const double* xz) {
  double F11 = 0, F12 = 0, F21 = 0, F22 = 0, rho = 0;
  for (int m = 0; m < 9; ++m) {
    F11 += xr[m] * dR[m];
    F12 += xr[m] * dZ[m];
    F21 += xz[m] * dR[m];
    F22 += xz[m] * dZ[m];
    rho += xr[m] * N[m];
  }
  return {F11, F12, F21, F22, rho / rho0};
}

}  // namespace

std::vector<double> corner_angles(const MeshSpec& spec) {
  const int n = spec.along;
  std::vector<double> theta(n + 1);
  if (spec.rim_grading == 1.0) {
    for (int e = 0; e <= n; ++e) theta[e] = spec.phi * e / n;
    return theta;
  }
  const double q = n > 1 ? std::pow(1.0 / spec.rim_grading, 1.0 / (n - 1)) : 1.0;
  double sum = 0.0, size = 1.0;
  for (int e = 0; e < n; ++e, size *= q) {
    theta[e] = sum;
    sum += size;
  }
  for (int e = 0; e < n; ++e) theta[e] *= spec.phi / sum;
  theta[n] = spec.phi;
  return theta;
}

int elements_along(double R, double h, double phi, int through) {
  return std::max(2, static_cast<int>(std::ceil(R * phi / (2.0 * h / through))));
}

Body::Body(const MeshSpec& spec, const fem::Material& material) : spec_(spec), material_(material) {
  if (!(spec.R > 0.0 && spec.h > 0.0 && spec.h < spec.R && spec.phi > 0.0 &&
        spec.phi < std::numbers::pi && spec.through >= 1 && spec.along >= 1 &&
        spec.rim_grading >= 1.0 && spec.rim_grading <= 100.0 && spec.crease_fan_from_rim >= 0.0 &&
        std::isfinite(spec.crease_fan_from_rim) && spec.crease_fan_band >= 0.0 &&
        std::isfinite(spec.crease_fan_band) &&
        std::all_of(spec.crease_seeds_from_rim.begin(), spec.crease_seeds_from_rim.end(),
                    [](double s) { return s > 0.0 && std::isfinite(s); }))) {
    throw std::invalid_argument(
        fmt::format("unusable axisymmetric mesh: R = {} m, h = {} m, phi = {} rad, {} x {} "
                    "elements, rim grading {} (1 to 100), crease fan {} m (band {} m), seeded "
                    "creases {} m (none of them negative, the seeds positive)",
                    spec.R, spec.h, spec.phi, spec.along, spec.through, spec.rim_grading,
                    spec.crease_fan_from_rim, spec.crease_fan_band,
                    fmt::join(spec.crease_seeds_from_rim, ", ")));
  }
  // Node lattice (i, j): i = 0..2 along along the meridian (polar angle), j = 0..2 through
  // through the thickness (inner to outer).
  const int ni = 2 * spec.along + 1, nj = 2 * spec.through + 1;
  const auto id = [nj](int i, int j) { return i * nj + j; };
  const auto corners = corner_angles(spec);
  std::vector<double> theta(ni);
  for (int i = 0; i < ni; ++i) {
    // Uniform: the lattice's own spacing (bit for bit the mesh without grading).
    theta[i] = spec.rim_grading == 1.0 ? spec.phi * i / (ni - 1)
               : i % 2 == 0            ? corners[i / 2]
                                       : 0.5 * (corners[i / 2] + corners[i / 2 + 1]);
    for (int j = 0; j < nj; ++j) {
      const double s = spec.R - 0.5 * spec.h + spec.h * j / (nj - 1);
      nodes_.r.push_back(i == 0 ? 0.0 : s * std::sin(theta[i]));
      nodes_.z.push_back(-s * std::cos(theta[i]));
    }
  }
  for (int j = 0; j < nj; ++j) {
    axis_.push_back(id(0, j));
    rim_.push_back(id(ni - 1, j));
  }
  for (int i = 0; i < ni; ++i) {
    outer_.push_back(id(i, nj - 1));
    inner_.push_back(id(i, 0));
  }
  // Element node order: local (a, b) with a along the meridian, b through h, node a * 3 + b.
  for (int e = 0; e < spec.along; ++e) {
    for (int k = 0; k < spec.through; ++k) {
      std::array<int, 9> el{};
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) el[3 * a + b] = id(2 * e + a, 2 * k + b);
      }
      elements_.push_back(el);
    }
  }
  if (spec.fan_layer < 0 || spec.fan_layer > std::min(2, spec.through)) {
    throw std::invalid_argument(
        fmt::format("a fan layer replaces 1 or 2 of the {} layers of elements through h, not {}",
                    spec.through, spec.fan_layer));
  }
  if (spec.fan_layer > 0 && spec.crease_fan_from_rim > 0.0) {
    throw std::invalid_argument(
        "a fan layer makes every inner corner node a crease's root: give no crease fan with it");
  }
  if (spec.crease_fan_from_rim > 0.0) add_crease_fans(theta);
  if (spec.fan_layer > 0) add_fan_layer(theta);
  if (!spec.crease_seeds_from_rim.empty()) add_crease_seeds(theta);

  // Quadrature data, and the consistent mass's diagonal for the lumping.
  mass_.assign(nodes_.size(), 0.0);
  const auto build = [&](Rule& rule, int n, bool masses) {
    const auto g = gauss(n);
    rule.points = n * n;
    for (std::size_t e = 0; e < elements_.size(); ++e) {
      const auto& el = elements_[e];
      std::array<double, 9> diag{};
      double element_mass = 0.0;
      for (int p = 0; p < n; ++p) {
        for (int q = 0; q < n; ++q) {
          const auto La = lagrange(g.x[p]), Lb = lagrange(g.x[q]);
          const auto dLa = lagrange_d(g.x[p]), dLb = lagrange_d(g.x[q]);
          std::array<double, 9> N{}, Ns{}, Nt{};
          for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
              N[3 * a + b] = La[a] * Lb[b];
              Ns[3 * a + b] = dLa[a] * Lb[b];
              Nt[3 * a + b] = La[a] * dLb[b];
            }
          }
          double J11 = 0, J12 = 0, J21 = 0, J22 = 0, rho0 = 0;  // d(R, Z) / d(s, t)
          for (int m = 0; m < 9; ++m) {
            const double R = nodes_.r[el[m]], Z = nodes_.z[el[m]];
            J11 += R * Ns[m];
            J12 += R * Nt[m];
            J21 += Z * Ns[m];
            J22 += Z * Nt[m];
            rho0 += R * N[m];
          }
          const double det = J11 * J22 - J12 * J21;
          if (!(std::abs(det) > 0.0) || !(rho0 > 0.0)) {
            throw std::invalid_argument(
                fmt::format("axisymmetric element {} is degenerate at a quadrature point", e));
          }
          const double w = g.w[p] * g.w[q] * std::abs(det) * kTwoPi * rho0;
          for (int m = 0; m < 9; ++m) {
            // dN/dR, dN/dZ from the inverse Jacobian.
            rule.N.push_back(N[m]);
            rule.dR.push_back((J22 * Ns[m] - J21 * Nt[m]) / det);
            rule.dZ.push_back((-J12 * Ns[m] + J11 * Nt[m]) / det);
          }
          rule.rho0.push_back(rho0);
          rule.weight.push_back(w);
          if (masses) {
            element_mass += material_.rho * w;
            for (int m = 0; m < 9; ++m) diag[m] += material_.rho * w * N[m] * N[m];
          }
        }
      }
      if (masses) {
        double sum = 0.0;
        for (double d : diag) sum += d;
        for (int m = 0; m < 9; ++m) mass_[el[m]] += element_mass * diag[m] / sum;
        volume_ += element_mass / material_.rho;
      }
    }
  };
  build(full_, 3, true);
  build(reduced_, spec.reduced_bulk ? 2 : 3, false);
  for (double m : mass_) total_mass_ += m;
}

double Body::corner_from_rim(int e, const std::vector<double>& theta) const {
  return inner_arc_from_rim(spec_, theta[static_cast<std::size_t>(2 * e)]);
}

int Body::nearest_inner_corner(double from_rim, int first, int last,
                               const std::vector<double>& theta) const {
  int nearest = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int e = first; e <= last; ++e) {
    const double d = std::abs(corner_from_rim(e, theta) - from_rim);
    if (d < best) best = d, nearest = e;
  }
  return nearest;
}

// The root nearest MeshSpec::crease_fan_from_rim and, with a band, every second corner node
// within it get a fan each; the lattice's nodes the blocks no longer hold are dropped.
void Body::add_crease_fans(const std::vector<double>& theta) {
  // The element index along whose first corner is the root.
  const int root = nearest_inner_corner(spec_.crease_fan_from_rim, 1, spec_.along - 1, theta);
  if (spec_.through < 2 || root < 0) {
    throw std::invalid_argument(fmt::format(
        "a crease fan needs two or more elements through h and two along ({} x {} here)",
        spec_.along, spec_.through));
  }
  // Every second corner node within half the band on either side: the blocks do not overlap.
  const double half = 0.5 * spec_.crease_fan_band;
  const double centre = corner_from_rim(root, theta);
  add_fan_block(root, theta);
  for (int e = root - 2; e >= 1 && corner_from_rim(e, theta) <= centre + half; e -= 2) {
    add_fan_block(e, theta);
  }
  for (int e = root + 2; e < spec_.along && corner_from_rim(e, theta) >= centre - half; e += 2) {
    add_fan_block(e, theta);
  }
  crease_root_ = 2 * root * (2 * spec_.through + 1);
  drop_unused_nodes();
}

namespace {

using UV = std::array<double, 2>;

// The nine nodes of a quadrilateral with corners c in the element's order (a, b) = (0, 0),
// (2, 0), (2, 2), (0, 2), straight in lattice coordinates: node (a, b) at the bilinear
// interpolation of the corners, its index from node_at.
template <typename NodeAt>
std::array<int, 9> quad_nodes(const std::array<UV, 4>& c, NodeAt&& node_at) {
  std::array<int, 9> el{};
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      const double x = 0.5 * a, y = 0.5 * b;
      UV uv{};
      for (int k = 0; k < 2; ++k) {
        uv[k] = (1 - x) * (1 - y) * c[0][k] + x * (1 - y) * c[1][k] + x * y * c[2][k] +
                (1 - x) * y * c[3][k];
      }
      el[3 * a + b] = node_at(uv);
    }
  }
  return el;
}

}  // namespace

std::array<double, 2> Body::lattice_point(double u, double v,
                                          const std::vector<double>& theta) const {
  const int ni = 2 * spec_.along + 1, nj = 2 * spec_.through + 1;
  const int lo = std::clamp(static_cast<int>(std::floor(u)), 0, ni - 2);
  const double t = theta[lo] + (u - lo) * (theta[lo + 1] - theta[lo]);
  const double s = spec_.R - 0.5 * spec_.h + spec_.h * v / (nj - 1);
  return {s * std::sin(t), -s * std::cos(t)};
}

std::function<int(const std::array<double, 2>&)> Body::block_nodes(
    int i0, int width, const std::vector<double>& theta) {
  const int nj = 2 * spec_.through + 1;
  return [this, i0, width, nj, &theta,
          created = std::vector<std::pair<UV, int>>()](const UV& uv) mutable {
    const bool on_lattice = uv[0] == std::round(uv[0]) && uv[1] == std::round(uv[1]);
    const bool on_boundary = uv[0] == 0 || uv[0] == width || uv[1] == 0 || uv[1] == 4;
    if (on_lattice && on_boundary) {
      return (i0 + static_cast<int>(uv[0])) * nj + static_cast<int>(uv[1]);
    }
    for (const auto& [at, id] : created) {
      if (std::abs(at[0] - uv[0]) < 1e-9 && std::abs(at[1] - uv[1]) < 1e-9) return id;
    }
    const auto [r, z] = lattice_point(i0 + uv[0], uv[1], theta);
    nodes_.r.push_back(r);
    nodes_.z.push_back(z);
    created.emplace_back(uv, static_cast<int>(nodes_.r.size()) - 1);
    return created.back().second;
  };
}

// The fan replaces the 2 x 2 block of elements whose inner-surface edge's middle corner is the
// root P: in the block's lattice coordinates (u along, v through, 0..4 each) its corners are
// A (0, 0), P (2, 0), B (4, 0), C (0, 2), D (4, 2), E (0, 4), M (2, 4), F (4, 4), and its
// five elements are A P O1 C, P O2 M O1, P B D O2, C O1 M E and O2 D F M, with two new
// corners O1, O2 at v = 1.6 on rays from P that split the angle between PD and the normal
// (and its mirror): every element convex whatever the block's aspect, P's three corners about
// 60 degrees on square elements. The block's boundary, its edges' middle nodes included, is
// the lattice's, so the fan conforms to the elements around it.
void Body::add_fan_block(int root, const std::vector<double>& theta) {
  const int nj = 2 * spec_.through + 1;
  const int i0 = 2 * (root - 1);
  // The rays from P: the lattice units' lengths along and through at P.
  const double along_unit = spec_.R * (theta[i0 + 4] - theta[i0]) / 4.0;
  const double through_unit = spec_.h / (nj - 1);
  const double pd = std::atan2(through_unit, along_unit);  // PD's angle from the surface
  const double ray = 0.5 * (pd + 0.5 * std::numbers::pi);
  const double du = 1.6 * through_unit / std::tan(ray) / along_unit;
  const UV A{0, 0}, P{2, 0}, B{4, 0}, C{0, 2}, D{4, 2}, E{0, 4}, M{2, 4}, F{4, 4};
  const UV O1{2 - du, 1.6}, O2{2 + du, 1.6};
  const std::array<std::array<UV, 4>, 5> quads{
      {{A, P, O1, C}, {P, O2, M, O1}, {P, B, D, O2}, {C, O1, M, E}, {O2, D, F, M}}};
  auto node_at = block_nodes(i0, 4, theta);
  std::array<std::array<int, 9>, 5> fan{};
  for (int q = 0; q < 5; ++q) fan[q] = quad_nodes(quads[q], node_at);
  // The inner-surface elements keep their places (element e * through is e's inner one).
  const int T = spec_.through;
  elements_[static_cast<std::size_t>((root - 1) * T)] = fan[0];
  elements_[static_cast<std::size_t>((root - 1) * T + 1)] = fan[3];
  elements_[static_cast<std::size_t>(root * T)] = fan[2];
  elements_[static_cast<std::size_t>(root * T + 1)] = fan[4];
  elements_.push_back(fan[1]);
  ++crease_fans_;
}

// The first `depth` layers (v from 0 to 2 depth in lattice units), column e from inner corner
// b_e = (2e, 0) to b_(e+1), under the corners M_e = (2e, 2 depth): two new corners per inner
// corner node, L_e = (2e - du, depth) and R_e = (2e + du, depth), and per column the elements
// S_e = b_e b_(e+1) L_(e+1) R_e (on the inner surface), U_e = R_e L_(e+1) M_(e+1) M_e (under
// the layers above) and, about each corner node between columns, the diamond
// D_e = b_e R_e M_e L_e. b_e's corners are then S_(e-1)'s, D_e's and S_e's, the three about
// 60 degrees where the elements are as long as thick (du at most 0.6: R_e and L_(e+1) stay
// apart on long-and-thin ones). At the axis R_0 = (0, depth) and at the rim L_n = (2n, depth)
// lie on the boundary, which takes the edge there that no element around could.
void Body::add_fan_layer(const std::vector<double>& theta) {
  const int n = spec_.along, T = spec_.through, nj = 2 * T + 1;
  const int depth = spec_.fan_layer;
  const double through_unit = spec_.h / (nj - 1);
  std::vector<double> du(n + 1, 0.0);
  for (int e = 1; e < n; ++e) {
    const double along_unit = 0.5 * spec_.R * (theta[2 * e + 1] - theta[2 * e - 1]);
    du[e] = std::min(0.6, std::tan(std::numbers::pi / 6.0) * depth * through_unit / along_unit);
  }
  std::map<std::pair<long long, long long>, int> created;
  std::vector<std::pair<double, int>> on_axis, on_rim;  // (v, node) of new boundary nodes
  const auto node_at = [&](const UV& uv) {
    const double iu = std::round(uv[0]), iv = std::round(uv[1]);
    if (std::abs(uv[0] - iu) < 1e-9 && std::abs(uv[1] - iv) < 1e-9) {
      return static_cast<int>(iu) * nj + static_cast<int>(iv);
    }
    const std::pair key{std::llround(uv[0] * 1e6), std::llround(uv[1] * 1e6)};
    if (const auto it = created.find(key); it != created.end()) return it->second;
    const auto [r, z] = lattice_point(uv[0], uv[1], theta);
    const int id = static_cast<int>(nodes_.r.size());
    nodes_.r.push_back(uv[0] == 0.0 ? 0.0 : r);
    nodes_.z.push_back(z);
    created.emplace(key, id);
    if (uv[0] == 0.0) on_axis.emplace_back(uv[1], id);
    if (uv[0] == 2.0 * n) on_rim.emplace_back(uv[1], id);
    return id;
  };
  const double mid = depth, top = 2.0 * depth;
  const auto b = [](int e) { return UV{2.0 * e, 0.0}; };
  const auto M = [&](int e) { return UV{2.0 * e, top}; };
  const auto L = [&](int e) { return UV{2.0 * e - du[e], mid}; };
  const auto R = [&](int e) { return UV{2.0 * e + du[e], mid}; };
  for (int e = 0; e < n; ++e) {
    const auto base = static_cast<std::size_t>(e * T);
    elements_[base] = quad_nodes({b(e), b(e + 1), L(e + 1), R(e)}, node_at);
    const auto under = quad_nodes({R(e), L(e + 1), M(e + 1), M(e)}, node_at);
    if (depth == 2) {
      elements_[base + 1] = under;
    } else {
      elements_.push_back(under);
    }
  }
  for (int e = 1; e < n; ++e) elements_.push_back(quad_nodes({b(e), R(e), M(e), L(e)}, node_at));
  // The new nodes on the axis and the rim face join those sets, in order through h.
  const auto merge = [&](std::vector<int>& set, int i, std::vector<std::pair<double, int>> extra) {
    for (int j = 0; j < nj; ++j) extra.emplace_back(j, i * nj + j);
    std::sort(extra.begin(), extra.end());
    set.clear();
    for (const auto& [v, id] : extra) set.push_back(id);
  };
  merge(axis_, 0, on_axis);
  merge(rim_, 2 * n, on_rim);
  drop_unused_nodes();  // the lattice's nodes inside the layer that no element holds now
}

// The inner corner node nearest each of MeshSpec::crease_seeds_from_rim gets a rosette and is
// moved radially outwards (into the solid) by MeshSpec::crease_seed_depth.
void Body::add_crease_seeds(const std::vector<double>& theta) {
  const double depth = spec_.crease_seed_depth;
  if (spec_.fan_layer > 0 || spec_.crease_fan_from_rim > 0.0 || !std::isfinite(depth) ||
      depth < 0.0 || !(depth < 0.1 * spec_.h) || spec_.through < 2 || spec_.along < 4) {
    throw std::invalid_argument(fmt::format(
        "a seeded crease needs two or more elements through h and four along, no crease fan or "
        "fan layer, and a notch from 0 to h / 10 deep ({} x {} elements, {} m here, h = {} m)",
        spec_.along, spec_.through, depth, spec_.h));
  }
  // Each root's element index along (its first corner), from the axis to the rim.
  std::vector<int> roots;
  for (const double s : spec_.crease_seeds_from_rim) {
    roots.push_back(nearest_inner_corner(s, 2, spec_.along - 2, theta));
  }
  std::sort(roots.begin(), roots.end());
  for (std::size_t k = 1; k < roots.size(); ++k) {
    if (roots[k] - roots[k - 1] < 4) {
      throw std::invalid_argument(fmt::format(
          "two seeded creases' rosettes overlap: their roots {:.3g} and {:.3g} mm from the rim "
          "are {} elements apart, and each takes two elements on either side",
          1e3 * corner_from_rim(roots[k - 1], theta), 1e3 * corner_from_rim(roots[k], theta),
          roots[k] - roots[k - 1]));
    }
  }
  // The lattice's node numbers hold until the unused nodes are dropped, after the last rosette.
  for (const int root : roots) {
    add_rosette(root, theta);
    const double t = theta[static_cast<std::size_t>(2 * root)];
    const int node = inner_[static_cast<std::size_t>(2 * root)];
    nodes_.r[node] += depth * std::sin(t);
    nodes_.z[node] -= depth * std::cos(t);
  }
  drop_unused_nodes();
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
    crease_seeds_.push_back(inner_[static_cast<std::size_t>(2 * *it)]);
  }
}

// The rosette replaces the block of elements root - 2 .. root + 1 along by the first two layers
// through h. In the block's lattice coordinates (u 0..8 along, v 0..4 through) the root is
// P = (4, 0). Four kites meet at P: P A_k C_k A_(k+1), k = 0..3, with A_0 = (6, 0) and
// A_4 = (2, 0) on the surface (so the inner surface's nodes stay the lattice's), A_1..A_3 on rays
// 45, 90 and 135 degrees from the surface, and C_k on the rays between, further out. Eight
// elements fill the ring between the kites and the block's boundary, one for each of its edges:
// the corners C_0, A_1, C_1, A_2, C_2, A_3, C_3 face the boundary's nodes (8, 2), (8, 4), (6, 4),
// (4, 4), (2, 4), (0, 4), (0, 2). The angles are physical (the lattice's units along and through
// differ); the rays' lengths are a = one element along, and 1.3 a for C. On elements longer than
// deep the kites would be skewed (a closed crease folds them), so the mesh is refused there.
void Body::add_rosette(int root, const std::vector<double>& theta) {
  const int nj = 2 * spec_.through + 1, T = spec_.through;
  const int i0 = 2 * (root - 2);
  const double along_unit =
      spec_.R * (theta[static_cast<std::size_t>(i0 + 8)] - theta[static_cast<std::size_t>(i0)]) /
      8.0;
  const double through_unit = spec_.h / (nj - 1);
  if (along_unit > 1.05 * through_unit) {
    throw std::invalid_argument(fmt::format(
        "a seeded crease's rosette needs elements no longer than deep: {:.3g} mm along and "
        "{:.3g} mm through here",
        2e3 * along_unit, 2e3 * through_unit));
  }
  const double a = 2.0 * along_unit;
  const auto ray = [&](double degrees, double length) {
    const double t = degrees * std::numbers::pi / 180.0;
    return UV{4.0 + length * std::cos(t) / along_unit, length * std::sin(t) / through_unit};
  };
  const UV P{4, 0}, A0{6, 0}, A4{2, 0};
  const UV A1 = ray(45, a), A2 = ray(90, a), A3 = ray(135, a);
  const UV C0 = ray(22.5, 1.3 * a), C1 = ray(67.5, 1.3 * a), C2 = ray(112.5, 1.3 * a),
           C3 = ray(157.5, 1.3 * a);
  // Element order: the surface's edge first (increasing u) where there is one.
  const std::array<std::array<UV, 4>, 12> quads{{
      {UV{0, 0}, A4, C3, UV{0, 2}},  // on the surface, column root - 2
      {A4, P, A3, C3},               // root - 1
      {P, A0, C0, A1},               // root
      {A0, UV{8, 0}, UV{8, 2}, C0},  // root + 1
      {UV{0, 2}, C3, A3, UV{0, 4}},
      {A3, C2, UV{2, 4}, UV{0, 4}},
      {C2, A2, UV{4, 4}, UV{2, 4}},
      {A2, C1, UV{6, 4}, UV{4, 4}},
      {C1, A1, UV{8, 4}, UV{6, 4}},
      {A1, C0, UV{8, 2}, UV{8, 4}},
      {P, A1, C1, A2},
      {P, A2, C2, A3},
  }};
  auto node_at = block_nodes(i0, 8, theta);
  // The block's eight elements: columns root - 2 .. root + 1, layers 0 and 1; the surface's
  // first, so that element column * through stays the column's inner one.
  for (int q = 0; q < 12; ++q) {
    const auto el = quad_nodes(quads[static_cast<std::size_t>(q)], node_at);
    const int column = root - 2 + q % 4;
    if (q < 8) {
      elements_[static_cast<std::size_t>(column * T + q / 4)] = el;
    } else {
      elements_.push_back(el);
    }
  }
}

double Body::from_rim(int node) const {
  if (node < 0) return std::numeric_limits<double>::quiet_NaN();
  return inner_arc_from_rim(spec_, std::atan2(nodes_.r[node], -nodes_.z[node]));
}

// Renumbers the nodes that some element holds, in their order, and drops the rest (the lattice's
// nodes inside a fan's block).
void Body::drop_unused_nodes() {
  std::vector<int> index(nodes_.size(), -1);
  for (const auto& el : elements_) {
    for (int m : el) index[m] = 0;
  }
  Points kept;
  for (std::size_t a = 0; a < index.size(); ++a) {
    if (index[a] < 0) continue;
    index[a] = static_cast<int>(kept.r.size());
    kept.r.push_back(nodes_.r[a]);
    kept.z.push_back(nodes_.z[a]);
  }
  nodes_ = std::move(kept);
  for (auto& el : elements_) {
    for (int& m : el) m = index[m];
  }
  for (auto* set : {&axis_, &rim_, &outer_, &inner_}) {
    for (int& a : *set) a = index[a];
  }
  if (crease_root_ >= 0) crease_root_ = index[crease_root_];
}

template <bool kEnergy>
double Body::element_loop(const Points& x, Points* f) const {
  return fem::with_law(material_,
                       [&](const auto& shear, const fem::law::LogVolumetric& volumetric) {
                         return element_loop<kEnergy>(x, f, shear, volumetric);
                       });
}

// Pass 0 takes the law's shear part at the full rule, pass 1 its volumetric part at the reduced
// rule; F = [F11 F12 0; F21 F22 0; 0 0 F33] in (r, z, hoop).
template <bool kEnergy, typename Shear>
double Body::element_loop(const Points& x, Points* f, const Shear& shear,
                          const fem::law::LogVolumetric& volumetric) const {
  double energy = 0.0;
  if (f) {
    f->r.assign(nodes_.size(), 0.0);
    f->z.assign(nodes_.size(), 0.0);
  }
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const auto& el = elements_[e];
    double xr[9], xz[9];
    for (int m = 0; m < 9; ++m) {
      xr[m] = x.r[el[m]];
      xz[m] = x.z[el[m]];
    }
    double fr[9] = {}, fz[9] = {};
    for (int pass = 0; pass < 2; ++pass) {
      const Rule& rule = pass == 0 ? full_ : reduced_;
      const std::size_t base = e * rule.points;
      for (int p = 0; p < rule.points; ++p) {
        const std::size_t qp = base + p;
        const double* N = &rule.N[9 * qp];
        const double* dR = &rule.dR[9 * qp];
        const double* dZ = &rule.dZ[9 * qp];
        const double rho0 = rule.rho0[qp];
        const auto [F11, F12, F21, F22, F33] = deformation_at(N, dR, dZ, rho0, xr, xz);
        const double d2 = F11 * F22 - F12 * F21;
        const double J = d2 * F33;
        const double I1 = F11 * F11 + F12 * F12 + F21 * F21 + F22 * F22 + F33 * F33;
        if (!(J > 0.0) || !std::isfinite(J) || (pass == 0 && !shear.admissible(I1))) {
          throw fem::InvertedElement(static_cast<int>(e), xr[0], 0.0, xz[0]);
        }
        const double lnJ = std::log(J);
        // F^-T of the 2 x 2 block, and of the hoop stretch.
        const double iT11 = F22 / d2, iT12 = -F21 / d2, iT21 = -F12 / d2, iT22 = F11 / d2;
        const double iT33 = 1.0 / F33;
        double P11, P12, P21, P22, P33;
        if (pass == 0) {
          const double a = shear.scale(I1);
          P11 = shear.stress(a, F11, iT11);
          P12 = shear.stress(a, F12, iT12);
          P21 = shear.stress(a, F21, iT21);
          P22 = shear.stress(a, F22, iT22);
          P33 = shear.stress(a, F33, iT33);
          if constexpr (kEnergy) energy += rule.weight[qp] * shear.energy(I1, lnJ);
        } else {
          const double s = volumetric.coefficient(lnJ);
          P11 = s * iT11;
          P12 = s * iT12;
          P21 = s * iT21;
          P22 = s * iT22;
          P33 = s * iT33;
          if constexpr (kEnergy) energy += volumetric.energy(lnJ, rule.weight[qp]);
        }
        if (f) {
          const double w = rule.weight[qp];
          const double h33 = P33 / rho0;
          for (int m = 0; m < 9; ++m) {
            fr[m] -= w * (P11 * dR[m] + P12 * dZ[m] + h33 * N[m]);
            fz[m] -= w * (P21 * dR[m] + P22 * dZ[m]);
          }
        }
      }
    }
    if (f) {
      for (int m = 0; m < 9; ++m) {
        f->r[el[m]] += fr[m];
        f->z[el[m]] += fz[m];
      }
    }
  }
  return energy;
}

void Body::internal_forces(const Points& x, Points& f) const { element_loop<false>(x, &f); }

double Body::strain_energy(const Points& x) const { return element_loop<true>(x, nullptr); }

namespace {

// det d(r, z) / d(s, t) of element el at (s, t), s along the meridian, t through h.
double meridian_det(const std::array<int, 9>& el, const Points& x, double s, double t) {
  const auto La = lagrange(s), Lb = lagrange(t);
  const auto dLa = lagrange_d(s), dLb = lagrange_d(t);
  double rs = 0, rt = 0, zs = 0, zt = 0;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      const int m = el[3 * a + b];
      rs += x.r[m] * dLa[a] * Lb[b];
      rt += x.r[m] * La[a] * dLb[b];
      zs += x.z[m] * dLa[a] * Lb[b];
      zt += x.z[m] * La[a] * dLb[b];
    }
  }
  return rs * zt - rt * zs;
}

}  // namespace

void Body::check_folds(const Points& x) const {
  std::vector<char> on_axis(nodes_.size(), 0);
  for (int a : axis_) on_axis[a] = 1;
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const auto& el = elements_[e];
    for (int m : el) {
      if (!on_axis[m] && !(x.r[m] > 0.0)) {
        throw fem::FoldedElement(static_cast<int>(e), 0.0, x.r[m], 0.0, x.z[m],
                                 fmt::format("its node {} is on or across the axis", m));
      }
    }
    const double sign = meridian_det(el, nodes_, 0.0, 0.0) < 0.0 ? -1.0 : 1.0;
    const auto found = fem::check_bicubic_on_square(
        [&](double s, double t) { return sign * meridian_det(el, x, s, t); });
    if (found.positive) continue;
    // det F at the point found, and the current place of that point.
    const double s = found.at[0], t = found.at[1];
    const auto La = lagrange(s), Lb = lagrange(t);
    double r = 0, z = 0, r0 = 0;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        const int m = el[3 * a + b];
        r += x.r[m] * La[a] * Lb[b];
        z += x.z[m] * La[a] * Lb[b];
        r0 += nodes_.r[m] * La[a] * Lb[b];
      }
    }
    const double J = found.min_found / (sign * meridian_det(el, nodes_, s, t)) * r / r0;
    // What the quadrature points see of it.
    double xr[9], xz[9];
    for (int m = 0; m < 9; ++m) {
      xr[m] = x.r[el[m]];
      xz[m] = x.z[el[m]];
    }
    double qmin = std::numeric_limits<double>::infinity(), qmax = -qmin;
    for (const Rule* rule : {&full_, &reduced_}) {
      for (int p = 0; p < rule->points; ++p) {
        const std::size_t qp = e * rule->points + p;
        const auto F = deformation_at(&rule->N[9 * qp], &rule->dR[9 * qp], &rule->dZ[9 * qp],
                                      rule->rho0[qp], xr, xz);
        const double Jq = (F.F11 * F.F22 - F.F12 * F.F21) * F.F33;
        qmin = std::min(qmin, Jq);
        qmax = std::max(qmax, Jq);
      }
    }
    const std::string what =
        found.min_found <= 0.0
            ? fmt::format("det F = {:.3g} at (s, t) = ({:.3f}, {:.3f})", J, s, t)
            : fmt::format(
                  "det F cannot be shown positive (bounded below by {:.3g} of the "
                  "meridian determinant after {} pieces)",
                  found.lower_bound, found.cells);
    throw fem::FoldedElement(
        static_cast<int>(e), J, r, 0.0, z,
        fmt::format("{}, while its quadrature points read det F = {:.3g} to {:.3g}", what, qmin,
                    qmax));
  }
}

double Body::cavity_volume(const Points& x) const {
  double V = 0.0;
  for_each_inner_point(x, [&](std::size_t, double w, const std::array<double, 3>&, double rho,
                              double, double dz) { V += w * std::numbers::pi * rho * rho * dz; });
  return V;
}

void Body::add_pressure_forces(const Points& x, double dp, Points& f) const {
  if (dp == 0.0) return;
  // f_a = -dp * integral of N_a n dA, n = (dz, -drho) / ds out of the cavity (into the material),
  // dA = 2 pi rho ds: exact with three Gauss points on the quadratic curve.
  for_each_inner_point(x, [&](std::size_t k, double w, const std::array<double, 3>& L, double rho,
                              double dr, double dz) {
    const double c = dp * w * 2.0 * std::numbers::pi * rho;
    for (int m = 0; m < 3; ++m) {
      const int a = inner_[k + m];
      f.r[a] -= c * L[m] * dz;
      f.z[a] += c * L[m] * dr;
    }
  });
}

double Body::highest_frequency() const {
  const std::size_t n = nodes_.size();
  std::vector<char> fixed_r(n, 0);
  for (int a : axis_) fixed_r[a] = 1;
  Points v{std::vector<double>(n), std::vector<double>(n)};
  // A start vector with every mode in it.
  for (std::size_t a = 0; a < n; ++a) {
    v.r[a] = fixed_r[a] ? 0.0 : std::sin(1.0 + 3.7 * static_cast<double>(a));
    v.z[a] = std::cos(2.0 + 5.3 * static_cast<double>(a));
  }
  Points f0, f1, x = nodes_;
  internal_forces(nodes_, f0);
  double lambda = 0.0;
  for (int it = 0; it < 200; ++it) {
    double norm = 0.0;
    for (std::size_t a = 0; a < n; ++a) norm += v.r[a] * v.r[a] + v.z[a] * v.z[a];
    norm = std::sqrt(norm);
    for (std::size_t a = 0; a < n; ++a) {
      v.r[a] /= norm;
      v.z[a] /= norm;
    }
    // A perturbation of 1e-7 h per node on average.
    const double eps = 1e-7 * spec_.h * std::sqrt(static_cast<double>(n));
    for (std::size_t a = 0; a < n; ++a) {
      x.r[a] = nodes_.r[a] + eps * v.r[a];
      x.z[a] = nodes_.z[a] + eps * v.z[a];
    }
    internal_forces(x, f1);
    // w = M^-1 K v = -M^-1 (f(x + eps v) - f(x)) / eps.
    double rayleigh = 0.0, vv = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
      const double wr = fixed_r[a] ? 0.0 : -(f1.r[a] - f0.r[a]) / (eps * mass_[a]);
      const double wz = -(f1.z[a] - f0.z[a]) / (eps * mass_[a]);
      rayleigh += wr * v.r[a] + wz * v.z[a];
      vv += v.r[a] * v.r[a] + v.z[a] * v.z[a];
      v.r[a] = wr;
      v.z[a] = wz;
    }
    const double next = rayleigh / vv;
    if (it > 20 && std::abs(next - lambda) < 1e-4 * std::abs(next)) {
      lambda = next;
      break;
    }
    lambda = next;
  }
  return std::sqrt(std::max(lambda, 0.0));
}

}  // namespace snapjump::axi
