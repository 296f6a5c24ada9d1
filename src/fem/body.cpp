#include "fem/body.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fem/fold_check.hpp"
#include "mesh/tet10.hpp"

namespace snapjump::fem {

using mesh::kTetNodes;
using mesh::kTriNodes;
using mesh::tet10_shape;
using mesh::tet10_shape_gradients;
using mesh::tet_rule_degree2;
using mesh::tet_rule_degree5;
using mesh::tri6_shape;
using mesh::tri6_shape_gradients;
using mesh::tri_rule_degree4;

namespace {

constexpr int kQp = 4;  // points of the degree-2 rule
constexpr int kGradStride = kTetNodes * 3;

// The determinant and F^-T of a row-major 3x3 whose entry k is A(k): one set of expressions for
// a plain matrix (det3, inverse_transpose) and for one point of the force loop's four (the same
// bits either way).
template <typename At>
[[gnu::always_inline]] inline double det3_of(At A) {
  return A(0) * (A(4) * A(8) - A(5) * A(7)) - A(1) * (A(3) * A(8) - A(5) * A(6)) +
         A(2) * (A(3) * A(7) - A(4) * A(6));
}

// put(k, entry k of F^-T) = put(k, cofactor k of F * inv), inv = 1 / det F.
template <typename At, typename Put>
[[gnu::always_inline]] inline void inverse_transpose_of(At F, double inv, Put put) {
  put(0, (F(4) * F(8) - F(5) * F(7)) * inv);
  put(1, (F(5) * F(6) - F(3) * F(8)) * inv);
  put(2, (F(3) * F(7) - F(4) * F(6)) * inv);
  put(3, (F(2) * F(7) - F(1) * F(8)) * inv);
  put(4, (F(0) * F(8) - F(2) * F(6)) * inv);
  put(5, (F(1) * F(6) - F(0) * F(7)) * inv);
  put(6, (F(1) * F(5) - F(2) * F(4)) * inv);
  put(7, (F(2) * F(3) - F(0) * F(5)) * inv);
  put(8, (F(0) * F(4) - F(1) * F(3)) * inv);
}

double det3(const double A[9]) {
  return det3_of([A](int k) { return A[k]; });
}

// F^-T of a row-major 3x3 with determinant J: cofactor matrix / J.
void inverse_transpose(const double F[9], double J, double out[9]) {
  inverse_transpose_of([F](int k) { return F[k]; }, 1.0 / J,
                       [out](int k, double v) { out[k] = v; });
}

}  // namespace

Material Material::from_young(double E, double nu, double rho) {
  if (!(E > 0 && nu > -1.0 && nu < 0.5 && rho > 0)) {
    throw std::invalid_argument(fmt::format(
        "the compressible neo-Hookean body needs E > 0, rho > 0 and -1 < nu < 0.5 (got E = {}, "
        "nu = {}, rho = {})",
        E, nu, rho));
  }
  return {E / (2.0 * (1.0 + nu)), E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), rho};
}

double Material::p_wave_speed() const { return std::sqrt((lambda + 2.0 * mu) / rho); }

Material Material::with_gent(double jm) const {
  if (!(jm > 0.0 && std::isfinite(jm))) {
    throw std::invalid_argument(
        fmt::format("Gent's law needs a positive, finite locking value Jm (got {})", jm));
  }
  Material m = *this;
  m.law = LawKind::gent;
  m.gent_jm = jm;
  return m;
}

namespace {

// I1 = tr(F^T F) of a row-major 3x3.
double first_invariant(const double F[9]) {
  double I1 = 0.0;
  for (int k = 0; k < 9; ++k) I1 += F[k] * F[k];
  return I1;
}

// psi(F) of one law at one point; +inf where det F <= 0 or the law is not defined at F.
template <typename Shear>
double point_energy(const Shear& shear, const law::LogVolumetric& volumetric, const double F[9]) {
  const double J = det3(F);
  if (!(J > 0.0)) return std::numeric_limits<double>::infinity();
  const double I1 = first_invariant(F);
  if (!shear.admissible(I1)) return std::numeric_limits<double>::infinity();
  const double lnJ = std::log(J);
  return shear.energy(I1, lnJ) + volumetric.energy(lnJ);
}

}  // namespace

bool first_piola_stress(const Material& m, const double F[9], double P[9]) {
  return with_law(m, [&](const auto& shear, const law::LogVolumetric& volumetric) {
    const double J = det3(F);
    if (!(J > 0.0)) return false;
    double I1 = 0.0;
    if constexpr (std::decay_t<decltype(shear)>::kNeedsI1) {
      I1 = first_invariant(F);
      if (!shear.admissible(I1)) return false;
    }
    double Finv_t[9];
    inverse_transpose(F, J, Finv_t);
    const double c = volumetric.coefficient(std::log(J));
    const double a = shear.scale(I1);
    for (int k = 0; k < 9; ++k) P[k] = shear.stress(a, F[k], Finv_t[k]) + c * Finv_t[k];
    return true;
  });
}

