#include "theory/scaling.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace snapjump::theory {

double rim_radius(double R, double phi) { return R * std::sin(phi); }

double cap_depth(double R, double phi) { return R * (1.0 - std::cos(phi)); }

double shell_volume(double R, double h, double phi) {
  const double outer = R + 0.5 * h;
  const double inner = R - 0.5 * h;
  return 2.0 * std::numbers::pi / 3.0 * (outer * outer * outer - inner * inner * inner) *
         (1.0 - std::cos(phi));
}

double shell_mass(double R, double h, double phi, double rho) {
  return rho * shell_volume(R, h, phi);
}

double cavity_volume(double R, double h, double phi) {
  const double Ri = R - 0.5 * h;
  const double d = Ri * (1.0 - std::cos(phi));
  return std::numbers::pi * d * d * (3.0 * Ri - d) / 3.0;
}

double zoelly_pressure(double E, double h, double R, double nu) {
  return 2.0 * E * h * h / (R * R * std::sqrt(3.0 * (1.0 - nu * nu)));
}

double reissner_stiffness(double E, double h, double R, double nu) {
  return 4.0 * E * h * h / (R * std::sqrt(3.0 * (1.0 - nu * nu)));
}

double r_c(double h, double R) { return std::sqrt(h * R); }
double e_c(double h) { return h; }
double F_c(double E, double h, double R) { return E * h * h * h / R; }
double t_c(double m, double E, double h, double R) { return std::sqrt(m * R / (E * h * h)); }
double alpha_t(double alpha_e, double alpha_F) { return std::sqrt(3.0 * alpha_e / alpha_F); }

double lifting_height(double R, double phi, double h, double alpha_e) {
  return cap_depth(R, phi) - alpha_e * h;
}

double snap_height(double alpha_F, double alpha_e, double E, double h, double net_weight,
                   double R) {
  return alpha_F * alpha_e * E * h * h * h * h / (net_weight * R);
}

double mirror_energy(double C, double E, double h, double d, double nu, double R) {
  return C * E * std::pow(h, 2.5) * std::pow(d, 1.5) / (std::pow(1.0 - nu * nu, 0.75) * R);
}

std::string to_string(Outcome o) {
  switch (o) {
    case Outcome::Jump:
      return "Jump";
    case Outcome::Snap:
      return "Snap";
    case Outcome::NoSnap:
      return "No snap";
    case Outcome::Thrown:
      return "Thrown";
  }
  return "?";
}

std::string OutcomeSet::text() const {
  std::string out;
  const auto add = [&](bool on, Outcome o) {
    if (!on) return;
    if (!out.empty()) out += " or ";
    out += to_string(o);
  };
  add(jump, Outcome::Jump);
  add(snap, Outcome::Snap);
  add(no_snap, Outcome::NoSnap);
  return out;
}

double jump_pressure(const config::Case& c) {
  if (c.protocol.delta_p_j) return *c.protocol.delta_p_j;
  return c.protocol.delta_p_j_over_pc *
         zoelly_pressure(c.material.E, c.shell.h, c.shell.R, c.material.nu);
}

namespace {

// Why the case lies beyond the contact theory, whose plate indents the cap by less than its
// depth, when e* = alpha_e h can reach the depth R (1 - cos phi) and H_l has no lower end (h / R
// above (1 - cos phi) / alpha_e at the upper bound); empty where H_l has both.
std::string depth_exceeded(const Prediction& p, double h_over_R, double phi) {
  if (!std::isnan(p.H_l.lo)) return {};
  return fmt::format(
      "the indentation at the onset, e* = alpha_e h, reaches {:.3g} mm, past the cap's depth "
      "R (1 - cos phi) = {:.3g} mm: the contact theory holds while the plate indents the cap by "
      "less than its depth (at phi = {:.3g} deg for h / R below {:.3g}; this case has {:.3g}), so "
      "H_l = depth - e*, H and U / (mg H_l) have no value there",
      1e3 * p.e_star.hi, 1e3 * p.cap_depth, phi * 180.0 / std::numbers::pi,
      h_over_R * p.cap_depth / p.e_star.hi, h_over_R);
}

}  // namespace

