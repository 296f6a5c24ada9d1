// The rigid plate z = 0 under the axisymmetric shell, acting exactly on the outer surface's nodes
// (no grid, no standoff): the axisymmetric counterpart of the 3D model's mpm::PlateRule.
//
// A node whose step would take it below z = 0 lands on it at the end of the step; the normal
// impulse that stops it is the plate's reaction, and Coulomb friction takes up to mu times that
// impulse from the node's radial momentum, never reversing it. The plate's force is the sum of the
// normal impulses over the step, divided by the step.
#pragma once

#include <cstddef>
#include <vector>

namespace snapjump::axi {

class PlateRule {
 public:
  // nodes: how many nodes the body has; mu: the Coulomb coefficient.
  PlateRule(std::size_t nodes, double mu) : mu_(mu), loaded_(nodes, 0) {}

  void begin_step();
  // Node a of mass m at height z, with the velocity (vr, vz) it would end this step of length dt
  // with: where the step would take it below the plate, the velocity is changed so that it lands
  // on it (z + dt vz = 0) and the impulse is counted.
  void apply(std::size_t a, double m, double z, double& vr, double& vz, double dt);
  void end_step(double dt) { force_ = impulse_ / dt; }

  // The reaction on the shell in the last step (up is positive) [N], and whether it pushed node a.
  [[nodiscard]] double force() const { return force_; }
  [[nodiscard]] bool loaded(std::size_t a) const { return loaded_[a] != 0; }

 private:
  double mu_;
  std::vector<char> loaded_;
  double impulse_ = 0.0;  // normal, summed over this step's nodes [N s]
  double force_ = 0.0;
};

}  // namespace snapjump::axi
