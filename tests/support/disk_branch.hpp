// The contact solver's disk branch (a spherical shell pressed by a plane, shallow-shell theory)
// in physical units, for the checks of both discretisations against it.
#pragma once

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "contact/contact.hpp"

namespace snapjump::test_support {

// F(e) [N] of the cap (R, h, E, nu) at indentation e [m], by linear interpolation along the
// branch: F = (D / R) N, e = e_hat h / sqrt(kappa), kappa = 12 (1 - nu^2), D = E h^3 / kappa.
// NaN beyond the branch's end, 0 for e <= 0.
class DiskBranchForce {
 public:
  DiskBranchForce(double R, double h, double E, double nu) {
    const double kappa = 12.0 * (1.0 - nu * nu);
    const double D = E * h * h * h / kappa;
    for (const auto& p : contact::disk_branch()) {
      points_.emplace_back(p.e_hat * h / std::sqrt(kappa), D / R * p.N);
    }
  }
  double operator()(double e) const {
    if (e <= 0.0) return 0.0;
    for (std::size_t i = 1; i < points_.size(); ++i) {
      if (points_[i].first >= e) {
        const auto [e0, f0] = points_[i - 1];
        const auto [e1, f1] = points_[i];
        return f0 + (f1 - f0) * (e - e0) / (e1 - e0);
      }
    }
    return std::numeric_limits<double>::quiet_NaN();
  }

 private:
  std::vector<std::pair<double, double>> points_;  // (e, F)
};

}  // namespace snapjump::test_support
