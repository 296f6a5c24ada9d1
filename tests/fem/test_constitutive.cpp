// What every material law (fem/constitutive.hpp) must satisfy, run for each law: no stress and no
// energy in the reference state, P = dpsi/dF (central differences), frame invariance
// (psi(QF) = psi(F), P(QF) = Q P(F)), the energy convex along a stretch and along a shear, the
// small-strain moduli of linear elasticity, and a refusal where det F <= 0. Then each law's own
// closed forms, and the bodies (3D and axisymmetric) evaluating the same law: the 3D patch test
// against the law's stress, the axisymmetric forces against its energy's gradient.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "axi/body.hpp"
#include "fem/body.hpp"
#include "mesh/cap_mesher.hpp"

namespace snapjump::fem {
namespace {

constexpr double kE = 1.2e6, kNu = 0.45, kRho = 1160.0;

struct LawCase {
  std::string name;
  Material material;
};

std::vector<LawCase> laws() {
  const auto nh = Material::from_young(kE, kNu, kRho);
  // Jm = 3: locking at a stretch of about 2.2 in uniaxial strain, close enough that the strains
  // below feel it.
  return {{"neo_Hookean", nh}, {"Gent_Jm_3", nh.with_gent(3.0)}};
}

class LawContract : public ::testing::TestWithParam<LawCase> {};

// Row-major products and a rotation about an oblique axis.
void multiply(const double A[9], const double B[9], double C[9]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      C[3 * i + j] = 0.0;
      for (int k = 0; k < 3; ++k) C[3 * i + j] += A[3 * i + k] * B[3 * k + j];
    }
}

void rotation(double angle, const double axis[3], double Q[9]) {
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double u[3] = {axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Q[3 * i + j] = (i == j ? c : 0.0) + (1.0 - c) * u[i] * u[j];
  Q[1] -= s * u[2];
  Q[2] += s * u[1];
  Q[3] += s * u[2];
  Q[5] -= s * u[0];
  Q[6] -= s * u[1];
  Q[7] += s * u[0];
}

// Deformation gradients of moderate strain (up to about 30 %), det F > 0.
std::vector<std::array<double, 9>> sample_gradients() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-0.3, 0.3);
  std::vector<std::array<double, 9>> out;
  while (out.size() < 6) {
    std::array<double, 9> F{};
    for (int k = 0; k < 9; ++k) F[k] = (k % 4 == 0 ? 1.0 : 0.0) + d(rng);
    const double J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
                     F[2] * (F[3] * F[7] - F[4] * F[6]);
    if (J > 0.3) out.push_back(F);
  }
  return out;
}

TEST_P(LawContract, NoStressNorEnergyAtTheReferenceState) {
  const auto& m = GetParam().material;
  const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double P[9];
  ASSERT_TRUE(first_piola_stress(m, I, P));
  for (double p : P) EXPECT_NEAR(p, 0.0, 1e-9 * m.mu);
  EXPECT_NEAR(energy_density(m, I), 0.0, 1e-12 * m.mu);
}

TEST_P(LawContract, StressIsTheEnergysDerivative) {
  const auto& m = GetParam().material;
  for (const auto& F : sample_gradients()) {
    double P[9];
    ASSERT_TRUE(first_piola_stress(m, F.data(), P));
    for (int k = 0; k < 9; ++k) {
      auto Fp = F, Fm = F;
      const double h = 1e-6;
      Fp[k] += h;
      Fm[k] -= h;
      const double d = (energy_density(m, Fp.data()) - energy_density(m, Fm.data())) / (2 * h);
      EXPECT_NEAR(P[k], d, 1e-6 * (m.lambda + 2 * m.mu)) << "entry " << k;
    }
  }
}

TEST_P(LawContract, EnergyAndStressAreFrameInvariant) {
  const auto& m = GetParam().material;
  const double axis[3] = {0.3, -0.5, 0.8};
  double Q[9];
  rotation(0.7, axis, Q);
  for (const auto& F : sample_gradients()) {
    double QF[9], P[9], PQ[9], QP[9];
    multiply(Q, F.data(), QF);
    const double psi = energy_density(m, F.data());
    EXPECT_NEAR(energy_density(m, QF), psi, 1e-10 * std::abs(psi) + 1e-12 * m.mu);
    ASSERT_TRUE(first_piola_stress(m, F.data(), P));
    ASSERT_TRUE(first_piola_stress(m, QF, PQ));
    multiply(Q, P, QP);
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(PQ[k], QP[k], 1e-9 * (m.lambda + 2 * m.mu)) << k;
  }
}

