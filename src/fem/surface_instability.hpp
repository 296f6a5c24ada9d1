// Biot's surface instability: the compression at which the flat free surface of a homogeneously
// strained half-space of a material stops being stable against small wrinkles (M. A. Biot,
// Appl. Sci. Res. A 12, 168 (1963)). For the incompressible neo-Hookean solid under plane strain
// the stretch along the surface is then 0.5437 (a compression of 0.456), the ratio of the normal
// stretch to it 3.383, whatever the stretch along the third axis. A crease, the large-amplitude
// fold the same surface forms, sets in earlier (a ratio of 2.4 for that solid: W. Hong, X. Zhao
// and Z. Suo, Appl. Phys. Lett. 95, 111901 (2009)); it has no small-amplitude precursor, so
// Biot's value is the point past which a smooth compressed surface cannot be had at all.
//
// The half-space x2 < 0, principal stretches lambda_1 along its surface (compressed), lambda_2
// normal to it (free: the normal Cauchy stress vanishes) and lambda_3 along the third axis, held
// fixed; an incremental displacement exp(i k x1 + k q x2) in the (x1, x2) plane. The material's
// instantaneous moduli (R. W. Ogden, Non-linear Elastic Deformations, 1984, Sec. 6.1) come from
// the derivatives of its strain energy in the principal stretches (fem::first_piola_stress, the
// second derivatives by central differences of it); incremental equilibrium gives two decaying
// exponents q, and the incremental traction on the surface vanishes for some mode where the 2 x 2
// determinant of the two exponents' tractions does. That determinant is odd under swapping the
// exponents; over their difference it is real, whether they are real or complex conjugates.
#pragma once

#include "fem/body.hpp"

namespace snapjump::fem {

// The ratio of the normal to the tangential stretch at which an incompressible neo-Hookean
// surface creases (Hong, Zhao and Suo 2009, above).
inline constexpr double kNeoHookeanCreaseRatio = 2.4;

struct SurfaceInstability {
  double tangential = 0.0;  // the stretch along the surface at the instability
  double normal = 0.0;      // the free surface's normal stretch there
  double ratio = 0.0;       // normal / tangential
};

// The instability of a free surface of m compressed along itself with the stretch along the third
// axis held at third_stretch. Throws std::runtime_error where the surface stays stable down to a
// stretch of 0.2 along it.
SurfaceInstability biot_instability(const Material& m, double third_stretch = 1.0);

// The free surface's normal stretch for the stretches along it and along the third axis: where
// the normal stress vanishes.
double free_normal_stretch(const Material& m, double tangential, double third_stretch);

}  // namespace snapjump::fem