double energy_density(const Material& m, const double F[9]) {
  return with_law(m, [&](const auto& shear, const law::LogVolumetric& volumetric) {
    return point_energy(shear, volumetric, F);
  });
}

InvertedElement::InvertedElement(int e, double px, double py, double pz)
    : std::runtime_error(fmt::format(
          "element {} is inverted or its force is not finite (near ({:.4g}, {:.4g}, {:.4g}) m)", e,
          px, py, pz)),
      element(e),
      x(px),
      y(py),
      z(pz) {}

FoldedElement::FoldedElement(int e, double det_f_, double px, double py, double pz,
                             const std::string& what)
    : std::runtime_error(fmt::format("element {} is folded through itself: {} (near ({:.4g}, "
                                     "{:.4g}, {:.4g}) m)",
                                     e, what, px, py, pz)),
      element(e),
      det_f(det_f_),
      x(px),
      y(py),
      z(pz) {}

FoldedElement::FoldedElement(const std::string& context, const FoldedElement& fold)
    : std::runtime_error(fmt::format("{}: {}", context, fold.what())),
      element(fold.element),
      det_f(fold.det_f),
      x(fold.x),
      y(fold.y),
      z(fold.z) {}

namespace {

// The items (elements, faces) at each of nn nodes: node a's are list[start[a] .. start[a + 1]),
// each as item * N + its local node, in item order.
template <std::size_t N>
void build_incidence(const std::vector<std::array<int, N>>& items, std::size_t nn,
                     std::vector<int>& start, std::vector<int>& list) {
  start.assign(nn + 1, 0);
  for (const auto& item : items) {
    for (int a : item) ++start[static_cast<std::size_t>(a) + 1];
  }
  for (std::size_t a = 0; a < nn; ++a) start[a + 1] += start[a];
  list.resize(static_cast<std::size_t>(start[nn]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < items.size(); ++i) {
    for (std::size_t k = 0; k < N; ++k) {
      list[static_cast<std::size_t>(fill[static_cast<std::size_t>(items[i][k])]++)] =
          static_cast<int>(i * N + k);
    }
  }
}

}  // namespace

Body::Body(mesh::Mesh mesh, const Material& material, BulkRule bulk)
    : mesh_(std::move(mesh)), material_(material), bulk_(bulk) {
  mesh::check_mesh(mesh_);
  const std::size_t ne = mesh_.tets.size();
  const std::size_t nn = mesh_.nodes.size();
  grad_.resize(ne * kQp * kGradStride);
  weight_.resize(ne * kQp);
  std::vector<double> n2(nn, 0.0);  // integral of N_a^2 over the body
  min_spacing_ = std::numeric_limits<double>::infinity();
  if (bulk_ == BulkRule::centroid) {
    centroid_grad_.resize(ne * kGradStride);
    centroid_weight_.resize(ne);
  }
  const auto rule = tet_rule_degree2();
  const auto mass_rule = tet_rule_degree5();
  for (std::size_t e = 0; e < ne; ++e) {
    const auto& tet = mesh_.tets[e];
    const auto jacobian = [&](const std::array<std::array<double, 3>, kTetNodes>& G, double Jm[9]) {
      std::fill(Jm, Jm + 9, 0.0);
      for (int a = 0; a < kTetNodes; ++a) {
        const double X[3] = {mesh_.nodes.x[tet[a]], mesh_.nodes.y[tet[a]], mesh_.nodes.z[tet[a]]};
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) Jm[3 * i + j] += X[i] * G[a][j];
        }
      }
    };
    // dN/dX at (r, s, t) into g; returns det(dX/dxi).
    const auto reference_gradients = [&](double r, double s, double t, double* g) {
      const auto G = tet10_shape_gradients(r, s, t);
      double Jm[9];
      jacobian(G, Jm);
      const double detJ = det3(Jm);
      double Jinv_t[9];  // (dX/dxi)^-T: dN/dX = (dX/dxi)^-T dN/dxi
      inverse_transpose(Jm, detJ, Jinv_t);
      for (int a = 0; a < kTetNodes; ++a) {
        for (int i = 0; i < 3; ++i) {
          g[3 * a + i] =
              Jinv_t[3 * i] * G[a][0] + Jinv_t[3 * i + 1] * G[a][1] + Jinv_t[3 * i + 2] * G[a][2];
        }
      }
      return detJ;
    };
    double element_weight = 0.0;  // the element's quadrature volume
    for (int q = 0; q < kQp; ++q) {
      const auto& p = rule[q];
      double g[kGradStride];
      const double detJ = reference_gradients(p.r, p.s, p.t, g);
      for (int k = 0; k < kGradStride; ++k) grad_[(e * kGradStride + k) * kQp + q] = g[k];
      weight_[e * kQp + q] = p.weight * detJ;
      element_weight += p.weight * detJ;
    }
    if (bulk_ == BulkRule::centroid) {
      if (!(reference_gradients(0.25, 0.25, 0.25, &centroid_grad_[e * kGradStride]) > 0.0)) {
        throw mesh::MeshError(fmt::format("element {} is degenerate at its centroid", e));
      }
      centroid_weight_[e] = element_weight;
    }
    for (const auto& p : mass_rule) {
      const auto G = tet10_shape_gradients(p.r, p.s, p.t);
      const auto N = tet10_shape(p.r, p.s, p.t);
      double Jm[9];
      jacobian(G, Jm);
      const double dV = p.weight * det3(Jm);
      volume_ += dV;
      for (int a = 0; a < kTetNodes; ++a) n2[tet[a]] += N[a] * N[a] * dV;
    }
    for (int a = 0; a < kTetNodes; ++a) {
      for (int b = a + 1; b < kTetNodes; ++b) {
        const int i = tet[a], j = tet[b];
        min_spacing_ = std::min(min_spacing_, std::hypot(mesh_.nodes.x[i] - mesh_.nodes.x[j],
                                                         mesh_.nodes.y[i] - mesh_.nodes.y[j],
                                                         mesh_.nodes.z[i] - mesh_.nodes.z[j]));
      }
    }
  }
  // The paper's diagonal scaling (paper, Eq. S9): m_a proportional to the integral of N_a^2,
  // summing to rho V.
  total_mass_ = material_.rho * volume_;
  double sum_n2 = 0.0;
  for (double v : n2) sum_n2 += v;
  mass_.resize(nn);
  for (std::size_t a = 0; a < nn; ++a) mass_[a] = total_mass_ * n2[a] / sum_n2;

  std::vector<char> is_clamped(nn, 0);
  for (int a : mesh_.clamped) is_clamped[a] = 1;
  std::vector<char> seen(nn, 0);
  for (const auto& f : mesh_.inner_faces) {
    for (int a : f) {
      if (is_clamped[a] && !seen[a]) {
        seen[a] = 1;
        inner_rim_.push_back(a);
      }
    }
  }
  if (!mesh_.inner_faces.empty() && !mesh_.clamped.empty() && inner_rim_.empty()) {
    throw mesh::MeshError("no inner face reaches the clamped rim: the cavity is not closed by it");
  }
  build_incidence(mesh_.inner_faces, nn, face_incidence_start_, face_incidence_);
  build_incidence(mesh_.tets, nn, incidence_start_, incidence_);
}

