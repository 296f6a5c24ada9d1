// Import of a gmsh .msh file (format 4) so that users can simulate other shell shapes.
#pragma once

#include <filesystem>

#include "mesh/mesh.hpp"

namespace snapjump::mesh {

// Reads 10-node tetrahedra and the physical groups (by name):
//   "inner"   (surfaces, 6-node triangles) the pressurised inner surface   required
//   "clamped" (any dimension)              the nodes glued to the container required
//   "outer"   (surfaces)                   the surface that meets the plate optional
//   "apex"    (a point)                    the lowest outer point          optional
// Without "outer", the outer surface is every boundary face that is neither inner nor clamped;
// without "apex", it is the lowest outer node. Throws MeshError for a missing file or group,
// linear or other element types, or invalid elements.
Mesh read_msh(const std::filesystem::path& path);

// Writes a mesh as .msh 4.1 with the physical groups read_msh understands ("inner", "clamped",
// "outer", and "shell" for the volume), so a generated cap can be inspected or edited in gmsh.
void write_msh(const Mesh& m, const std::filesystem::path& path);

}  // namespace snapjump::mesh
