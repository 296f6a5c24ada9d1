// Positions, velocities or forces of a set of points, as structure of arrays: point a is
// (x[a], y[a], z[a]). The mesh's nodes and the MPM particles are both Points.
#pragma once

#include <cstddef>
#include <vector>

namespace snapjump::core {

struct Points {
  std::vector<double> x, y, z;
  [[nodiscard]] std::size_t size() const { return x.size(); }
  void resize(std::size_t n) {
    x.resize(n);
    y.resize(n);
    z.resize(n);
  }
  void push_back(double px, double py, double pz) {
    x.push_back(px);
    y.push_back(py);
    z.push_back(pz);
  }
};

}  // namespace snapjump::core