void Body::check_point(std::size_t e, int q, const char* what) const {
  if (e >= mesh_.tets.size() || q < 0 || q >= kQp) {
    throw std::out_of_range(
        fmt::format("{}: no element {} or quadrature point {} (of {})", what, e, q, kQp));
  }
}

std::array<double, kGradStride> Body::point_gradients(std::size_t e, int q) const {
  check_point(e, q, "point_gradients");
  std::array<double, kGradStride> g{};
  const auto qs = static_cast<std::size_t>(q);
  for (std::size_t k = 0; k < kGradStride; ++k) g[k] = grad_[(e * kGradStride + k) * kQp + qs];
  return g;
}

double Body::point_weight(std::size_t e, int q) const {
  check_point(e, q, "point_weight");
  return weight_[e * kQp + static_cast<std::size_t>(q)];
}

double Body::quadrature_volume() const {
  double v = 0.0;
  for (double w : weight_) v += w;
  return v;
}

double Body::stable_time_step(double factor) const {
  return factor * min_spacing_ / material_.p_wave_speed();
}

// Power iteration on M^-1 K, K v from the forces of a small displacement eps v about the
// reference state (where the forces vanish): the iterate tends to the highest mode, its Rayleigh
// quotient to omega_max^2.
double Body::highest_frequency() const { return highest_frequency(mesh_.nodes); }

