#include "io/vtu.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <numbers>
#include <sstream>

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

// The <Cells> of a grid of cells of `per_cell` nodes of VTK type `type`, and the end of the file.
void write_cells_and_close(std::ostream& out, const std::vector<int>& connectivity, int per_cell,
                           int type) {
  const std::size_t cells = connectivity.size() / static_cast<std::size_t>(per_cell);
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
}

// A named set of points, written as a 0/1 point array that ParaView can threshold on.
struct PointSet {
  const char* name;
  std::vector<char> member;
};

// The unstructured grid of a body: points at x (displacement from the reference X moved by
// dz_ref along z, velocity v), cells of `per_cell` nodes of VTK type `type`, the point sets, a
// cell scalar when given, and the time as field data.
void write_grid(const std::filesystem::path& path, const mesh::Points& x, const mesh::Points& X,
                double dz_ref, const mesh::Points& v, const std::vector<int>& connectivity,
                int per_cell, int type, const std::vector<double>* energy,
                const std::vector<PointSet>& sets, double time) {
  std::ostringstream out;
  const std::size_t cells = connectivity.size() / static_cast<std::size_t>(per_cell);
  fmt::print(out,
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n  <UnstructuredGrid>\n    <FieldData>\n"
             "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
             "format=\"ascii\">{:.9g}</DataArray>\n    </FieldData>\n"
             "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n      <Points>\n",
             time, x.size(), cells);
  write_vector(out, "Points", x, nullptr);
  fmt::print(out, "      </Points>\n      <PointData Vectors=\"displacement\">\n");
  mesh::Points placed = X;
  for (auto& z : placed.z) z += dz_ref;
  write_vector(out, "displacement", x, &placed);
  write_vector(out, "velocity", v, nullptr);
  for (const auto& set : sets) {
    fmt::print(out, "        <DataArray type=\"UInt8\" Name=\"{}\" format=\"ascii\">\n", set.name);
    for (const char m : set.member) fmt::print(out, "{}\n", m ? 1 : 0);
    fmt::print(out, "        </DataArray>\n");
  }
  fmt::print(out, "      </PointData>\n");
  if (energy) {
    fmt::print(out,
               "      <CellData Scalars=\"strain_energy_density\">\n"
               "        <DataArray type=\"Float64\" Name=\"strain_energy_density\" "
               "format=\"ascii\">\n");
    for (double e : *energy) fmt::print(out, "{:.6g}\n", e);
    fmt::print(out, "        </DataArray>\n      </CellData>\n");
  }
  write_cells_and_close(out, connectivity, per_cell, type);
  write_file_atomically(path, std::move(out).str());
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

namespace {

// How far the clamped nodes (and with them the container) have moved along z from the
// reference: the displacement is measured from the reference shape placed there.
double rim_offset(const std::vector<int>& rim, const std::vector<double>& z,
                  const std::vector<double>& z_ref) {
  if (rim.empty()) return 0.0;
  double d = 0.0;
  for (int a : rim) d += z[a] - z_ref[a];
  return d / static_cast<double>(rim.size());
}

std::vector<char> members(std::size_t n, const std::vector<int>& nodes) {
  std::vector<char> m(n, 0);
  for (int a : nodes) m[static_cast<std::size_t>(a)] = 1;
  return m;
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const fem::Body& body, const mesh::Points& x,
               const mesh::Points& v, double time) {
  const auto& m = body.mesh();
  const auto energy = body.element_energy_density(x);
  std::vector<int> cells;
  cells.reserve(10 * m.tets.size());
  for (const auto& t : m.tets) {
    for (int k = 0; k < 10; ++k) cells.push_back(t[kVtkFromGmsh[k]]);
  }
  std::vector<int> inner;
  for (const auto& f : m.inner_faces) inner.insert(inner.end(), f.begin(), f.end());
  const std::size_t n = x.size();
  const std::vector<PointSet> sets{{"inner", members(n, inner)},
                                   {"outer", members(n, m.outer)},
                                   {"clamped", members(n, m.clamped)}};
  write_grid(path, x, m.nodes, rim_offset(m.clamped, x.z, m.nodes.z), v, cells, 10, 24, &energy,
             sets, time);
}

void write_vtu(const std::filesystem::path& path, const axi::Body& body, const axi::Points& x,
               const axi::Points& v, double time) {
  // VTK_BIQUADRATIC_QUAD (28): corners counter-clockwise, edge midpoints, centre.
  constexpr int kVtkFromLocal[9] = {0, 6, 8, 2, 3, 7, 5, 1, 4};
  std::vector<int> cells;
  cells.reserve(9 * body.num_elements());
  for (const auto& e : body.elements()) {
    for (int k = 0; k < 9; ++k) cells.push_back(e[kVtkFromLocal[k]]);
  }
  const std::size_t n = x.size();
  const std::vector<PointSet> sets{{"inner", members(n, body.inner())},
                                   {"outer", members(n, body.outer())},
                                   {"clamped", members(n, body.rim())}};
  write_grid(path, in_plane(x), in_plane(body.nodes()), rim_offset(body.rim(), x.z, body.nodes().z),
             in_plane(v), cells, 9, 28, nullptr, sets, time);
}

void write_apparatus_vtu(const std::filesystem::path& path, double plate_half_width,
                         double rim_radius, double rim_z, double container_height) {
  // The plate: one quadrilateral at z = 0. The container: the side of a cylinder standing on the
  // rim, as 48 quadrilaterals.
  constexpr int kSides = 48;
  std::ostringstream out;
  const int points = 4 + 2 * kSides, cells = 1 + kSides;
  fmt::print(out,
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n  <UnstructuredGrid>\n    <Piece "
             "NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n      <Points>\n        <DataArray "
             "type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
             points, cells);
  const double w = plate_half_width;
  fmt::print(out, "{} {} 0\n{} {} 0\n{} {} 0\n{} {} 0\n", -w, -w, w, -w, w, w, -w, w);
  for (int k = 0; k < kSides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kSides;
    const double px = rim_radius * std::cos(a), py = rim_radius * std::sin(a);
    fmt::print(out, "{:.9g} {:.9g} {:.9g}\n{:.9g} {:.9g} {:.9g}\n", px, py, rim_z, px, py,
               rim_z + container_height);
  }
  fmt::print(out,
             "        </DataArray>\n      </Points>\n      <CellData Scalars=\"part\">\n"
             "        <DataArray type=\"UInt8\" Name=\"part\" format=\"ascii\">\n0\n");
  for (int k = 0; k < kSides; ++k) fmt::print(out, "1\n");
  fmt::print(out, "        </DataArray>\n      </CellData>\n");
  std::vector<int> quads{0, 1, 2, 3};
  for (int k = 0; k < kSides; ++k) {
    const int a = 4 + 2 * k, b = 4 + 2 * ((k + 1) % kSides);
    quads.insert(quads.end(), {a, b, b + 1, a + 1});
  }
  write_cells_and_close(out, quads, 4, 9);  // VTK_QUAD
  write_file_atomically(path, std::move(out).str());
}

std::string apparatus_file(const std::string& frame) {
  auto name = frame;
  const auto at = name.rfind("frame_");
  if (at != std::string::npos) name.replace(at, 6, "apparatus_");
  return name;
}

void PvdCollection::add(double t, const std::string& file) {
  frames_.emplace_back(t, file);
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const auto& [time, name] : frames_) {
    out += fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", time, name);
    // The plate and the container of that frame, when it was written (runs made before they
    // were have none).
    const auto apparatus = apparatus_file(name);
    std::error_code ec;
    if (apparatus != name && std::filesystem::exists(path_.parent_path() / apparatus, ec)) {
      out += fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"1\" file=\"{}\"/>\n", time,
                         apparatus);
    }
  }
  out += "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, out);
}

}  // namespace snapjump::io
