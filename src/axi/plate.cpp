#include "axi/plate.hpp"

#include <algorithm>
#include <cmath>

namespace snapjump::axi {

void PlateRule::begin_step() {
  std::fill(loaded_.begin(), loaded_.end(), 0);
  impulse_ = 0.0;
}

void PlateRule::apply(std::size_t a, double m, double z, double& vr, double& vz, double dt) {
  if (!(z + dt * vz < 0.0)) return;
  const double landing = -z / dt;
  const double jn = m * (landing - vz);
  vz = landing;
  const double jt = mu_ * jn;
  const double pr = m * vr;
  vr = std::abs(pr) <= jt ? 0.0 : vr - std::copysign(jt, pr) * (1.0 / m);
  impulse_ += jn;
  loaded_[a] = 1;
}

}  // namespace snapjump::axi
