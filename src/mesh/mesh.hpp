// A quadratic tetrahedral mesh of a shell with the node sets the simulator needs.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/input_error.hpp"
#include "core/points.hpp"

namespace snapjump::mesh {

// Node a is at (x[a], y[a], z[a]).
using Points = core::Points;

struct Mesh {
  Points nodes;                                 // reference positions [m]
  std::vector<std::array<int, 10>> tets;        // 10-node tetrahedra, gmsh node order
  std::vector<std::array<int, 6>> inner_faces;  // 6-node triangles of the pressurised surface,
                                                // oriented with the normal out of the cavity
                                                // (into the material)
  std::vector<int> clamped;                     // nodes glued to the container (the rim face)
  std::vector<int> outer;   // nodes of the outer surface (the one that meets the plate)
  int apex = -1;            // the outer node on the axis, lowest point of the cap
  std::string description;  // where it came from, for reports
};

// A mesh that cannot be used. what() says what is wrong and where.
class MeshError : public InputError {
 public:
  using InputError::InputError;
};

// Checks element validity (positive Jacobian at every node and quadrature point, no degenerate
// element) and index ranges. Throws MeshError naming the element and where it is.
void check_mesh(const Mesh& m);

// A shell for the popper also needs clamped nodes, an outer surface, inner faces and an apex.
void check_shell_sets(const Mesh& m);

// Shifts every node by (0, 0, dz).
void translate_z(Mesh& m, double dz);

// Renumbers the nodes along a Morton (z-order) curve of their positions, and orders the
// tetrahedra and inner faces by their lowest node in that numbering; the node sets keep their
// ascending order. Nodes near each other in space are then near each other in memory, as the
// background grid visits them, and a thread that owns a range of nodes owns a region of space.
// The mesh is the same body: only the numbering changes (ties keep their old order).
void sort_along_curve(Mesh& m);

// Faces of the tetrahedra that belong to no other tetrahedron (the boundary), as 6-node
// triangles oriented outward.
std::vector<std::array<int, 6>> boundary_faces(const Mesh& m);

}  // namespace snapjump::mesh
