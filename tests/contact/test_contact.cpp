// Tests of snapjump::contact against closed forms (Reissner, the Hamiltonian first integral of
// the ridge, clamped-plate Bessel limit) and against the paper's published numbers
// (N+ = 76.94, n(2) = 20.83, N- = 46.8; at nu = 1/2: 1.2 < alpha_r < 1.6, 1.8 < alpha_e < 4.5,
// 5.3 < alpha_F < 8.5).  Where the computed numbers honestly differ from the paper's the tests
// pin the explanation (see docs/contact-solver.md), never a number this code printed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "contact/contact.hpp"
#include "theory/prefactors.hpp"

namespace sc = snapjump::contact;

namespace {

// Paper (snap-and-jump.tex, "Elastic shells pushed by a rigid plane").
constexpr double kPaperNPlus = 76.94;
constexpr double kPaperN2 = 20.83;
constexpr double kPaperNMinus = 46.8;
constexpr double kKappaHalf = 9.0;  // 12 (1 - 0.5^2)

class ContactConstants : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    constants_ = new sc::Constants(sc::compute_constants(sc::SolverOptions{}));
  }
  static void TearDownTestSuite() {
    delete constants_;
    constants_ = nullptr;
  }
  static const sc::Constants& c() { return *constants_; }

 private:
  static inline sc::Constants* constants_ = nullptr;
};

TEST_F(ContactConstants, ReissnerSlopeAndNPlus) {
  // ReissnerSlopeIsEight
  // Closed form: F = 4 E h^2 e / (R sqrt(3 (1 - nu^2)))  <=>  N = 8 e_hat.
  EXPECT_NEAR(c().reissner_slope, 8.0, 8.0 * 1e-3);
  EXPECT_LT(c().reissner_fit_spread, 8.0 * 1e-3);
  // NPlusMatchesPaper
  EXPECT_NEAR(c().N_plus, kPaperNPlus, 0.01 * kPaperNPlus);
  EXPECT_GT(c().a_plus, 0.0);
  EXPECT_GT(c().e_hat_plus, 0.0);
  EXPECT_LT(c().c1_plus, 0.0);  // compressed contact disk
}

TEST_F(ContactConstants, ClampedPlateConditionHoldsAtNPlus) {
  // Power-series condition theta(a) = 0 ...
  EXPECT_NEAR(sc::clamped_plate_function(c().a_plus, c().c1_plus), 0.0, 1e-9);
  // ... and the independent collocation eigenvalue problem: top eigenvalue crosses zero there.
  EXPECT_NEAR(c().plate_eigenvalue_at_plus, 0.0, 1e-7);
  const double mu_scale = 14.68 / (c().a_plus * c().a_plus);  // j_{1,1}^2 / a^2
  EXPECT_LT(std::abs(c().plate_eigenvalue_at_plus), 1e-8 * mu_scale);
  // Earlier on the branch the flat disk is stable (all eigenvalues negative).
  const auto early = sc::disk_branch(sc::SolverOptions{}, 0.8 * c().a_plus);
  EXPECT_LT(sc::clamped_plate_top_eigenvalue(early.back().a, early.back().c1), -0.1);
  EXPECT_GT(early.back().plate_function, 0.0);
}

TEST(ContactPlate, EigenvalueMatchesBesselLimit) {
  // For a small disk the x^2/16 term is negligible: theta = J1(k x) with k^2 = -c1 - mu,
  // clamped at x = a when k a = j_{1,1} = 3.8317059702, so mu = -j11^2/a^2 - c1 (+ O(a^2/16)).
  const double j11 = 3.8317059702075125;
  const double a = 0.3, c1 = -2.0;
  EXPECT_NEAR(sc::clamped_plate_top_eigenvalue(a, c1), -j11 * j11 / (a * a) - c1, 1e-2);
  // The series solution with c1 = -j11^2/a^2 vanishes at a up to the same small correction.
  EXPECT_NEAR(sc::clamped_plate_function(a, -j11 * j11 / (a * a)), 0.0, 1e-3);
  EXPECT_NEAR(sc::clamped_plate_function(0.02, -j11 * j11 / (0.02 * 0.02)), 0.0, 1e-8);
}

