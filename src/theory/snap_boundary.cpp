#include "theory/snap_boundary.hpp"

#include <cmath>

#include "theory/scaling.hpp"

namespace snapjump::theory {

std::optional<double> snap_boundary_weight(config::Case c, SnapMarginEnd end,
                                           const ContactConstants& constants) {
  const auto margin = [&](double mg) {
    c.popper.net_weight = mg;
    const auto p = predict(c, constants);
    return end == SnapMarginEnd::Lower ? p.snap_margin.lo : p.snap_margin.hi;
  };
  double a = c.popper.net_weight > 0.0 ? c.popper.net_weight : 1.0;
  double b = a;
  for (int i = 0; i < 60 && !(margin(a) > 1.0); ++i) a /= 10.0;
  for (int i = 0; i < 60 && !(margin(b) < 1.0); ++i) b *= 10.0;
  if (!(margin(a) > 1.0) || !(margin(b) < 1.0)) return std::nullopt;
  for (int i = 0; i < 200 && b / a > 1.0 + 1e-12; ++i) {
    const double m = std::sqrt(a * b);
    (margin(m) > 1.0 ? a : b) = m;
  }
  return std::sqrt(a * b);
}

}  // namespace snapjump::theory
