// One vertical degree of freedom: the container that the rim is glued to. Shared by the
// discretisations of the shell (the MPM grid's clamp and the axisymmetric model's).
#pragma once

namespace snapjump::core {

struct RigidBody {
  double mass = 0.0;           // [kg]
  double z = 0.0;              // height of its reference point [m]
  double vz = 0.0;             // [m/s]
  double applied_force = 0.0;  // forces other than the clamp (weight share, gas) [N]
  double clamp_force = 0.0;    // force of the shell on the body in the last step [N]
  // Advances the body over dt with the applied force and the last clamp reaction.
  void advance(double dt) {
    vz += dt * (applied_force + clamp_force) / mass;
    z += dt * vz;
  }
};

}  // namespace snapjump::core
