// Snapshots that ParaView opens: one VTK XML unstructured grid (.vtu) per frame with quadratic
// tetrahedra, and a .pvd collection that gives each frame its physical time.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "axi/body.hpp"
#include "fem/body.hpp"

namespace snapjump::io {

// Writes the body at positions x with point data displacement and velocity, and cell data the
// strain energy density (averaged over the element). Throws std::runtime_error on I/O failure.
void write_vtu(const std::filesystem::path& path, const fem::Body& body, const mesh::Points& x,
               const mesh::Points& v);
// The axisymmetric body's meridian section as 9-node quadrilaterals in the plane y = 0 (x the
// radius), with point data displacement and velocity.
void write_vtu(const std::filesystem::path& path, const axi::Body& body, const axi::Points& x,
               const axi::Points& v);

// A .pvd collection, rewritten after each frame so that a run stopped early still has a valid
// one.
class PvdCollection {
 public:
  explicit PvdCollection(std::filesystem::path path) : path_(std::move(path)) {}
  // Adds a frame (file name relative to the .pvd's folder) at time t and rewrites the file.
  void add(double t, const std::string& file);
  [[nodiscard]] std::size_t size() const { return frames_.size(); }

 private:
  std::filesystem::path path_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace snapjump::io
