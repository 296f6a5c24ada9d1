// Inverse design: from targets for a jump (height, force, margin, stored energy, t*) and the
// constraints of a build (material, payload, footprint, thinnest wall, the pump's suction) to the
// spherical caps (R, h) that meet them by the theory's closed forms, taking the prefactors'
// LOWER bounds (their upper ones for a ceiling) so that their uncertainty cannot make a design
// fail (docs/design.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "theory/scaling.hpp"

namespace snapjump::theory {

// A quantity's target: at least `lo`, and at most `hi` when given.
struct Target {
  double lo = 0.0;
  std::optional<double> hi;
};

struct DesignTargets {
  std::optional<Target> H;       // jump height [m]
  std::optional<Target> F_star;  // peak force of the snap [N]
  double margin = 1.0;           // F* / mg at least this (1: the theory's Jump)
  std::optional<double> energy;  // stored energy of the inverted shell at least this [J]
  std::optional<double> t_star;  // t* (onset to launch) at most this [s]
};

// The build: the base case gives the material, phi, the protocol and the apparatus; these bound
// the search.
struct DesignSpace {
  // The net weight: fixed (lo == hi) or searched in a range [N].
  double net_weight_lo = 0.0, net_weight_hi = 0.0;
  double max_footprint = 0.1;  // the rim's diameter 2 R sin(phi) at most [m]
  double min_h = 0.5e-3;       // the thinnest wall that can be cast [m]
  double min_R = 5e-3;         // the smallest shell radius searched [m]
  // The thickest shell searched, h / R: the paper's fabricated shells reach 0.1 (25, 2.5) mm,
  // and the thin-shell theory is least to be trusted beyond what it was checked on; at most 0.18
  // (about 0.19 the theory's range ends, Prediction::beyond_range).
  double max_h_over_R = 0.1;
  // Zoelly's p_c at most this: the pump must buckle the shell [Pa]; absent: no limit.
  std::optional<double> max_suction;
  int grid = 160;  // points per searched dimension (log-spaced)
};

enum class Rank { Smallest, Lightest, Margin, Highest };
// "smallest", "lightest", "margin", "highest" (H's lower bound).
std::optional<Rank> parse_rank(const std::string& s);
std::string to_string(Rank r);

struct Design {
  double R = 0.0, h = 0.0, net_weight = 0.0;
  Prediction prediction;
  double footprint = 0.0;  // 2 R sin(phi) [m]
  // The smallest relative slack over the targets and constraints: >= 0 when all are met.
  double slack = 0.0;
  std::string binding;  // the target or constraint of that smallest slack
};

// One searched design in the paper's Fig. 3(c) plane, for the design figure.
struct DesignPoint {
  double h_over_R = 0.0;
  double load = 0.0;     // E h^2 / mg
  double H_lower = 0.0;  // H's lower bound [m]
  bool feasible = false;
};

struct DesignResult {
  std::vector<Design> designs;  // feasible, ranked, near-duplicates thinned
  // When nothing is feasible: the design closest to it, and in words which constraint binds
  // there and by how much.
  std::optional<Design> closest;
  std::string infeasible;
  // Feasible designs no other beats in both footprint (smaller) and H's lower bound (larger).
  std::vector<Design> pareto;
  long evaluated = 0;               // how many designs the search predicted
  std::vector<DesignPoint> points;  // every searched design within the theory's range
};

// The case of one design: the base with shell.R, shell.h and popper.net_weight replaced (and the
// popper's mass as the case's rule gives it, when the base did not set it).
config::Case design_case(const config::Case& base, double R, double h, double net_weight);

// Searches a log-spaced grid over R (min_R to the footprint's), h (min_h to max_h_over_R R) and,
// when it is a range, the net weight; returns the best `count` designs. Throws config::CaseError
// for a search space that makes no sense (bounds inverted, negative).
DesignResult design(const config::Case& base, const DesignTargets& targets,
                    const DesignSpace& space, Rank rank, int count);

}  // namespace snapjump::theory
