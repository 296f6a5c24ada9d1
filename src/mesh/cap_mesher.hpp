// The spherical cap of a case as a quadratic tetrahedral mesh.
#pragma once

#include <string>

#include "config/case.hpp"
#include "mesh/mesh.hpp"

namespace snapjump::mesh {

struct CapSpec {
  double R = 0.0;             // mid-surface radius [m]
  double h = 0.0;             // thickness [m]
  double phi = 0.0;           // rim polar angle from the apex [rad]
  double element_size = 0.0;  // target in-surface edge length of the quadratic elements [m]
  int layers = 2;             // quadratic elements through the thickness
  // Grading (0: none): element size rim_size within rim_band of the rim and contact_size within
  // contact_band of the apex (arc lengths on the mid-surface); from there the size grows by
  // kSizeGrowth of the distance until it reaches element_size.
  double rim_size = 0.0, rim_band = 0.0;
  double contact_size = 0.0, contact_band = 0.0;
  [[nodiscard]] bool graded() const { return rim_size > 0.0 || contact_size > 0.0; }
};

// How fast a graded cap's elements grow away from a fine zone: 0.3 m per metre, so that
// neighbouring elements differ by about 30 % in size.
inline constexpr double kSizeGrowth = 0.3;

// The element size a graded cap asks for at arc length `arc` from the apex on the mid-surface
// (element_size where no fine zone reaches).
double cap_element_size(const CapSpec& spec, double arc);

// ", 1 mm within 4 mm of the rim, 2 mm within 18 mm of the apex" for a graded cap, empty for a
// uniform one: the grading as the mesh's description and the commands' reports give it.
std::string grading_summary(const CapSpec& spec);

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
