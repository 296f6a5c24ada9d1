// Snapshots that ParaView opens: one VTK XML unstructured grid (.vtu) per frame with quadratic
// tetrahedra, and a .pvd collection that gives each frame its physical time.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "axi/body.hpp"
#include "fem/body.hpp"

namespace snapjump::io {

// Writes the body at positions x with point data displacement (from the reference shape moved
// along z with the clamped rim, i.e. with the container: the shell's own motion, which ParaView's
// Warp By Vector shows), velocity and the node sets inner, outer and clamped (0/1), cell data the
// strain energy density (averaged over the element), and field data TimeValue = time [s]. Every
// snapshot file (and the .pvd) is written through io::write_file_atomically: a failed write
// leaves no partial file and throws io::WriteFailed naming it.
void write_vtu(const std::filesystem::path& path, const fem::Body& body, const mesh::Points& x,
               const mesh::Points& v, double time);
// The axisymmetric body's meridian section as 9-node quadrilaterals in the plane y = 0 (x the
// radius), with the same point data and time.
void write_vtu(const std::filesystem::path& path, const axi::Body& body, const axi::Points& x,
               const axi::Points& v, double time);

// The apparatus of one frame as simple geometry: the plate (a square of half-width
// plate_half_width at z = 0, cell data part = 0) and the container's side (a cylinder of the
// rim's radius from rim_z up by container_height, part = 1).
void write_apparatus_vtu(const std::filesystem::path& path, double plate_half_width,
                         double rim_radius, double rim_z, double container_height);
// The apparatus file of a frame: "snapshots/frame_00012.vtu" -> "snapshots/apparatus_00012.vtu".
std::string apparatus_file(const std::string& frame);

// A .pvd collection, rewritten after each frame so that a run stopped early still has a valid
// one.
class PvdCollection {
 public:
  explicit PvdCollection(std::filesystem::path path) : path_(std::move(path)) {}
  // Adds a frame (file name relative to the .pvd's folder) at time t and rewrites the file; the
  // frame's apparatus file (apparatus_file()), when it exists, is part 1 of the same time step.
  void add(double t, const std::string& file);
  [[nodiscard]] std::size_t size() const { return frames_.size(); }

 private:
  std::filesystem::path path_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace snapjump::io
