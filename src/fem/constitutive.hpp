// The shell's material laws, one source for every path that evaluates them: the 3D body's scalar
// and four-point loops, its centroid bulk, and the axisymmetric body.
//
// Every law is isotropic and hyperelastic, its strain energy the sum of a shear part, a function
// of I1 = tr(F^T F) and J = det F, and a volumetric part shared by all laws:
//
//   psi(F) = psi_s(I1, J) + lambda/2 (ln J)^2,
//   P = dpsi/dF = P_s + lambda ln J F^-T,  P_s = 2 dpsi_s/dI1 F + J dpsi_s/dJ F^-T.
//
// The split is the one selective integration needs: the volumetric part can be integrated at
// fewer points than the shear part (fem::BulkRule, the axisymmetric body's reduced rule). The
// shear part is not isochoric (it carries -mu ln J, which cancels the stress at F = I).
//
// A law is a small value type with
//   energy(I1, lnJ)           psi_s,
//   scale(I1)                 a per-point factor its stress needs (computed once per point),
//   stress(scale, F_k, T_k)   entry k of P_s, from entry k of F and of T = F^-T,
//   admissible(I1)            whether psi_s is finite there,
//   kNeedsI1                  whether scale() reads I1 (the force loops skip I1 otherwise).
// The functions are templates on the number type so that the loops over four points (lanes of a
// `#pragma omp simd` loop) and the scalar code are the same expressions, hence the same bits.
#pragma once

#include <cmath>

namespace snapjump::fem::law {

// The volumetric part every law shares: psi_v = lambda/2 (ln J)^2, P_v = lambda ln J F^-T.
struct LogVolumetric {
  double lambda = 0.0;  // first Lame constant [Pa]
  // weight * psi_v, the weight multiplied first: a quadrature point's share and the density
  // (weight 1) round alike.
  template <typename T>
  [[nodiscard]] T energy(T lnJ, double weight = 1.0) const {
    return weight * 0.5 * lambda * lnJ * lnJ;
  }
  // P_v = coefficient(ln J) F^-T.
  template <typename T>
  [[nodiscard]] T coefficient(T lnJ) const {
    return lambda * lnJ;
  }
};

// The compressible neo-Hookean law of the paper (paper, Eq. S3): psi_s = mu/2 (I1 - 3) - mu ln J,
// hence P_s = mu (F - F^-T).
struct NeoHookean {
  double mu = 0.0;  // shear modulus [Pa]
  static constexpr bool kNeedsI1 = false;
  template <typename T>
  [[nodiscard]] T energy(T I1, T lnJ) const {
    return 0.5 * mu * (I1 - 3.0) - mu * lnJ;
  }
  template <typename T>
  [[nodiscard]] T scale(T /*I1*/) const {
    return mu;
  }
  template <typename T>
  [[nodiscard]] T stress(T s, T F, T Finv_t) const {
    return s * (F - Finv_t);
  }
  template <typename T>
  [[nodiscard]] bool admissible(T /*I1*/) const {
    return true;
  }
};

// Gent's law (A. N. Gent, Rubber Chem. Technol. 69, 59 (1996)), a neo-Hookean solid whose chains
// lock at I1 - 3 = Jm: psi_s = -mu Jm/2 ln(1 - (I1 - 3)/Jm) - mu ln J, hence
// P_s = mu / (1 - (I1 - 3)/Jm) F - mu F^-T. At small strain its shear modulus is mu and it adds
// 2 mu / Jm to the first Lame constant (the term (mu / 4 Jm)(I1 - 3)^2 of its expansion);
// fem::with_law takes that off the volumetric part, so a case's E and nu are the small-strain
// moduli under either law. It tends to the neo-Hookean law as Jm grows.
struct Gent {
  double mu = 0.0;  // shear modulus [Pa]
  double jm = 0.0;  // the locking value of I1 - 3 [-]
  static constexpr bool kNeedsI1 = true;
  template <typename T>
  [[nodiscard]] T energy(T I1, T lnJ) const {
    return -0.5 * mu * jm * std::log(1.0 - (I1 - 3.0) / jm) - mu * lnJ;
  }
  template <typename T>
  [[nodiscard]] T scale(T I1) const {
    return mu / (1.0 - (I1 - 3.0) / jm);
  }
  template <typename T>
  [[nodiscard]] T stress(T s, T F, T Finv_t) const {
    return s * F - mu * Finv_t;
  }
  template <typename T>
  [[nodiscard]] bool admissible(T I1) const {
    return I1 - 3.0 < jm;
  }
};

}  // namespace snapjump::fem::law
