// The dimensionless prefactors alpha_r, alpha_e, alpha_F, alpha_t of the paper's scaling laws,
// bounded by the shell-plane contact problem (see docs/theory.md).
//
// The contact problem is universal in rescaled units (x = r / l, e_hat = sqrt(kappa) e / h,
// N = kappa F R / (E h^3), kappa = 12 (1 - nu^2)); the bounds at a given nu follow from two points
// of it. This file is the one place where those points come from.
#pragma once

#include <string>

namespace snapjump::theory {

// A point of the shell-plane contact problem in rescaled units.
struct ContactPoint {
  double x = 0.0;      // contact radius r / l
  double e_hat = 0.0;  // apex displacement sqrt(kappa) e / h
  double N = 0.0;      // force kappa F R / (E h^3)
};

struct ContactConstants {
  ContactPoint lower;  // ring-to-disk estimate: the disk branch meets the ring law (N-)
  ContactPoint upper;  // end of the disk branch, where the contact disk buckles (N+)
  double n2 = 0.0;     // ring law N = n2 sqrt(e_hat) in the paper's form
  // C in U = C E h^(5/2) d^(3/2) / ((1 - nu^2)^(3/4) R), the stored energy of a mirror-buckled
  // cap whose apex moved by d.
  double mirror_energy_prefactor = 0.0;
  std::string source;  // where these numbers come from, for reports
};

// The constants in force. Until the contact solver lands these are the paper's published values
// (see prefactors.cpp); the solver will replace this single function.
const ContactConstants& contact_constants();

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
