#include "mesh/solid_mesher.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "mesh/gmsh_model.hpp"

namespace snapjump::mesh {
namespace {

Mesh finish(const std::string& description, double element_size) {
  gmsh::option::setNumber("Mesh.MeshSizeMax", element_size);
  gmsh::option::setNumber("Mesh.ElementOrder", 2);
  gmsh::option::setNumber("Mesh.HighOrderOptimize", 1);
  gmsh::model::mesh::generate(3);
  auto model = tets_of_current_model(
      [&](const std::string& what) { return MeshError(fmt::format("{}: {}", description, what)); });
  Mesh m = std::move(model.mesh);
  m.description = description;
  std::set<int> boundary;
  for (const auto& f : boundary_faces(m)) boundary.insert(f.begin(), f.end());
  m.outer.assign(boundary.begin(), boundary.end());
  for (int a : m.outer) {
    if (m.apex < 0 || m.nodes.z[a] < m.nodes.z[m.apex]) m.apex = a;
  }
  check_mesh(m);
  return m;
}

}  // namespace

Mesh make_ball_mesh(double radius, double cz, double element_size, double contact_size,
                    double contact_zone) {
  if (!(radius > 0 && element_size > 0 && element_size < radius)) {
    throw MeshError(fmt::format("ball mesh needs 0 < element_size < radius (got {}, {})",
                                element_size, radius));
  }
  GmshSession session;
  gmsh::model::add("snapjump-ball");
  gmsh::model::occ::addSphere(0, 0, cz, radius);
  gmsh::model::occ::synchronize();
  if (contact_size > 0 && contact_zone > 0) {
    // Finer elements near the lowest point, where the ball meets the plate.
    const int point = gmsh::model::occ::addPoint(0, 0, cz - radius);
    gmsh::model::occ::synchronize();
    const int distance = gmsh::model::mesh::field::add("Distance");
    gmsh::model::mesh::field::setNumbers(distance, "PointsList", {static_cast<double>(point)});
    const int threshold = gmsh::model::mesh::field::add("Threshold");
    gmsh::model::mesh::field::setNumber(threshold, "InField", distance);
    gmsh::model::mesh::field::setNumber(threshold, "SizeMin", contact_size);
    gmsh::model::mesh::field::setNumber(threshold, "SizeMax", element_size);
    gmsh::model::mesh::field::setNumber(threshold, "DistMin", contact_zone);
    gmsh::model::mesh::field::setNumber(threshold, "DistMax", 2 * contact_zone);
    gmsh::model::mesh::field::setAsBackgroundMesh(threshold);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  }
  return finish(fmt::format("ball of radius {} m", radius), element_size);
}

Mesh make_box_mesh(double x0, double y0, double z0, double lx, double ly, double lz,
                   double element_size) {
  if (!(lx > 0 && ly > 0 && lz > 0 && element_size > 0)) {
    throw MeshError("box mesh needs positive sides and element size");
  }
  GmshSession session;
  gmsh::model::add("snapjump-box");
  gmsh::model::occ::addBox(x0, y0, z0, lx, ly, lz);
  gmsh::model::occ::synchronize();
  return finish(fmt::format("box {} x {} x {} m", lx, ly, lz), element_size);
}

}  // namespace snapjump::mesh