double Body::highest_frequency(const mesh::Points& at, mesh::Points* mode) const {
  const std::size_t n = num_nodes();
  mesh::Points v, x = at, f, f0;
  const bool warm = mode != nullptr && mode->size() == n;
  if (warm) {
    v = *mode;
  } else {
    for (std::size_t a = 0; a < n; ++a) {  // a start vector with every mode in it
      const auto d = static_cast<double>(a);
      v.push_back(std::sin(1.0 + 3.7 * d), std::cos(2.0 + 5.3 * d), std::sin(0.5 + 7.1 * d));
    }
  }
  internal_forces(at, f0);
  double lambda = 0.0;
  bool converged = false;
  for (int it = 0; it < 500 && !converged; ++it) {
    double norm = 0.0;
    for (std::size_t a = 0; a < n; ++a) norm += v.x[a] * v.x[a] + v.y[a] * v.y[a] + v.z[a] * v.z[a];
    norm = std::sqrt(norm);
    for (std::size_t a = 0; a < n; ++a) {
      v.x[a] /= norm;
      v.y[a] /= norm;
      v.z[a] /= norm;
    }
    // A displacement of about 1e-7 of the smallest node spacing per node; K v from the change of
    // the internal forces.
    const double eps = 1e-7 * min_spacing_ * std::sqrt(static_cast<double>(n));
    for (std::size_t a = 0; a < n; ++a) {
      x.x[a] = at.x[a] + eps * v.x[a];
      x.y[a] = at.y[a] + eps * v.y[a];
      x.z[a] = at.z[a] + eps * v.z[a];
    }
    internal_forces(x, f);
    double vw = 0.0, vv = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
      const double s = -1.0 / (eps * mass_[a]);
      const double w[3] = {s * (f.x[a] - f0.x[a]), s * (f.y[a] - f0.y[a]), s * (f.z[a] - f0.z[a])};
      vw += w[0] * v.x[a] + w[1] * v.y[a] + w[2] * v.z[a];
      vv += v.x[a] * v.x[a] + v.y[a] * v.y[a] + v.z[a] * v.z[a];
      v.x[a] = w[0];
      v.y[a] = w[1];
      v.z[a] = w[2];
    }
    const double next = vw / vv;
    converged = it > (warm ? 3 : 20) && std::abs(next - lambda) < 1e-5 * std::abs(next);
    lambda = next;
  }
  if (mode != nullptr) *mode = v;
  return std::sqrt(std::max(lambda, 0.0));
}

namespace {

// Records element e as inverted if it is the lowest-numbered one so far: the element a failed
// step names does not depend on which thread found it first.
void note_inverted(std::atomic<int>& lowest, int e) {
  int seen = lowest.load();
  while ((seen < 0 || e < seen) && !lowest.compare_exchange_weak(seen, e)) {
  }
}

// Throws InvertedElement for element e (none when e < 0), placed at its first node.
void throw_if_inverted(int e, const mesh::Mesh& m, const mesh::Points& x) {
  if (e < 0) return;
  const int a = m.tets[static_cast<std::size_t>(e)][0];
  throw InvertedElement(e, x.x[a], x.y[a], x.z[a]);
}

}  // namespace

