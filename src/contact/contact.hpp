// snapjump::contact — axisymmetric shallow-shell contact of a spherical shell pushed by a
// rigid plane (Donnell–Mushtari–Vlasov / Föppl–von Kármán): the universal curves N(e_hat) of
// the disk and ring (mirror-buckled) contact states, the ridge boundary layer n(2), the
// mirror-buckling energy prefactor, and the prefactor bounds alpha_r, alpha_e, alpha_F,
// alpha_t that the paper takes from them.
//
// Problem statement, method, checks and every computed number beside the paper's:
// docs/contact-solver.md.
//
// Rescaled units (nu drops out of the problem):
//   kappa = 12 (1 - nu^2),  l = sqrt(h R) / kappa^(1/4),  W = l^2 / R = h / sqrt(kappa),
//   x = r / l (radius),  e_hat = e / W (displacement of the plane),
//   F = (D / R) N = E h^3 N / (kappa R) (force): the disk law F_disk = E h^3 N_hat(e_hat) /
//   (12 (1 - nu^2) R) of the paper's Eq. S19, N = N_hat.
// Unknowns t(x) (slope of the deflection, theta = (l/R) t) and s(x) (stress function,
// psi = r N_r = (D/l) s); once-integrated equations, L f = f'' + f'/x - f/x^2:
//   L t = s (1 + t/x) + N/(2 pi x) H(x - a),     L s = -(t + t^2/(2x)),
// far field t -> 0, s -> -N/(2 pi x).  e_hat is the displacement of the plane from the
// undeformed apex: x^2/2 + w(x) = e_hat on the contact set and >= e_hat elsewhere, with
// w(x) = -int_x^inf t.
//
// Numerical method: spectral-element Chebyshev collocation on a truncated domain
// [.., a + domain_length] with the far-field conditions imposed at its end, damped Newton
// iteration with Eigen's sparse LU, natural continuation in the contact radius a.  Every
// returned solution carries its checks (discrete residual, ODE residual between collocation
// nodes, non-penetration gap).  Re-entrant; no global state.
#pragma once

#include <iosfwd>
#include <limits>
#include <vector>

