#include "io/vtu.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <fstream>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace snapjump::io {
namespace {

// VTK_QUADRATIC_TETRA (24) orders the edge nodes (0,1), (1,2), (0,2), (0,3), (1,3), (2,3); gmsh's
// last two are (2,3), (1,3).
constexpr int kVtkFromGmsh[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

void write_vector(std::ostream& out, const char* name, const mesh::Points& a,
                  const mesh::Points* b) {
  fmt::print(out,
             "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" "
             "format=\"ascii\">\n",
             name);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (b != nullptr) {
      fmt::print(out, "{:.9g} {:.9g} {:.9g}\n", a.x[i] - b->x[i], a.y[i] - b->y[i],
                 a.z[i] - b->z[i]);
    } else {
      fmt::print(out, "{:.9g} {:.9g} {:.9g}\n", a.x[i], a.y[i], a.z[i]);
    }
  }
  fmt::print(out, "        </DataArray>\n");
}

}  // namespace

namespace {

// The unstructured grid of a body: points at x (displacement from X, velocity v), cells of
// `per_cell` nodes of VTK type `type`, and a cell scalar when given.
void write_grid(const std::filesystem::path& path, const mesh::Points& x, const mesh::Points& X,
                const mesh::Points& v, const std::vector<int>& connectivity, int per_cell, int type,
                const std::vector<double>* energy) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  const std::size_t cells = connectivity.size() / static_cast<std::size_t>(per_cell);
  fmt::print(out,
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" "
             "NumberOfCells=\"{}\">\n      <Points>\n",
             x.size(), cells);
  write_vector(out, "Points", x, nullptr);
  fmt::print(out, "      </Points>\n      <PointData Vectors=\"displacement\">\n");
  write_vector(out, "displacement", x, &X);
  write_vector(out, "velocity", v, nullptr);
  fmt::print(out, "      </PointData>\n");
  if (energy) {
    fmt::print(out,
               "      <CellData Scalars=\"strain_energy_density\">\n"
               "        <DataArray type=\"Float64\" Name=\"strain_energy_density\" "
               "format=\"ascii\">\n");
    for (double e : *energy) fmt::print(out, "{:.6g}\n", e);
    fmt::print(out, "        </DataArray>\n      </CellData>\n");
  }
  fmt::print(out,
             "      <Cells>\n"
             "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (std::size_t e = 0; e < cells; ++e) {
    for (int k = 0; k < per_cell; ++k) fmt::print(out, "{} ", connectivity[e * per_cell + k]);
    out << '\n';
  }
  fmt::print(out,
             "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
             "format=\"ascii\">\n");
  for (std::size_t e = 0; e < cells; ++e) fmt::print(out, "{}\n", per_cell * (e + 1));
  fmt::print(out,
             "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" "
             "format=\"ascii\">\n");
  for (std::size_t e = 0; e < cells; ++e) fmt::print(out, "{}\n", type);
  fmt::print(out,
             "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
             "</VTKFile>\n");
  if (!out) throw std::runtime_error(fmt::format("writing {} failed", path.string()));
}

// The meridian plane as the plane y = 0 of the snapshot.
mesh::Points in_plane(const axi::Points& p) {
  mesh::Points q;
  q.x = p.r;
  q.y.assign(p.size(), 0.0);
  q.z = p.z;
  return q;
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const fem::Body& body, const mesh::Points& x,
               const mesh::Points& v) {
  const auto& m = body.mesh();
  const auto energy = body.element_energy_density(x);
  std::vector<int> cells;
  cells.reserve(10 * m.tets.size());
  for (const auto& t : m.tets) {
    for (int k = 0; k < 10; ++k) cells.push_back(t[kVtkFromGmsh[k]]);
  }
  write_grid(path, x, m.nodes, v, cells, 10, 24, &energy);
}

void write_vtu(const std::filesystem::path& path, const axi::Body& body, const axi::Points& x,
               const axi::Points& v) {
  // VTK_BIQUADRATIC_QUAD (28): corners counter-clockwise, edge midpoints, centre.
  constexpr int kVtkFromLocal[9] = {0, 6, 8, 2, 3, 7, 5, 1, 4};
  std::vector<int> cells;
  cells.reserve(9 * body.num_elements());
  for (const auto& e : body.elements()) {
    for (int k = 0; k < 9; ++k) cells.push_back(e[kVtkFromLocal[k]]);
  }
  write_grid(path, in_plane(x), in_plane(body.nodes()), in_plane(v), cells, 9, 28, nullptr);
}

void PvdCollection::add(double t, const std::string& file) {
  frames_.emplace_back(t, file);
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const auto& [time, name] : frames_) {
    out += fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", time, name);
  }
  out += "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, out);
}

}  // namespace snapjump::io