TEST_F(ContactConstants, RidgeN2AndMirrorEnergy) {
  // RidgeN2MatchesPaperAndFirstIntegral
  EXPECT_NEAR(c().n2, kPaperN2, 0.01 * kPaperN2);
  EXPECT_NEAR(c().n2, 3.0 * std::numbers::pi * c().ridge_I, 1e-12);
  const sc::RidgeSolution r = sc::solve_ridge();
  // Hamiltonian phi'^2/2 - sigma'^2/2 - sigma (phi^2 - 1)/2 is conserved and 0 at infinity,
  // so sigma(0) = -phi'(0)^2.
  EXPECT_NEAR(r.hamiltonian0, 0.0, 1e-8);
  EXPECT_NEAR(r.phi.front(), 0.0, 1e-12);
  EXPECT_NEAR(r.phi.back(), 1.0, 1e-12);
  EXPECT_LT(r.sigma0, 0.0);
  // FullRingBranchTendsToRidgeLaw
  // Independent route to n2: N/a of large rings of the full problem, extrapolated to a -> inf.
  EXPECT_NEAR(c().n2_ring_extrapolated, c().n2, 1e-3);
  // MirrorEnergyPrefactor
  // C = pi I / 12^(3/4) = n2 / (3 * 12^(3/4)) with d the apex displacement r^2/R.
  const double c_paper = kPaperN2 / (3.0 * std::pow(12.0, 0.75));
  EXPECT_NEAR(c().mirror_energy_prefactor, c_paper, 0.01 * c_paper);
  EXPECT_NEAR(c().mirror_energy_prefactor_cap_height,
              std::pow(2.0, 1.5) * c().mirror_energy_prefactor, 1e-12);
}

TEST_F(ContactConstants, LowerCrossingAndBounds) {
  // NMinusPaperConstruction
  // The crossing really is on the paper's ring law N = n2 sqrt(e_hat).
  EXPECT_NEAR(c().N_minus, c().n2 * std::sqrt(c().e_hat_minus), 1e-8);
  EXPECT_NEAR(c().N_minus_paper_n2, kPaperN2 * std::sqrt(c().e_hat_minus_paper_n2), 1e-8);
  // Not the paper's 46.8: the computed crossing is 3-4 % higher (docs/contact-solver.md);
  // the paper's own alpha_F_lo = 5.3 corresponds to the crossing with its n2 = 20.83.
  EXPECT_NEAR(c().N_minus, kPaperNMinus, 0.04 * kPaperNMinus);
  EXPECT_NEAR(c().N_minus_paper_n2 / kKappaHalf, 5.3, 0.05);
  EXPECT_LT(c().N_minus, c().N_plus);
  // With the ring law in the note's geometry (e = r^2/(2R)) there is no crossing before N+.
  EXPECT_LT(c().max_disk_over_note_law, 1.0);
  EXPECT_TRUE(std::isnan(c().N_minus_note));
  // BoundsAtHalfAgreeWithPaperWhereTheyShould
  namespace th = snapjump::theory;
  const th::Prefactors b = th::prefactor_bounds(th::from_solver(c()), 0.5);
  EXPECT_NEAR(b.alpha_r.lo, 1.2, 0.05);
  EXPECT_NEAR(b.alpha_r.hi, 1.6, 0.05);
  EXPECT_NEAR(b.alpha_e.lo, 1.8, 0.05);
  // The paper's alpha_e,hi = 4.5 is the ring law's displacement at force N+,
  // (N+/n2)^2 / sqrt(kappa); the disk branch itself ends at e_hat+ = 7.46 (alpha_e = 2.49).
  EXPECT_NEAR(b.alpha_e.hi, 4.5, 0.05);
  EXPECT_NEAR(c().e_hat_plus / std::sqrt(kKappaHalf), 2.49, 0.01);
  EXPECT_NEAR(b.alpha_F.hi, 8.5, 0.05);
  // alpha_F_lo: 5.38 with the computed n2 = 20.95, 5.33 with the paper's n2 (tested above):
  // the paper's 5.3 is missed by 0.08 because its n2 is 0.6 % low (docs/contact-solver.md).
  EXPECT_NEAR(b.alpha_F.lo, 5.38, 0.01);
  // alpha_t = sqrt(3 alpha_e / alpha_F) at each point, ordered.
  const double t_plus = std::sqrt(3.0 * b.alpha_e.hi / b.alpha_F.hi);
  const double t_minus = std::sqrt(3.0 * b.alpha_e.lo / b.alpha_F.lo);
  EXPECT_DOUBLE_EQ(b.alpha_t.lo, std::min(t_plus, t_minus));
  EXPECT_DOUBLE_EQ(b.alpha_t.hi, std::max(t_plus, t_minus));
  EXPECT_LT(b.alpha_r.lo, b.alpha_r.hi);
  EXPECT_LT(b.alpha_e.lo, b.alpha_e.hi);
  EXPECT_LT(b.alpha_F.lo, b.alpha_F.hi);
  // BoundsScaleWithKappa
  for (const double nu : {0.3, 0.45, 0.5}) {
    const double kappa = 12.0 * (1.0 - nu * nu);
    const th::Prefactors bn = th::prefactor_bounds(th::from_solver(c()), nu);
    EXPECT_NEAR(bn.alpha_F.hi * kappa, c().N_plus, 1e-9);
    EXPECT_NEAR(bn.alpha_F.lo * kappa, c().N_minus, 1e-9);
    EXPECT_NEAR(bn.alpha_e.hi * std::sqrt(kappa), c().e_hat_ring_law_at_plus, 1e-9);
    EXPECT_NEAR(bn.alpha_r.hi * std::pow(kappa, 0.25), c().a_plus, 1e-9);
  }
}