namespace snapjump::contact {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct SolverOptions {
  // Length of the truncated outer domain beyond the contact edge (disk, ring) or beyond the
  // ridge crest (boundary layer), in units of l.  Perturbations of the far field decay like
  // exp(-x/sqrt(2)), so 40 leaves a truncation error far below the discretisation error.
  double domain_length = 40.0;
  // Polynomial degree on every spectral element (the convergence knob).
  int resolution = 16;
  // Largest element length in the smooth far field (units of l).
  double element_length = 3.0;
  // Disk branch: first contact radius (the a -> 0 end), geometric steps (ratio
  // small_a_ratio) up to a = 0.5, then steps of da.
  double a_min = 1e-8;
  double small_a_ratio = 2.0;
  double da = 0.05;
  // Ring branch: continuation from ring_a_max downwards in steps of ring_da.
  double ring_a_max = 6.0;
  double ring_da = 0.2;
  // Newton iteration: converged when the full Newton update is below newton_tol (relative,
  // infinity norm).
  double newton_tol = 1e-10;
  int max_newton_iterations = 40;
};

// One point of the disk-contact branch (flat contact disk of radius a).
struct DiskPoint {
  double a;      // contact radius
  double N;      // force
  double e_hat;  // displacement of the plane
  double c1;     // s = x^3/16 + c1 x inside the disk (c1 < 0: compressed disk)
  // Checks of this solution:
  double residual = 0;          // max |discrete residual| (collocation + boundary rows)
  double offgrid_residual = 0;  // max |ODE residual| of the interpolant between the nodes
  double min_gap = 0;           // min over the nodes x >= a of x^2/2 + w(x) - e_hat (>= 0)
  double plate_function = 0;    // clamped_plate_function(a, c1); 0 at the end of the branch
};

// One point of the ring-contact branch (mirror-buckled shell touching along x = a).
struct RingPoint {
  double a;      // ring radius
  double N;      // force
  double e_hat;  // displacement of the plane
  // Checks of this solution:
  double residual = 0;
  double offgrid_residual = 0;
  double min_gap = 0;   // min over all nodes of x^2/2 + w(x) - e_hat (>= 0; = 0 at x = a)
  double apex_gap = 0;  // w(0) - e_hat: height of the inverted apex above the plane (> 0)
};

// Disk branch from a = options.a_min (the a -> 0 end; e_hat = 0.086 at a = 1e-8) to its end, the
// axisymmetric clamped-plate buckling of the compressed contact disk (the last point is that
// end, located to round-off in a).  If a_stop is finite and comes first, the branch is cut at
// a = a_stop instead.  Throws std::runtime_error if a Newton solve does not converge.
[[nodiscard]] std::vector<DiskPoint> disk_branch(
    const SolverOptions& options = {}, double a_stop = std::numeric_limits<double>::infinity());

// Ring branch: mirror-buckled shell touching the plane along the circle x = a, by continuation
// from a = options.ring_a_max (started from the ridge boundary-layer solution) down to a_min.
// Going down, the branch ends where it bifurcates from the disk branch, at the clamped-plate
// buckling point (a_plus, N_plus): there the inverted cap comes down onto the plane
// (apex_gap -> 0).  The step is halved on approach and the branch is returned to within
// ~1e-3 ring_da of that end.  A state is accepted only if Newton converged, N > 0,
// min_gap >= -1e-9 (no penetration) and apex_gap > 1e-6 (a genuine ring state: the disk
// states also solve the ring equations).  Sorted by increasing a.
[[nodiscard]] std::vector<RingPoint> ring_branch(const SolverOptions& options = {},
                                                 double a_min = 0.0);

// One ring state at radius a by Newton iteration started directly from the ridge
// boundary-layer solution (no continuation; meant for large rings, a >~ 4).
// Throws std::runtime_error if Newton does not converge.
[[nodiscard]] RingPoint ring_point(const SolverOptions& options, double a);

// Clamped-plate buckling function of the flat contact disk:
//   theta'' + theta'/x - theta/x^2 - (x^2/16 + c1) theta = 0,  theta(0) = 0,
// regular solution theta = x + c1 x^3/8 + ... (an entire power series, summed exactly),
// returned as theta(a)/a.  Its first zero along the disk branch is the end of the branch (N+).
[[nodiscard]] double clamped_plate_function(double a, double c1);

// Independent check of the same condition: the eigenvalue mu closest to zero of
//   theta'' + theta'/x - theta/x^2 - (x^2/16 + c1) theta = mu theta,  theta(0) = theta(a) = 0,
// by Chebyshev collocation of degree n and inverse iteration.  While the flat disk is stable
// all eigenvalues are negative and this is the top one (mu < 0); mu = 0 at buckling.
[[nodiscard]] double clamped_plate_top_eigenvalue(double a, double c1, int n = 40);

// Ridge boundary layer  phi'' = sigma phi,  sigma'' = (1 - phi^2)/2,
// phi(0) = 0, sigma'(0) = 0, phi(inf) = 1, sigma(inf) = 0 (phi odd, sigma even on the line).
struct RidgeSolution {
  double I = 0;                        // integral over the whole line of phi'^2 + sigma'^2
  double n2 = 0;                       // 3 pi I
  double phi_prime0 = 0;               // phi'(0)
  double sigma0 = 0;                   // sigma(0)
  double hamiltonian0 = 0;             // phi'(0)^2 + sigma(0): first integral, exactly 0
  double residual = 0;                 // discrete residual
  double offgrid_residual = 0;         // ODE residual between the nodes
  std::vector<double> xi, phi, sigma;  // nodal values, xi >= 0
};
[[nodiscard]] RidgeSolution solve_ridge(const SolverOptions& options = {});

struct Constants {
  // Linear (Reissner) limit: dN/de_hat as e_hat -> 0 (closed form 8), from the small-load
  // end of the disk branch (e_hat <= 0.3; a_min = 1e-8 reaches e_hat = 0.086) by a cubic
  // least-squares fit of N/e_hat in e_hat.
  double reissner_slope = kNaN;
  double reissner_fit_spread = kNaN;  // |cubic - quadratic| intercepts

  // End of the disk branch: clamped-plate buckling of the contact disk (paper: N+ = 76.94).
  double N_plus = kNaN, a_plus = kNaN, e_hat_plus = kNaN, c1_plus = kNaN;
  double plate_eigenvalue_at_plus = kNaN;  // clamped_plate_top_eigenvalue(a_plus, c1_plus)

  // Ridge boundary layer: the n(2) of the ring law (paper, Eq. S20; the paper quotes 20.83).
  double ridge_I = kNaN;
  double n2 = kNaN;
  // Independent check of n2: N/a of the full ring branch at a = 20, 30, 40, 60, extrapolated
  // to a -> infinity by a cubic in 1/a.
  double n2_ring_extrapolated = kNaN;