namespace {

// The current positions of an element's nodes.
[[gnu::always_inline]] inline void gather(const std::array<int, kTetNodes>& tet,
                                          const mesh::Points& x, double xe[kTetNodes][3]) {
  for (int a = 0; a < kTetNodes; ++a) {
    xe[a][0] = x.x[tet[a]];
    xe[a][1] = x.y[tet[a]];
    xe[a][2] = x.z[tet[a]];
  }
}

// F = sum_a x_a (dN_a/dX)^T at one point, g the point's [node][3] gradients.
[[gnu::always_inline]] inline void deformation_gradient(const double (*xe)[3], const double* g,
                                                        double F[9]) {
  std::fill(F, F + 9, 0.0);
  for (int a = 0; a < kTetNodes; ++a) {
    for (int i = 0; i < 3; ++i) {
      F[3 * i + 0] += xe[a][i] * g[3 * a + 0];
      F[3 * i + 1] += xe[a][i] * g[3 * a + 1];
      F[3 * i + 2] += xe[a][i] * g[3 * a + 2];
    }
  }
}

// The same at the four quadrature points at once, G the element's [node][3][point] gradients:
// F[k][q] is entry k at point q, summed over the nodes in the order of the one-point loop, so
// each point's F has the same bits; the four points side by side let the compiler use vectors.
[[gnu::always_inline]] inline void deformation_gradients(const double (*xe)[3], const double* G,
                                                         double F[9][kQp]) {
  for (int k = 0; k < 9; ++k) std::fill(F[k], F[k] + kQp, 0.0);
  for (int a = 0; a < kTetNodes; ++a) {
    for (int i = 0; i < 3; ++i) {
      const double xi = xe[a][i];
      for (int j = 0; j < 3; ++j) {
        const double* g = G + (3 * a + j) * kQp;
#pragma omp simd
        for (int q = 0; q < kQp; ++q) F[3 * i + j][q] += xi * g[q];
      }
    }
  }
}

// Point q's entries of F[9][kQp].
[[gnu::always_inline]] inline void at_point(const double F[9][kQp], int q, double Fq[9]) {
  for (int k = 0; k < 9; ++k) Fq[k] = F[k][q];
}

// out_a -= w P dN_a/dX at one point (g as for deformation_gradient).
[[gnu::always_inline]] inline void add_point_forces(const double P[9], const double* g, double w,
                                                    double* out) {
  for (int a = 0; a < kTetNodes; ++a) {
    for (int i = 0; i < 3; ++i) {
      out[3 * a + i] -=
          w * (P[3 * i] * g[3 * a] + P[3 * i + 1] * g[3 * a + 1] + P[3 * i + 2] * g[3 * a + 2]);
    }
  }
}

// out_a -= w_q P_q dN_a/dX(q) for the four points, subtracted point after point: the bits of
// add_point_forces called for q = 0, 1, 2, 3 (G and P as for deformation_gradients).
[[gnu::always_inline]] inline void add_nodal_forces(const double P[9][kQp], const double* G,
                                                    const double* w, double* out) {
  for (int a = 0; a < kTetNodes; ++a) {
    const double* g0 = G + 3 * a * kQp;
    const double* g1 = g0 + kQp;
    const double* g2 = g1 + kQp;
    for (int i = 0; i < 3; ++i) {
      double t[kQp];
#pragma omp simd
      for (int q = 0; q < kQp; ++q) {
        t[q] = w[q] * (P[3 * i][q] * g0[q] + P[3 * i + 1][q] * g1[q] + P[3 * i + 2][q] * g2[q]);
      }
      double& o = out[3 * a + i];
      for (int q = 0; q < kQp; ++q) o -= t[q];
    }
  }
}

// first_piola_stress at the four points at once (F and P as for deformation_gradients): the same
// expressions point by point (det3_of, inverse_transpose_of, the law's), so each point's P has
// first_piola_stress's bits; the logarithm stays the scalar library call. False where some point's
// J is not positive or the law is not defined.
template <typename Shear>
[[gnu::always_inline]] inline bool stresses_at_points(const Shear& shear,
                                                      const law::LogVolumetric& volumetric,
                                                      const double F[9][kQp], double P[9][kQp]) {
  double J[kQp], c[kQp], a[kQp] = {};
  bool positive = true;
#pragma omp simd
  for (int q = 0; q < kQp; ++q) J[q] = det3_of([&F, q](int k) { return F[k][q]; });
  for (int q = 0; q < kQp; ++q) positive = positive && J[q] > 0.0;
  if (!positive) return false;
  if constexpr (Shear::kNeedsI1) {
    for (int q = 0; q < kQp; ++q) {
      double I1 = 0.0;
      for (int k = 0; k < 9; ++k) I1 += F[k][q] * F[k][q];
      if (!shear.admissible(I1)) return false;
      a[q] = shear.scale(I1);
    }
  }
  // Scalar on purpose: a vector logarithm (libmvec, -ffast-math) would round differently.
  for (int q = 0; q < kQp; ++q) c[q] = volumetric.coefficient(std::log(J[q]));
  double T[9][kQp];  // F^-T
#pragma omp simd
  for (int q = 0; q < kQp; ++q) {
    inverse_transpose_of([&F, q](int k) { return F[k][q]; }, 1.0 / J[q],
                         [&T, q](int k, double v) { T[k][q] = v; });
  }
  for (int k = 0; k < 9; ++k) {
#pragma omp simd
    for (int q = 0; q < kQp; ++q) {
      // A law whose factor does not depend on I1 gets it as a constant (no array in the loop).
      const double s = Shear::kNeedsI1 ? a[q] : shear.scale(0.0);
      P[k][q] = shear.stress(s, F[k][q], T[k][q]) + c[q] * T[k][q];
    }
  }
  return true;
}

}  // namespace

template <bool kEnergy>
[[gnu::always_inline]] inline bool Body::element_pass(int e, const mesh::Points& x,
                                                      double* out) const {
  return with_law(material_, [&](const auto& shear, const law::LogVolumetric& volumetric) {
    return element_pass<kEnergy>(e, x, shear, volumetric, out);
  });
}

template <bool kEnergy, typename Shear>
[[gnu::always_inline]] inline bool Body::element_pass(int e, const mesh::Points& x,
                                                      const Shear& shear,
                                                      const law::LogVolumetric& volumetric,
                                                      double* out) const {
  const auto es = static_cast<std::size_t>(e);
  double xe[kTetNodes][3];
  gather(mesh_.tets[es], x, xe);
  if constexpr (kEnergy) {
    *out = 0.0;
  } else {
    std::fill(out, out + 3 * kTetNodes, 0.0);
  }
  // With the bulk at the centroid, the four points carry the rest of the energy.
  const law::LogVolumetric at_points{bulk_ == BulkRule::centroid ? 0.0 : volumetric.lambda};
  const double* G = &grad_[es * kQp * kGradStride];
  const double* w = &weight_[es * kQp];
  double F[9][kQp];
  deformation_gradients(xe, G, F);
  if constexpr (kEnergy) {
    for (int q = 0; q < kQp; ++q) {
      double Fq[9];
      at_point(F, q, Fq);
      const double psi = point_energy(shear, at_points, Fq);
      if (!std::isfinite(psi)) return false;
      *out += w[q] * psi;
    }
  } else {
    double P[9][kQp];
    if (!stresses_at_points(shear, at_points, F, P)) return false;
    add_nodal_forces(P, G, w, out);
  }
  if (bulk_ == BulkRule::centroid) {
    const double* g = &centroid_grad_[es * kGradStride];
    const double wc = centroid_weight_[es];
    double Fc[9];
    deformation_gradient(xe, g, Fc);
    const double J = det3(Fc);
    if (!(J > 0.0)) return false;
    const double lnJ = std::log(J);
    if constexpr (kEnergy) {
      *out += volumetric.energy(lnJ, wc);
    } else {
      double P[9];  // lambda ln J F^-T
      inverse_transpose(Fc, J, P);
      const double c = volumetric.coefficient(lnJ);
      for (double& v : P) v *= c;
      add_point_forces(P, g, wc, out);
    }
  }
  return true;
}

