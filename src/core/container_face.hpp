// The container's rigid bottom face, where the shell is glued to it, as a one-sided obstacle.
//
// In the cap's frame (centre of curvature at the origin, apex on the negative z axis) the rim
// face lies in the cone of polar angle phi about the centre. From the rim face's inner corner
// (s = R - h/2 from the centre) outwards that cone is rigid: the clamped face itself, then the
// acrylic beyond the hole of diameter 2 R sin(phi). No point of the shell may cross it there.
// The container moves along z only: dz is its displacement from the cap's frame. r is the
// distance from the axis; in 3D the normal's radial part points along (x, y) / r.
#pragma once

#include <cmath>

namespace snapjump::core {

struct ContainerFace {
  double cos_phi = 1.0, sin_phi = 0.0;  // of the rim face's polar angle phi
  double s_min = 0.0;  // where the rigid part starts, from the centre of curvature [m]

  // Signed distance of (r, z) into the container (positive: across the face), and the distance
  // along the face from the centre, for a container shifted by dz.
  [[nodiscard]] double gap(double r, double z, double dz) const {
    return r * cos_phi + (z - dz) * sin_phi;
  }
  [[nodiscard]] double along(double r, double z, double dz) const {
    return r * sin_phi - (z - dz) * cos_phi;
  }
  // Whether (r, z) lies across the rigid part of the face.
  [[nodiscard]] bool inside(double r, double z, double dz) const {
    return gap(r, z, dz) > 0.0 && along(r, z, dz) >= s_min;
  }
  // Unit normal into the container in the meridian plane, (cos phi, sin phi).
  [[nodiscard]] double nr() const { return cos_phi; }
  [[nodiscard]] double nz() const { return sin_phi; }
  // The normal speed to take out of a point at (r, z) moving at (vr, vz) so that its step of dt
  // ends on the face (0 when it would end on the shell's side, or over the hole), for the
  // container at dz at the end of the step. Frictionless: the tangential velocity is kept.
  [[nodiscard]] double stop(double r, double z, double vr, double vz, double dt, double dz) const {
    const double re = r + dt * vr, ze = z + dt * vz;
    if (!inside(re, ze, dz)) return 0.0;
    return gap(re, ze, dz) / dt;
  }
};

// The face of a cap of radius R (mid-surface), thickness h and rim angle phi [rad].
inline ContainerFace container_face(double R, double h, double phi) {
  return {std::cos(phi), std::sin(phi), R - 0.5 * h};
}

}  // namespace snapjump::core
