// The dimensionless prefactors alpha_r, alpha_e, alpha_F, alpha_t of the paper's scaling laws,
// bounded by the shell-plane contact problem (see docs/theory.md).
//
// The contact problem is universal in rescaled units (x = r / l, e_hat = sqrt(kappa) e / h,
// N = kappa F R / (E h^3), kappa = 12 (1 - nu^2)); the bounds at a given nu follow from two points
// of it. This file is the one place where those points come from.
#pragma once

#include <string>

namespace snapjump::contact {
struct Constants;
}

namespace snapjump::theory {

// A point of the shell-plane contact problem in rescaled units.
struct ContactPoint {
  double x = 0.0;      // contact radius r / l
  double e_hat = 0.0;  // apex displacement sqrt(kappa) e / h
  double N = 0.0;      // force kappa F R / (E h^3)
};

struct ContactConstants {
  // ring-to-disk estimate: the disk branch (paper, Eq. S19) meets the ring law (paper, Eq. S21),
  // N-
  ContactPoint lower;
  ContactPoint upper;  // the disk instability N+ (contact radius of the disk there; apex
                       // displacement of the ring state that carries N+, see docs/theory.md)
  // ring law N = n2 sqrt(e_hat): the paper's Eq. S21 in rescaled units (Eq. S20 with r = sqrt(e R))
  double n2 = 0.0;
  // C in U = C E h^(5/2) H^(3/2) / ((1 - nu^2)^(3/4) R), the stored energy of a mirror-buckled
  // cap of height H (for the fully inverted cap, H = R (1 - cos phi)).
  double mirror_energy_prefactor = 0.0;
  std::string source;  // where these numbers come from, for reports
};

// The constants in force: computed once per process by the shell-plane contact solver
// (about a second) and kept.
const ContactConstants& contact_constants();

// The mapping from the solver's numbers to the two bounding points. The lower point is the
// crossing of the disk branch with the paper's ring law (x = disk contact radius there); the
// upper point takes N+ and the disk contact radius at N+, and the apex displacement that the
// ring law assigns to the force N+, e_hat = (N+ / n2)^2, which is how the paper's range
// 1.8 < alpha_e < 4.5 arises (the disk branch itself ends at e_hat = 7.46).
ContactConstants from_solver(const contact::Constants& c);

// The paper's published constants (N+ = 76.94, N- = 46.8, n(2) = 20.83, with the contact
// radius and displacement recovered from its nu = 1/2 ranges), for comparison.
ContactConstants paper_constants();

struct Range {
  double lo = 0.0;
  double hi = 0.0;
};

struct Prefactors {
  Range alpha_r;  // r* / sqrt(h R)
  Range alpha_e;  // e* / h
  Range alpha_F;  // F* / (E h^3 / R)
  Range alpha_t;  // t* / sqrt(m R / (E h^2)), alpha_t = sqrt(3 alpha_e / alpha_F)
};

// kappa = 12 (1 - nu^2)
double kappa(double nu);

// alpha_r = x / kappa^(1/4), alpha_e = e_hat / sqrt(kappa), alpha_F = N / kappa at the two points;
// each range is ordered (lo <= hi).
Prefactors prefactor_bounds(const ContactConstants& c, double nu);

}  // namespace snapjump::theory