Prediction predict(const config::Case& c, const ContactConstants& constants) {
  const double R = c.shell.R, h = c.shell.h, phi = c.shell.phi;
  const double E = c.material.E, nu = c.material.nu;
  const double mg = c.popper.net_weight;
  Prediction p;
  p.constants_source = constants.source;
  p.rim_radius = rim_radius(R, phi);
  p.cap_depth = cap_depth(R, phi);
  p.shell_volume = shell_volume(R, h, phi);
  p.shell_mass = shell_mass(R, h, phi, c.material.rho);
  p.cavity_volume = cavity_volume(R, h, phi);
  p.net_weight = mg;
  p.popper_mass = c.popper.mass;
  p.counterweight = c.popper.counterweight();
  p.moving_mass = c.popper.moving_mass();
  p.zoelly_pc = zoelly_pressure(E, h, R, nu);
  p.delta_p_j = jump_pressure(c);

  p.r_c = r_c(h, R);
  p.e_c = e_c(h);
  p.F_c = F_c(E, h, R);
  p.t_c = t_c(p.moving_mass, E, h, R);

  const auto& a = p.alpha = prefactor_bounds(constants, nu);
  // r* = alpha_r r_c, e* = alpha_e h, F* = alpha_F F_c (paper, Eq. 1); t* = alpha_t t_c.
  p.r_star = {a.alpha_r.lo * p.r_c, a.alpha_r.hi * p.r_c};
  p.e_star = {a.alpha_e.lo * p.e_c, a.alpha_e.hi * p.e_c};
  p.F_star = {a.alpha_F.lo * p.F_c, a.alpha_F.hi * p.F_c};
  p.t_star = {a.alpha_t.lo * p.t_c, a.alpha_t.hi * p.t_c};
  // H_l falls and H_s rises with the prefactors; each end takes the extremes independently. The
  // contact theory indents the cap by less than its depth: an end where e* reaches the depth is
  // no lift at all, NaN, and the outcome unknown.
  const auto lift = [&](double alpha_e) {
    const double Hl = lifting_height(R, phi, h, alpha_e);
    return Hl > 0.0 ? Hl : std::numeric_limits<double>::quiet_NaN();
  };
  p.H_l = {lift(a.alpha_e.hi), lift(a.alpha_e.lo)};
  p.beyond_range = depth_exceeded(p, h / R, phi);
  p.H_s = {snap_height(a.alpha_F.lo, a.alpha_e.lo, E, h, mg, R),
           snap_height(a.alpha_F.hi, a.alpha_e.hi, E, h, mg, R)};
  p.H = {p.H_l.lo + p.H_s.lo, p.H_l.hi + p.H_s.hi};

  // Jump: the impulsive force must exceed the net weight.
  p.jump_margin = {p.F_star.lo / mg, p.F_star.hi / mg};
  // Snap: the fully inverted shell must store enough energy to lift the popper by H_l.
  p.inverted_energy = mirror_energy(constants.mirror_energy_prefactor, E, h, p.cap_depth, nu, R);
  p.snap_margin = {p.inverted_energy / (mg * p.H_l.hi), p.inverted_energy / (mg * p.H_l.lo)};
  if (!p.beyond_range.empty()) return p;

  const bool can_snap = p.snap_margin.hi >= 1.0;
  const bool can_fail_to_snap = p.snap_margin.lo < 1.0;
  p.outcome.no_snap = can_fail_to_snap;
  if (can_snap) {
    p.outcome.jump = p.jump_margin.hi > 1.0;
    p.outcome.snap = p.jump_margin.lo <= 1.0;
  }
  return p;
}

std::string Prediction::outcome_text() const {
  return beyond_range.empty() ? outcome.text() : "unknown: " + beyond_range;
}

}  // namespace snapjump::theory