template <typename Shear>
SNAPJUMP_AVX2 bool Body::element_forces_wide(int e, const mesh::Points& x, const Shear& shear,
                                             const law::LogVolumetric& volumetric,
                                             double* out) const {
  return element_pass<false>(e, x, shear, volumetric, out);
}

// Inside the force pass's parallel region: every element's nodal forces into its slots of ef
// under one law (chosen once per pass, not per element).
template <typename Shear>
void Body::element_forces(const mesh::Points& x, const Shear& shear,
                          const law::LogVolumetric& volumetric, double* ef,
                          std::atomic<int>& bad) const {
  const long ne = static_cast<long>(mesh_.tets.size());
#pragma omp for schedule(static)
  for (long e = 0; e < ne; ++e) {
    double* out = ef + 3 * kTetNodes * e;
    const int el = static_cast<int>(e);
    const bool ok = wide_ ? element_forces_wide(el, x, shear, volumetric, out)
                          : element_pass<false>(el, x, shear, volumetric, out);
    if (!ok) note_inverted(bad, el);
  }
}

namespace {

std::array<std::array<double, 3>, kTetNodes> element_nodes(const std::array<int, kTetNodes>& tet,
                                                           const mesh::Points& x) {
  std::array<std::array<double, 3>, kTetNodes> out{};
  for (int a = 0; a < kTetNodes; ++a) out[a] = {x.x[tet[a]], x.y[tet[a]], x.z[tet[a]]};
  return out;
}

}  // namespace

void Body::check_folds(const mesh::Points& x) const {
  const long ne = static_cast<long>(mesh_.tets.size());
  std::atomic<int> bad{-1};
#pragma omp parallel for schedule(static)
  for (long e = 0; e < ne; ++e) {
    const auto& tet = mesh_.tets[static_cast<std::size_t>(e)];
    if (!check_tet10(element_nodes(tet, mesh_.nodes), element_nodes(tet, x)).positive) {
      note_inverted(bad, static_cast<int>(e));
    }
  }
  const int e = bad.load();
  if (e < 0) return;
  const auto& tet = mesh_.tets[static_cast<std::size_t>(e)];
  const auto found = check_tet10(element_nodes(tet, mesh_.nodes), element_nodes(tet, x));
  // What the quadrature points see of it.
  double qmin = std::numeric_limits<double>::infinity(), qmax = -qmin;
  for (int q = 0; q < 4; ++q) {
    const auto g = point_gradients(static_cast<std::size_t>(e), q);
    double xe[kTetNodes][3], F[9];
    gather(tet, x, xe);
    deformation_gradient(xe, g.data(), F);
    qmin = std::min(qmin, det3(F));
    qmax = std::max(qmax, det3(F));
  }
  const auto N = mesh::tet10_shape(found.at[0], found.at[1], found.at[2]);
  double p[3] = {};
  for (int a = 0; a < kTetNodes; ++a) {
    p[0] += N[a] * x.x[tet[a]];
    p[1] += N[a] * x.y[tet[a]];
    p[2] += N[a] * x.z[tet[a]];
  }
  const std::string what =
      found.min_found <= 0.0
          ? fmt::format("det F = {:.3g} at reference point ({:.3f}, {:.3f}, {:.3f})",
                        found.min_found, found.at[0], found.at[1], found.at[2])
          : fmt::format(
                "det F cannot be shown positive (det(dx/dxi) bounded below by {:.3g} "
                "after {} pieces)",
                found.lower_bound, found.cells);
  throw FoldedElement(e, found.min_found, p[0], p[1], p[2],
                      fmt::format("{}, while its quadrature points read det F = {:.3g} to {:.3g}",
                                  what, qmin, qmax));
}

void Body::internal_forces(const mesh::Points& x, mesh::Points& f) const {
  ForceScratch scratch;
  internal_forces(x, f, scratch);
}

