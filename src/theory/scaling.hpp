// Closed-form theory of the paper: cap geometry, Zoelly's buckling pressure, the scales
// r_c, e_c, F_c, t_c, the characteristic quantities r*, e*, F*, t*, the heights H_l, H_s, H and
// the predicted outcome (Jump / Snap / No snap). Everything in SI.
#pragma once

#include <string>

#include "config/case.hpp"
#include "theory/prefactors.hpp"

namespace snapjump::theory {

// --- Spherical cap of mid-surface radius R, thickness h, rim polar angle phi ---------------------
double rim_radius(double R, double phi);              // R sin(phi)
double cap_depth(double R, double phi);               // R (1 - cos(phi))
double shell_volume(double R, double h, double phi);  // material volume, radial rim cut
double shell_mass(double R, double h, double phi, double rho);
// Volume between the inner surface (radius R - h/2) and the plane of its rim circle.
double cavity_volume(double R, double h, double phi);

// --- Classical shell results ------------------------------------------------------------------
// Zoelly: p_c = 2 E h^2 / (R^2 sqrt(3 (1 - nu^2))).
double zoelly_pressure(double E, double h, double R, double nu);
// Reissner's point-load stiffness of a spherical shell: F / e = 4 E h^2 / (R sqrt(3 (1 - nu^2))).
double reissner_stiffness(double E, double h, double R, double nu);

// --- Scales of the paper ----------------------------------------------------------------------
// From the text before the paper's Eq. 1 (r_c, e_c, F_c) and after it (t_c, alpha_t), unnumbered.
double r_c(double h, double R);                      // sqrt(h R)
double e_c(double h);                                // h
double F_c(double E, double h, double R);            // E h^3 / R
double t_c(double m, double E, double h, double R);  // sqrt(m R / (E h^2))
double alpha_t(double alpha_e, double alpha_F);      // sqrt(3 alpha_e / alpha_F)

// H_l = R (1 - cos phi) - alpha_e h: lift of the container up to the contact transition (paper,
// Eq. 2).
double lifting_height(double R, double phi, double h, double alpha_e);
// H_s = alpha_F alpha_e E h^4 / (m g R): flight height from the snap, m g the net weight (paper,
// Eq. 3, with alpha_H = alpha_F alpha_e).
double snap_height(double alpha_F, double alpha_e, double E, double h, double net_weight, double R);
// Stored energy of the mirror-buckled cap, U = C E h^(5/2) d^(3/2) / ((1 - nu^2)^(3/4) R).
double mirror_energy(double C, double E, double h, double d, double nu, double R);

// --- The prediction for one case ---------------------------------------------------------------
// Thrown is observed only, never predicted: the popper left the plate and flew without the snap on
// the plate (docs/analysis.md, "Outcome").
enum class Outcome { Jump, Snap, NoSnap, Thrown };
std::string to_string(Outcome o);  // "Jump", "Snap", "No snap", "Thrown"

// Which outcomes the theory allows within its prefactor bounds.
struct OutcomeSet {
  bool jump = false;
  bool snap = false;
  bool no_snap = false;
  [[nodiscard]] bool certain() const {
    return (jump ? 1 : 0) + (snap ? 1 : 0) + (no_snap ? 1 : 0) == 1;
  }
  [[nodiscard]] std::string text() const;  // "Jump", "Jump or Snap", ...
};

struct Prediction {
  // geometry
  double rim_radius = 0.0, cap_depth = 0.0, shell_volume = 0.0, shell_mass = 0.0;
  double cavity_volume = 0.0;
  // loads
  // The apparatus: the popper's own mass, the counterweight and their sum, the inertia m that
  // enters t_c (a rigid wire: the plate's force accelerates both).
  double net_weight = 0.0, popper_mass = 0.0, counterweight = 0.0, moving_mass = 0.0;
  double zoelly_pc = 0.0, delta_p_j = 0.0;
  // scales
  double r_c = 0.0, e_c = 0.0, F_c = 0.0, t_c = 0.0;
  // prefactors and the quantities they bound: r*, e*, F* (paper, Eq. 1), t* = alpha_t t_c,
  // H_l (paper, Eq. 2), H_s (paper, Eq. 3), H = H_l + H_s
  Prefactors alpha;
  Range r_star, e_star, F_star, t_star, H_l, H_s, H;
  // outcome criteria
  double inverted_energy = 0.0;  // U of the fully inverted shell, apex displacement R(1-cos phi)
  Range jump_margin;             // F* / mg; Jump needs > 1
  Range snap_margin;             // U / (mg H_l); No snap when < 1
  OutcomeSet outcome;
  std::string constants_source;
  // Where the case leaves the theory's range, in words; empty inside it. Beyond it the ends of
  // the ranges that rest on the broken assumption are NaN (no value), and the outcome is unknown
  // (no outcome in `outcome`).
  std::string beyond_range;
  // The outcome as reports write it: outcome.text(), or "unknown: " and beyond_range.
  [[nodiscard]] std::string outcome_text() const;
};

Prediction predict(const config::Case& c, const ContactConstants& constants);

// delta_p_j in Pa: as given, or delta_p_j_over_pc times Zoelly's p_c of the case.
double jump_pressure(const config::Case& c);

}  // namespace snapjump::theory
