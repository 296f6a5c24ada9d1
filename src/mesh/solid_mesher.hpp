// Solid bodies in 10-node tetrahedra, for validating the MPM engine (a ball dropped on the plate,
// a block sliding on it). They have no clamp and no pressurised faces; `outer` holds their
// boundary nodes and `apex` their lowest node.
#pragma once

#include "mesh/mesh.hpp"

namespace snapjump::mesh {

// A ball of the given radius centred at (0, 0, cz). Elements of size `element_size`, refined to
// `contact_size` within `contact_zone` of the lowest point (0 = uniform).
Mesh make_ball_mesh(double radius, double cz, double element_size, double contact_size = 0.0,
                    double contact_zone = 0.0);

// A box [x0, x0 + lx] x [y0, y0 + ly] x [z0, z0 + lz].
Mesh make_box_mesh(double x0, double y0, double z0, double lx, double ly, double lz,
                   double element_size);

}  // namespace snapjump::mesh