// f_a = -sum over points of w P(F) dN_a/dX (paper, Eq. S10).
// One parallel region: each element's nodal forces into its own slots, then each node adds up the
// slots of its elements in element order. No two threads write one value, and every node's sum
// has the same order at any thread count.
void Body::internal_forces(const mesh::Points& x, mesh::Points& f, ForceScratch& scratch) const {
  const std::size_t n = num_nodes();
  const long nn = static_cast<long>(n);
  f.x.resize(n);
  f.y.resize(n);
  f.z.resize(n);
  scratch.element_forces.resize(mesh_.tets.size() * 3 * kTetNodes);
  double* ef = scratch.element_forces.data();
  std::atomic<int> bad{-1};
#pragma omp parallel
  {
    with_law(material_, [&](const auto& shear, const law::LogVolumetric& volumetric) {
      element_forces(x, shear, volumetric, ef, bad);
    });
    // (the loop's barrier: every slot is written, and `bad` is final)
    if (bad.load() < 0) {
#pragma omp for schedule(static)
      for (long a = 0; a < nn; ++a) {
        double s[3] = {0.0, 0.0, 0.0};
        for (int k = incidence_start_[a]; k < incidence_start_[a + 1]; ++k) {
          const double* slot = ef + 3 * static_cast<std::size_t>(incidence_[k]);
          s[0] += slot[0];
          s[1] += slot[1];
          s[2] += slot[2];
        }
        f.x[a] = s[0];
        f.y[a] = s[1];
        f.z[a] = s[2];
      }
    }
  }
  throw_if_inverted(bad.load(), mesh_, x);
}

// Each element's energy, added up in element order after the parallel loop: a sum that does not
// depend on the number of threads (an OpenMP reduction would).
double Body::strain_energy(const mesh::Points& x) const {
  const long ne = static_cast<long>(mesh_.tets.size());
  std::vector<double> energy(mesh_.tets.size(), 0.0);
  std::atomic<int> bad{-1};
#pragma omp parallel for schedule(static)
  for (long e = 0; e < ne; ++e) {
    if (!element_pass<true>(static_cast<int>(e), x, &energy[static_cast<std::size_t>(e)])) {
      note_inverted(bad, static_cast<int>(e));
    }
  }
  throw_if_inverted(bad.load(), mesh_, x);
  double total = 0.0;
  for (const double u : energy) total += u;
  return total;
}

std::vector<double> Body::element_energy_density(const mesh::Points& x) const {
  std::vector<double> out(mesh_.tets.size(), 0.0);
  for (std::size_t e = 0; e < mesh_.tets.size(); ++e) {
    if (bulk_ == BulkRule::centroid) {  // the element's energy as the forces integrate it
      double W = 0.0;
      if (!element_pass<true>(static_cast<int>(e), x, &W)) W = 0.0;  // inverted: shown as 0
      out[e] = W / centroid_weight_[e];
      continue;
    }
    double xe[kTetNodes][3];
    gather(mesh_.tets[e], x, xe);
    double W = 0.0, V = 0.0;
    double F[9][kQp];
    deformation_gradients(xe, &grad_[e * kQp * kGradStride], F);
    for (int q = 0; q < kQp; ++q) {
      const double w = weight_[e * kQp + q];
      double Fq[9];
      at_point(F, q, Fq);
      const double psi = energy_density(material_, Fq);
      W += w * (std::isfinite(psi) ? psi : 0.0);
      V += w;
    }
    out[e] = W / V;
  }
  return out;
}

namespace {

// The inner faces' quadrature rule with its shape functions and their gradients at each point.
struct FaceRule {
  static constexpr std::size_t kMaxPoints = 8;
  std::size_t size = 0;
  std::array<double, kMaxPoints> weight{};
  std::array<std::array<double, kTriNodes>, kMaxPoints> N{};
  std::array<std::array<std::array<double, 2>, kTriNodes>, kMaxPoints> G{};
};
FaceRule face_rule() {
  const auto rule = tri_rule_degree4();
  if (rule.size() > FaceRule::kMaxPoints) throw std::logic_error("face_rule: rule too long");
  FaceRule r;
  r.size = rule.size();
  for (std::size_t q = 0; q < rule.size(); ++q) {
    r.weight[q] = rule[q].weight;
    r.N[q] = tri6_shape(rule[q].r, rule[q].s);
    r.G[q] = tri6_shape_gradients(rule[q].r, rule[q].s);
  }
  return r;
}

// Calls visit(k, n, p) at each quadrature point q of each face f, k = f * points + q, with the
// area vector n = w dx/dr x dx/ds and the position p there. In parallel over the faces: visit
// writes to slot k only.
template <typename Visit>
void face_points(const FaceRule& rule, const std::vector<std::array<int, 6>>& faces,
                 const mesh::Points& x, Visit&& visit) {
  const long nf = static_cast<long>(faces.size());
  const std::size_t nq = rule.size;
#pragma omp parallel for schedule(static)
  for (long f = 0; f < nf; ++f) {
    const auto& face = faces[static_cast<std::size_t>(f)];
    double xa[kTriNodes][3];
    for (int a = 0; a < kTriNodes; ++a) {
      xa[a][0] = x.x[face[a]];
      xa[a][1] = x.y[face[a]];
      xa[a][2] = x.z[face[a]];
    }
    for (std::size_t q = 0; q < nq; ++q) {
      double p[3] = {}, dr[3] = {}, ds[3] = {};
      for (int a = 0; a < kTriNodes; ++a) {
        for (int i = 0; i < 3; ++i) {
          p[i] += rule.N[q][a] * xa[a][i];
          dr[i] += rule.G[q][a][0] * xa[a][i];
          ds[i] += rule.G[q][a][1] * xa[a][i];
        }
      }
      const double w = rule.weight[q];
      const double n[3] = {w * (dr[1] * ds[2] - dr[2] * ds[1]), w * (dr[2] * ds[0] - dr[0] * ds[2]),
                           w * (dr[0] * ds[1] - dr[1] * ds[0])};
      visit(static_cast<std::size_t>(f) * nq + q, n, p);
    }
  }
}

}  // namespace