// psi(s) along F = I + s A for a stretch and a shear: second differences positive from strong
// compression to 60 % stretch.
TEST_P(LawContract, EnergyIsConvexAlongAStretchAndAShear) {
  const auto& m = GetParam().material;
  const double stretch[9] = {1, 0, 0, 0, 0, 0, 0, 0, 0}, shear[9] = {0, 1, 0, 0, 0, 0, 0, 0, 0};
  for (const double* A : {stretch, shear}) {
    auto psi = [&](double s) {
      double F[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      for (int k = 0; k < 9; ++k) F[k] += s * A[k];
      return energy_density(m, F);
    };
    const double ds = 0.01;
    for (double s = (A == stretch ? -0.5 : -0.6); s <= 0.6; s += 0.05) {
      EXPECT_GT(psi(s + ds) - 2 * psi(s) + psi(s - ds), 0.0) << "s = " << s;
    }
  }
}

// Linear elasticity at small strain: uniaxial strain eps gives P11 = (lambda + 2 mu) eps,
// P22 = lambda eps; a shear gamma gives P12 = mu gamma.
TEST_P(LawContract, SmallStrainGivesTheLameModuli) {
  const auto& m = GetParam().material;
  const double eps = 1e-7;
  const double Fu[9] = {1 + eps, 0, 0, 0, 1, 0, 0, 0, 1};
  const double Fs[9] = {1, eps, 0, 0, 1, 0, 0, 0, 1};
  double P[9];
  ASSERT_TRUE(first_piola_stress(m, Fu, P));
  EXPECT_NEAR(P[0] / eps, m.lambda + 2 * m.mu, 1e-5 * (m.lambda + 2 * m.mu));
  EXPECT_NEAR(P[4] / eps, m.lambda, 1e-5 * (m.lambda + 2 * m.mu));
  ASSERT_TRUE(first_piola_stress(m, Fs, P));
  EXPECT_NEAR(P[1] / eps, m.mu, 1e-5 * m.mu);
}

TEST_P(LawContract, AnInvertedGradientIsRefused) {
  const auto& m = GetParam().material;
  const double F[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1}, Z[9] = {1, 0, 0, 0, 1, 0, 0, 0, 0};
  double P[9];
  EXPECT_FALSE(first_piola_stress(m, F, P));
  EXPECT_FALSE(first_piola_stress(m, Z, P));
  EXPECT_EQ(energy_density(m, F), std::numeric_limits<double>::infinity());
}

INSTANTIATE_TEST_SUITE_P(Laws, LawContract, ::testing::ValuesIn(laws()),
                         [](const auto& info) { return info.param.name; });

// Uniaxial strain F = diag(s, 1, 1), worked out by hand from Gent's energy:
// P11 = mu s / (1 - (s^2 - 1)/Jm) - mu / s + (lambda - 2 mu / Jm) ln s / s (lambda the small-strain
// Lame constant); the neo-Hookean law is Jm -> inf.
TEST(GentLaw, UniaxialStrainHasItsClosedFormAndLocks) {
  const auto nh = Material::from_young(kE, kNu, kRho);
  for (const double jm : {0.5, 3.0, 30.0}) {
    const auto g = nh.with_gent(jm);
    for (const double s : {0.8, 1.1, 1.2}) {
      const double F[9] = {s, 0, 0, 0, 1, 0, 0, 0, 1};
      double P[9];
      ASSERT_TRUE(first_piola_stress(g, F, P));
      const double expected = g.mu * s / (1.0 - (s * s - 1.0) / jm) - g.mu / s +
                              (g.lambda - 2.0 * g.mu / jm) * std::log(s) / s;
      EXPECT_NEAR(P[0], expected, 1e-12 * (g.lambda + 2 * g.mu)) << jm << " " << s;
    }
  }
  // Large Jm: the neo-Hookean stress, to (I1 - 3) / Jm.
  const double F[9] = {1.2, 0.1, 0, 0, 0.9, 0, 0, 0, 1.05};
  double Pn[9], Pg[9];
  ASSERT_TRUE(first_piola_stress(nh, F, Pn));
  ASSERT_TRUE(first_piola_stress(nh.with_gent(1e8), F, Pg));
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(Pg[k], Pn[k], 1e-6 * nh.mu) << k;
  // At and beyond the lock (I1 - 3 >= Jm) there is no state.
  const double L[9] = {2, 0, 0, 0, 1, 0, 0, 0, 1};  // I1 - 3 = 3
  double P[9];
  EXPECT_FALSE(first_piola_stress(nh.with_gent(3.0), L, P));
  EXPECT_EQ(energy_density(nh.with_gent(2.9), L), std::numeric_limits<double>::infinity());
  EXPECT_THROW((void)nh.with_gent(0.0), std::invalid_argument);
  EXPECT_THROW((void)nh.with_gent(std::nan("")), std::invalid_argument);
}

// The 3D body with each law: an affine deformation's nodal forces have the moment -P(A) V.
TEST_P(LawContract, TheBodysAffinePatchTestGivesTheLawsStress) {
  const auto& m = GetParam().material;
  const Body body(mesh::make_cap_mesh({.R = 0.03,
                                       .h = 0.002,
                                       .phi = 80.0 * std::numbers::pi / 180.0,
                                       .element_size = 0.008,
                                       .layers = 1}),
                  m);
  const double A[9] = {1.15, 0.05, -0.02, 0.03, 0.9, 0.04, -0.01, 0.02, 1.1};
  const auto& X = body.mesh().nodes;
  mesh::Points x;
  for (std::size_t a = 0; a < X.size(); ++a) {
    x.push_back(A[0] * X.x[a] + A[1] * X.y[a] + A[2] * X.z[a],
                A[3] * X.x[a] + A[4] * X.y[a] + A[5] * X.z[a],
                A[6] * X.x[a] + A[7] * X.y[a] + A[8] * X.z[a]);
  }
  mesh::Points f;
  body.internal_forces(x, f);
  double P[9];
  ASSERT_TRUE(first_piola_stress(m, A, P));
  double moment[9] = {}, pmax = 0.0;
  for (std::size_t a = 0; a < X.size(); ++a) {
    const double fa[3] = {f.x[a], f.y[a], f.z[a]}, Xa[3] = {X.x[a], X.y[a], X.z[a]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) moment[3 * i + j] += fa[i] * Xa[j];
  }
  for (double p : P) pmax = std::max(pmax, std::abs(p));
  const double V = body.quadrature_volume();
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(moment[k], -P[k] * V, 1e-9 * pmax * V) << k;
  EXPECT_NEAR(body.strain_energy(x), V * energy_density(m, A), 1e-9 * pmax * V);
}

// The axisymmetric body with each law: its forces are minus its energy's gradient.
TEST_P(LawContract, TheAxisymmetricBodysForcesAreMinusItsEnergysGradient) {
  const double R = 0.03, h = 0.002, phi = 80.0 * std::numbers::pi / 180.0;
  const axi::Body b({R, h, phi, 2, axi::elements_along(R, h, phi, 2)}, GetParam().material);
  auto x = b.nodes();
  for (std::size_t a = 0; a < x.size(); ++a) {  // up to 20 % in the hoop, smooth
    x.r[a] *= 1.0 + 0.2 * std::sin(40.0 * x.z[a]);
    x.z[a] += 1e-3 * std::cos(60.0 * x.r[a]);
  }
  axi::Points f;
  b.internal_forces(x, f);
  double fmax = 0.0;
  for (std::size_t a = 0; a < f.size(); ++a)
    fmax = std::max({fmax, std::abs(f.r[a]), std::abs(f.z[a])});
  const double dx = 1e-8;
  for (const std::size_t a : {std::size_t{7}, f.size() / 3, f.size() / 2, f.size() - 4}) {
    auto xp = x, xm = x;
    xp.r[a] += dx;
    xm.r[a] -= dx;
    const double dr = (b.strain_energy(xp) - b.strain_energy(xm)) / (2 * dx);
    EXPECT_NEAR(f.r[a], -dr, 1e-5 * std::abs(dr) + 1e-6 * fmax) << "node " << a;
  }
}

}  // namespace
}  // namespace snapjump::fem