TEST_F(ContactConstants, SolutionsCheckedAndRingBifurcatesFromDiskEnd) {
  // SolutionsAreChecked
  EXPECT_LT(c().max_residual, 1e-7);
  EXPECT_LT(c().max_offgrid_residual, 1e-6);
  EXPECT_GE(c().min_disk_gap, -1e-9);  // no penetration of the plane
  EXPECT_GE(c().min_ring_gap, -1e-9);
  EXPECT_GT(c().min_ring_apex_gap, 0.0);
  // RingBranchBifurcatesFromDiskEnd
  EXPECT_NEAR(c().ring_a_end, c().a_plus, 0.01);
  EXPECT_NEAR(c().ring_N_end, c().N_plus, 0.5);
  EXPECT_NEAR(c().ring_e_hat_end, c().e_hat_plus, 0.05);
  // Subcritical: forces on the ring branch dip below N+ before rising again.
  EXPECT_LT(c().ring_N_min, c().N_plus);
  EXPECT_GT(c().ring_a_at_N_min, c().a_plus);
  EXPECT_LT(c().ring_e_hat_min, c().e_hat_plus);
}

TEST(ContactConvergence, HeadlineNumbersStableUnderRefinement) {
  // Raising the polynomial degree by 8 / lengthening the domain by 1.5x changes nothing
  // visible.
  const sc::Constants k = sc::compute_constants(sc::SolverOptions{}, true);
  for (const double d : {k.dN_plus_resolution, k.dN_plus_domain, k.dN_minus_resolution,
                         k.dN_minus_domain, k.de_hat_plus_resolution, k.de_hat_plus_domain,
                         k.dn2_resolution, k.dn2_domain, k.dreissner_resolution, k.dreissner_domain,
                         k.dring_N_min_resolution, k.dring_N_min_domain}) {
    EXPECT_TRUE(std::isfinite(d));
    EXPECT_LT(std::abs(d), 1e-6);
  }
}