void Body::add_pressure_forces(const mesh::Points& x, double dp, mesh::Points& f) const {
  ForceScratch scratch;
  add_pressure_forces(x, dp, f, scratch);
}

// The area vectors of every face point first, then each node adds its faces' shares in face
// order, point by point: the sums a face-by-face loop would make, at any thread count.
void Body::add_pressure_forces(const mesh::Points& x, double dp, mesh::Points& f,
                               ForceScratch& scratch) const {
  const auto rule = face_rule();
  const std::size_t nq = rule.size;
  scratch.face_normals.resize(3 * nq * mesh_.inner_faces.size());
  double* n = scratch.face_normals.data();
  face_points(rule, mesh_.inner_faces, x, [n](std::size_t k, const double* nk, const double*) {
    std::copy(nk, nk + 3, n + 3 * k);
  });
  const long nn = static_cast<long>(num_nodes());
#pragma omp parallel for schedule(static)
  for (long a = 0; a < nn; ++a) {
    const auto as = static_cast<std::size_t>(a);
    const int k0 = face_incidence_start_[as], k1 = face_incidence_start_[as + 1];
    if (k0 == k1) continue;
    // The node's force held in registers while its shares are subtracted, in the same order.
    double fa[3] = {f.x[as], f.y[as], f.z[as]};
    for (int k = k0; k < k1; ++k) {
      const auto slot = static_cast<std::size_t>(face_incidence_[static_cast<std::size_t>(k)]);
      const std::size_t face = slot / kTriNodes, local = slot % kTriNodes;
      for (std::size_t q = 0; q < nq; ++q) {
        const double* nv = n + 3 * (face * nq + q);
        const double s = dp * rule.N[q][local];
        fa[0] -= s * nv[0];
        fa[1] -= s * nv[1];
        fa[2] -= s * nv[2];
      }
    }
    f.x[as] = fa[0];
    f.y[as] = fa[1];
    f.z[as] = fa[2];
  }
}

double Body::cavity_volume(const mesh::Points& x) const {
  if (inner_rim_.empty()) {
    throw std::logic_error("cavity_volume: the body has no inner faces closed by a clamped rim");
  }
  // Reference point: the centre of the inner rim circle, which lies in the rim plane, so the
  // flat lid closing the cavity adds nothing to (1/3) integral of (x - x0) . n dA.
  double c[3] = {};
  for (int a : inner_rim_) {
    c[0] += x.x[a];
    c[1] += x.y[a];
    c[2] += x.z[a];
  }
  for (double& v : c) v /= static_cast<double>(inner_rim_.size());
  const auto rule = face_rule();
  std::vector<double> terms(rule.size * mesh_.inner_faces.size());  // (p - c) . n per point
  face_points(rule, mesh_.inner_faces, x, [&](std::size_t k, const double* n, const double* p) {
    terms[k] = (p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1] + (p[2] - c[2]) * n[2];
  });
  double volume = 0.0;  // point by point, in face order
  for (const double t : terms) volume += t;
  return volume / 3.0;
}

void Body::cavity_volume_gradient(const mesh::Points& x, mesh::Points& g) const {
  const std::size_t n = num_nodes();
  g.x.assign(n, 0.0);
  g.y.assign(n, 0.0);
  g.z.assign(n, 0.0);
  add_pressure_forces(x, -1.0, g);
}

void Body::add_gravity(double g, mesh::Points& f) const {
  for (std::size_t a = 0; a < mass_.size(); ++a) f.z[a] -= mass_[a] * g;
}

}  // namespace snapjump::fem
