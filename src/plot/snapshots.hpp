// Reading back the snapshots that `snapjump run` writes (io/vtu.hpp): the ParaView collection
// run.pvd (frame times and files) and the point coordinates of one ASCII .vtu frame.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace snapjump::plot {

struct Frame {
  double time = 0.0;           // [s]
  std::filesystem::path file;  // the .vtu, as the collection names it (relative to it)
};

// The frames of a .pvd collection in file order. Throws PlotInputError naming the file when it
// is missing, unreadable or lists no frame.
std::vector<Frame> read_pvd(const std::filesystem::path& path);

// The frame whose time is nearest t (the earlier on a tie). `frames` must not be empty.
const Frame& nearest_frame(const std::vector<Frame>& frames, double t);

// The points of an ASCII VTK unstructured grid (the <Points> array), in metres. Throws
// PlotInputError naming the file when it is missing or not in the format snapjump writes.
std::vector<std::array<double, 3>> read_vtu_points(const std::filesystem::path& path);

}  // namespace snapjump::plot
