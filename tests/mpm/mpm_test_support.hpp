// What the MPM tests share: a force provider that gives none, random particles with random
// velocities and affine matrices, and the shell body as a force provider (hybrid/) under short
// names.
#pragma once

#include <random>
#include <vector>

#include "hybrid/body_forces.hpp"
#include "mpm/stepper.hpp"

namespace snapjump::mpm::testing {

using hybrid::BodyForces;
using hybrid::particles_of;

class NoForces final : public ForceProvider {
 public:
  void forces(const mesh::Points& x, double, mesh::Points& f) override {
    f.x.assign(x.size(), 0.0);
    f.y.assign(x.size(), 0.0);
    f.z.assign(x.size(), 0.0);
  }
};

inline Particles random_particles(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-0.01, 0.01), mass(0.5e-6, 2e-6), vel(-1.0, 1.0);
  mesh::Points x;
  std::vector<double> m;
  for (int i = 0; i < n; ++i) {
    x.push_back(pos(rng), pos(rng), pos(rng) + 0.02);
    m.push_back(mass(rng));
  }
  auto p = Particles::at_rest(x, m);
  for (int i = 0; i < n; ++i) {
    p.v.x[i] = vel(rng);
    p.v.y[i] = vel(rng);
    p.v.z[i] = vel(rng);
    for (int k = 0; k < 9; ++k) p.C[9 * i + k] = 50.0 * vel(rng);
  }
  return p;
}

}  // namespace snapjump::mpm::testing
