#include "theory/prefactors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "contact/contact.hpp"

namespace snapjump::theory {

// The paper's supplement quotes N+ = 76.94, N- = 46.8 and n(2) = 20.83, and at nu = 1/2
// (kappa = 9) the ranges 1.2 < alpha_r < 1.6 and 1.8 < alpha_e < 4.5. The contact radius and
// apex displacement of the two points are not quoted; they are recovered here from those ranges
// (x = alpha_r kappa^(1/4), e_hat = alpha_e sqrt(kappa) at kappa = 9), so that converting back at
// nu = 1/2 returns the paper's alpha_r and alpha_e. alpha_F follows from N: 46.8 / 9 = 5.2 and
// 76.94 / 9 = 8.55, where the paper rounds to 5.3 and 8.5.
//
// Mirror-buckling energy: the paper gives no prefactor; the ridge energy U = pi a^3 I with the
// paper's n2 = 3 pi I, written with the cap height, gives C = 2^(3/2) n2 / (3 12^(3/4)).
ContactConstants paper_constants() {
  constexpr double kappa_half = 9.0;  // kappa at nu = 1/2
  const double quarter = std::pow(kappa_half, 0.25);
  const double half = std::sqrt(kappa_half);
  ContactConstants c;
  c.lower = ContactPoint{1.2 * quarter, 1.8 * half, 46.8};
  c.upper = ContactPoint{1.6 * quarter, 4.5 * half, 76.94};
  c.n2 = 20.83;
  c.mirror_energy_prefactor = std::pow(2.0, 1.5) * c.n2 / (3.0 * std::pow(12.0, 0.75));
  c.source =
      "paper's published constants (N+ = 76.94, N- = 46.8, n(2) = 20.83; contact radius and "
      "apex displacement from its nu = 1/2 ranges)";
  return c;
}

ContactConstants from_solver(const contact::Constants& s) {
  ContactConstants c;
  c.lower = ContactPoint{s.a_minus, s.e_hat_minus, s.N_minus};
  c.upper = ContactPoint{s.a_plus, s.e_hat_ring_law_at_plus, s.N_plus};
  c.n2 = s.n2;
  c.mirror_energy_prefactor = s.mirror_energy_prefactor_cap_height;
  c.source = fmt::format(
      "shell-plane contact solver: N+ = {:.4f}, N- = {:.4f}, n(2) = {:.4f} (snapjump contact)",
      s.N_plus, s.N_minus, s.n2);
  return c;
}

const ContactConstants& contact_constants() {
  static const ContactConstants constants = from_solver(contact::compute_constants());
  return constants;
}

double kappa(double nu) { return 12.0 * (1.0 - nu * nu); }

Prefactors prefactor_bounds(const ContactConstants& c, double nu) {
  const double k = kappa(nu);
  const double quarter = std::pow(k, 0.25);
  const double half = std::sqrt(k);
  const auto ordered = [](double a, double b) { return Range{std::min(a, b), std::max(a, b)}; };
  const auto alpha_t = [&](const ContactPoint& p) {
    return std::sqrt(3.0 * (p.e_hat / half) / (p.N / k));
  };
  Prefactors p;
  p.alpha_r = ordered(c.lower.x / quarter, c.upper.x / quarter);
  p.alpha_e = ordered(c.lower.e_hat / half, c.upper.e_hat / half);
  p.alpha_F = ordered(c.lower.N / k, c.upper.N / k);
  p.alpha_t = ordered(alpha_t(c.lower), alpha_t(c.upper));
  return p;
}

}  // namespace snapjump::theory