  // Lower bound as the paper constructs it: the disk branch meets the ring law written with
  // e = r^2/R, i.e. N = n2 sqrt(e_hat) (paper, Eq. S21; N- = 46.8 there).  a_minus is the DISK
  // contact radius there; ring_radius_minus = sqrt(e_hat_minus) the ring radius that law assigns.
  double N_minus = kNaN, a_minus = kNaN, e_hat_minus = kNaN, c1_minus = kNaN;
  double ring_radius_minus = kNaN;
  // The same crossing with the paper's rounded n2 = 20.83 instead of the computed n2.
  double N_minus_paper_n2 = kNaN, a_minus_paper_n2 = kNaN, e_hat_minus_paper_n2 = kNaN;
  // The same construction with the ring law in the geometry of the reference note (plane
  // displacement e_hat = a^2/2, N = n2 sqrt(2 e_hat)).  max_disk_over_note_law is the max
  // over the disk branch of N_disk / (n2 sqrt(2 e_hat)); if it is < 1 the curves do not cross
  // before N+ and the *_note fields stay NaN.
  double N_minus_note = kNaN, a_minus_note = kNaN, e_hat_minus_note = kNaN;
  double max_disk_over_note_law = kNaN;
  // The paper's alpha_e upper bound is reproduced by the ring-law displacement at force N+:
  // e_hat = (N+/n2)^2 (kept for the comparison in docs/contact-solver.md).
  double e_hat_ring_law_at_plus = kNaN;

  // The computed ring branch (mirror-buckled states of the full problem).  It bifurcates from
  // the disk branch at the clamped-plate buckling point; ring_*_end is the last ring state
  // found on the way down and must agree with a_plus, N_plus, e_hat_plus.
  double ring_a_end = kNaN, ring_N_end = kNaN, ring_e_hat_end = kNaN;
  // Lowest force on the ring branch (force-controlled ring -> disk limit in this model) and
  // the fold of the ring branch in e_hat (displacement-controlled limit), refined by
  // successive parabolas through solves at spacing 0.05, 0.01, 0.002 in a.
  double ring_N_min = kNaN, ring_a_at_N_min = kNaN, ring_e_hat_at_N_min = kNaN;
  double ring_e_hat_min = kNaN, ring_a_at_e_hat_min = kNaN, ring_N_at_e_hat_min = kNaN;

  // Shape of the disk branch: N(e_hat) is increasing; its slope dN/de_hat starts at 8,
  // DEcreases to disk_min_slope at the inflection point e_hat = disk_e_hat_inflection and
  // increases after it (finite differences between branch points; ~1e-2 accurate).
  double disk_min_slope = kNaN, disk_e_hat_inflection = kNaN;

  // Mirror-buckled cap energy U = C E h^(5/2) d^(3/2) / ((1 - nu^2)^(3/4) R), from the ridge:
  // U = pi a^3 I in units of (D/R) W.
  // CONVENTION: d is the APEX displacement of the mirror-buckled cap, d = r^2/R (the depth of
  // the inverted apex below the undeformed apex, i.e. twice the cap height r^2/(2R)).  This is
  // the e = r^2/R of the paper's rewritten F_ring and the usual Pogorelov dimple depth; with it
  // C = pi I / 12^(3/4).
  double mirror_energy_prefactor = kNaN;
  // The same energy written with the cap height H = r^2/(2R) = R(1 - cos phi) (the plane
  // displacement of the ring state) instead of d: C_H = 2^(3/2) C.
  double mirror_energy_prefactor_cap_height = kNaN;

  // Checks (worst values over every solution used above).
  double max_residual = kNaN;          // discrete residuals (disk, ring, ridge)
  double max_offgrid_residual = kNaN;  // ODE residual between collocation nodes
  double min_disk_gap = kNaN;          // non-penetration on the disk branch (>= -1e-9)
  double min_ring_gap = kNaN;          // non-penetration on the ring branch (>= -1e-9)
  double min_ring_apex_gap = kNaN;     // smallest w(0) - e_hat on the ring branch (> 0)
  // Convergence: changes of the headline numbers when the polynomial degree is raised by 8 and
  // when the domain is made 1.5x longer (filled only when compute_constants is asked to).
  double dN_plus_resolution = kNaN, dN_plus_domain = kNaN;
  double dN_minus_resolution = kNaN, dN_minus_domain = kNaN;
  double de_hat_plus_resolution = kNaN, de_hat_plus_domain = kNaN;
  double dn2_resolution = kNaN, dn2_domain = kNaN;
  double dreissner_resolution = kNaN, dreissner_domain = kNaN;
  double dring_N_min_resolution = kNaN, dring_N_min_domain = kNaN;
};

// Computes everything above (nu-independent universal numbers).  With check_convergence the
// core computation is repeated at resolution + 8 and at 1.5 x domain_length and the changes are
// stored in the d*_resolution / d*_domain fields.  Throws std::runtime_error on a failed solve.
[[nodiscard]] Constants compute_constants(const SolverOptions& options = {},
                                          bool check_convergence = false);

// The prefactor bounds that follow from these numbers at a given nu are computed by
// theory::prefactor_bounds (src/theory/prefactors.hpp), from theory::from_solver(constants).

// CSV, header "branch,a,N,e_hat,c1,residual,min_gap" then one line per point ("disk" then
// "ring" rows); c1 is empty on ring rows.  Rescaled units.
void write_curves_csv(std::ostream& os, const std::vector<DiskPoint>& disk,
                      const std::vector<RingPoint>& ring);

}  // namespace snapjump::contact
