// The project's fuzz targets: each feeds arbitrary bytes to one of snapjump's readers. A reader
// may refuse its input only with the error it documents (which names the file); a crash, a
// sanitizer report or any other exception is a finding. The same functions serve the libFuzzer
// binary (`make fuzz`, fuzz/fuzz_main.cpp) and the replay test of `make test`, which feeds them
// every input kept under tests/data/fuzz/<target>/.
#pragma once

#include <string_view>
#include <vector>

namespace snapjump::fuzz {

struct Target {
  const char* name;  // also the folder of its inputs under tests/data/fuzz/
  void (*run)(std::string_view bytes);
  // What the target builds once before its first input (nullptr: nothing), so that libFuzzer's
  // per-input timeout measures the reader alone.
  void (*setup)() = nullptr;
};

// All targets: case (a case file), series (a time series or force-plate record, CSV), table (a
// sweep's table, CSV), sweep (a sweep file), checkpoint (checkpoint.bin of a 3D and an
// axisymmetric popper), vtu (a snapshot), pvd (a snapshot collection), msh (a gmsh mesh).
const std::vector<Target>& targets();
// The target called `name`, or nullptr.
const Target* find_target(std::string_view name);

}  // namespace snapjump::fuzz
