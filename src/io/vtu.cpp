#include "io/vtu.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <fstream>
#include <stdexcept>

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

void write_vtu(const std::filesystem::path& path, const fem::Body& body, const mesh::Points& x,
               const mesh::Points& v) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  const auto& m = body.mesh();
  const auto energy = body.element_energy_density(x);
  fmt::print(out,
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" "
             "NumberOfCells=\"{}\">\n      <Points>\n",
             x.size(), m.tets.size());
  write_vector(out, "Points", x, nullptr);
  fmt::print(out, "      </Points>\n      <PointData Vectors=\"displacement\">\n");
  write_vector(out, "displacement", x, &m.nodes);
  write_vector(out, "velocity", v, nullptr);
  fmt::print(out,
             "      </PointData>\n      <CellData Scalars=\"strain_energy_density\">\n"
             "        <DataArray type=\"Float64\" Name=\"strain_energy_density\" "
             "format=\"ascii\">\n");
  for (double e : energy) fmt::print(out, "{:.6g}\n", e);
  fmt::print(out,
             "        </DataArray>\n      </CellData>\n      <Cells>\n"
             "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& t : m.tets) {
    for (int k = 0; k < 10; ++k) fmt::print(out, "{} ", t[kVtkFromGmsh[k]]);
    out << '\n';
  }
  fmt::print(out,
             "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
             "format=\"ascii\">\n");
  for (std::size_t e = 0; e < m.tets.size(); ++e) fmt::print(out, "{}\n", 10 * (e + 1));
  fmt::print(out,
             "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" "
             "format=\"ascii\">\n");
  for (std::size_t e = 0; e < m.tets.size(); ++e) out << "24\n";
  fmt::print(out,
             "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
             "</VTKFile>\n");
  if (!out) throw std::runtime_error(fmt::format("writing {} failed", path.string()));
}

void PvdCollection::add(double t, const std::string& file) {
  frames_.emplace_back(t, file);
  const auto tmp = path_.string() + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", tmp));
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "  <Collection>\n";
    for (const auto& [time, name] : frames_) {
      fmt::print(out, "    <DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", time, name);
    }
    out << "  </Collection>\n</VTKFile>\n";
    if (!out) throw std::runtime_error(fmt::format("writing {} failed", tmp));
  }
  std::filesystem::rename(tmp, path_);
}

}  // namespace snapjump::io