TEST(ContactDisk, BranchIsMonotoneAndConvexBeyondInflection) {
  const auto d = sc::disk_branch();
  ASSERT_GT(d.size(), 20u);
  double min_slope = 1e300;
  for (size_t i = 1; i < d.size(); ++i) {
    EXPECT_GT(d[i].a, d[i - 1].a);
    EXPECT_GT(d[i].N, d[i - 1].N);
    EXPECT_GT(d[i].e_hat, d[i - 1].e_hat);
    min_slope = std::min(min_slope, (d[i].N - d[i - 1].N) / (d[i].e_hat - d[i - 1].e_hat));
  }
  EXPECT_GT(min_slope, 0.0);
  // Convex (slope increasing) once e_hat > 1.5 ...
  for (size_t i = 2; i < d.size(); ++i) {
    if (d[i - 2].e_hat < 1.5) continue;
    const double s1 = (d[i - 1].N - d[i - 2].N) / (d[i - 1].e_hat - d[i - 2].e_hat);
    const double s2 = (d[i].N - d[i - 1].N) / (d[i].e_hat - d[i - 1].e_hat);
    EXPECT_GT(s2, s1) << "at e_hat = " << d[i].e_hat;
  }
  // ... but NOT from the origin: the slope first falls from the Reissner value 8.
  EXPECT_LT(min_slope, 7.5);
  // Every point is a checked solution that does not cross the plane.
  for (const auto& p : d) {
    EXPECT_LT(p.residual, 1e-7);
    EXPECT_LT(p.offgrid_residual, 1e-6);
    EXPECT_GE(p.min_gap, -1e-9);
  }
  // Small-load end: N ~ 8 e_hat.
  EXPECT_NEAR(d.front().N / d.front().e_hat, 8.0, 0.15);
  // Last point is the clamped-plate buckling point.
  EXPECT_NEAR(d.back().plate_function, 0.0, 1e-9);
}

TEST(ContactDisk, ConvergesWithResolutionAndDomain) {
  sc::SolverOptions base;
  base.a_min = 0.5;
  sc::SolverOptions fine = base;
  fine.resolution = 28;
  sc::SolverOptions longer = base;
  longer.domain_length = 70.0;
  const auto p0 = sc::disk_branch(base, 2.0).back();
  const auto p1 = sc::disk_branch(fine, 2.0).back();
  const auto p2 = sc::disk_branch(longer, 2.0).back();
  EXPECT_NEAR(p0.N, p1.N, 1e-7 * p0.N);
  EXPECT_NEAR(p0.e_hat, p1.e_hat, 1e-7 * p0.e_hat);
  EXPECT_NEAR(p0.N, p2.N, 1e-7 * p0.N);
  EXPECT_NEAR(p0.e_hat, p2.e_hat, 1e-7 * p0.e_hat);
  // A deliberately too short domain is visibly wrong: the far field matters.
  sc::SolverOptions short_domain = base;
  short_domain.domain_length = 4.0;
  const auto p3 = sc::disk_branch(short_domain, 2.0).back();
  EXPECT_GT(std::abs(p3.N - p0.N), 1e-4 * p0.N);
}

TEST(ContactRing, BranchIsCheckedAndAboveThePlane) {
  const auto r = sc::ring_branch();
  ASSERT_GT(r.size(), 10u);
  for (size_t i = 1; i < r.size(); ++i) EXPECT_GT(r[i].a, r[i - 1].a);
  for (const auto& p : r) {
    EXPECT_LT(p.residual, 1e-7);
    EXPECT_LT(p.offgrid_residual, 1e-6);
    EXPECT_GE(p.min_gap, -1e-9);
    EXPECT_GT(p.apex_gap, 0.0);
    EXPECT_GT(p.N, 0.0);
  }
  // Far along the branch N approaches the ridge law n2 a from below.
  const sc::RingPoint big = sc::ring_point(sc::SolverOptions{}, 30.0);
  EXPECT_NEAR(big.N / big.a, kPaperN2, 0.01 * kPaperN2);
  EXPECT_NEAR(big.e_hat, 0.5 * big.a * big.a, 0.05 * big.e_hat);  // e ~ a^2/2
}

TEST(ContactCsv, WritesBothBranchesWithHeader) {
  const std::vector<sc::DiskPoint> d{{0.5, 11.0, 1.5, -0.5}, {1.0, 20.0, 2.6, -0.9}};
  const std::vector<sc::RingPoint> r{{3.0, 72.0, 7.5}};
  std::ostringstream os;
  sc::write_curves_csv(os, d, r);
  std::istringstream is(os.str());
  std::string line;
  std::getline(is, line);
  EXPECT_EQ(line, "branch,a,N,e_hat,c1,residual,min_gap");
  int disk_rows = 0, ring_rows = 0;
  while (std::getline(is, line)) {
    if (line.rfind("disk,", 0) == 0) ++disk_rows;
    if (line.rfind("ring,", 0) == 0) ++ring_rows;
  }
  EXPECT_EQ(disk_rows, 2);
  EXPECT_EQ(ring_rows, 1);
}

}  // namespace
