// The spherical cap of a case as a quadratic tetrahedral mesh.
#pragma once

#include "config/case.hpp"
#include "mesh/mesh.hpp"

namespace snapjump::mesh {

struct CapSpec {
  double R = 0.0;             // mid-surface radius [m]
  double h = 0.0;             // thickness [m]
  double phi = 0.0;           // rim polar angle from the apex [rad]
  double element_size = 0.0;  // target in-surface edge length of the quadratic elements [m]
  int layers = 2;             // quadratic elements through the thickness
};

// The cap of a case at its resolution: numerics.element_size if given, else the preset's
// fraction of sqrt(h R) (the scale of the contact zone), and numerics.elements_through_thickness
// layers, else the preset's (config::preset, the one table of the presets).
CapSpec cap_spec(const config::Case& c);

// Meshes the cap with its centre of curvature at the origin and its apex on the negative z axis
// (outer apex at z = -(R + h/2)). gmsh triangulates the mid-surface; each triangle is extruded
// radially into `layers` prisms split into three tetrahedra with a conforming rule, and the edge
// nodes are placed on the spheres (and on the rim cone) they belong to. The rim face is the cut
// along the radius at polar angle phi. Throws MeshError for an unusable spec.
Mesh make_cap_mesh(const CapSpec& spec);

}  // namespace snapjump::mesh
