// The stretches of the inner surface (the cavity's wall), where the inverted cap's fold next to
// the clamp compresses the elastomer most: the measure a crease criterion reads.
//
// A crease (a self-contacting fold of a compressed free surface, with no length of its own) sets
// in where the surface's principal stretches in the plane of the fold, the one along the surface
// lambda_t compressed and the one normal to it lambda_n, reach a ratio lambda_n / lambda_t that
// depends on the material alone: 2.4 for an incompressible neo-Hookean solid, whatever the
// stretch along the fold's line (W. Hong, X. Zhao and Z. Suo, Appl. Phys. Lett. 95, 111901
// (2009); 0.35 compression in plane strain). In the axisymmetric cap the fold's line is a hoop,
// its plane the meridian section: the ratio is that of the meridian deformation gradient's
// principal stretches at the surface.
#pragma once

#include <vector>

#include "axi/body.hpp"

namespace snapjump::axi {

struct SurfaceStretch {
  double from_rim = 0.0;  // the point's distance from the rim face along the undeformed surface [m]
  double tangential = 1.0;  // stretch along the surface (the meridian direction)
  double ratio = 1.0;       // largest over smallest principal stretch of the meridian section
  bool compressed = false;  // the smaller principal stretch lies along the surface (the stretch
                            // along it is nearer the smaller)
};

// At `per_element` evenly spaced points (ends included, at least 2) of each inner-surface
// segment, from the axis to the rim, at positions x. Throws std::invalid_argument for fewer than
// 2 points.
std::vector<SurfaceStretch> inner_surface_stretches(const Body& body, const Points& x,
                                                    int per_element = 5);

// The largest ratio among the points where the surface is compressed along itself (1 and
// from_rim NaN where none is).
SurfaceStretch largest_compressed_ratio(const std::vector<SurfaceStretch>& stretches);

}  // namespace snapjump::axi
