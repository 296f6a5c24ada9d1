// Shared by the mesh readers and generators: the 10-node tetrahedra of gmsh's current model.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <unordered_map>

#include "mesh/gmsh_session.hpp"
#include "mesh/mesh.hpp"

namespace snapjump::mesh {

struct ModelTets {
  Mesh mesh;                                   // nodes and tets only
  std::unordered_map<std::size_t, int> index;  // gmsh node tag -> mesh node
};

// The volume elements of the current model, which must all be 10-node tetrahedra; `fail` makes
// the error to throw from a description.
ModelTets tets_of_current_model(const std::function<MeshError(const std::string&)>& fail);

}  // namespace snapjump::mesh
