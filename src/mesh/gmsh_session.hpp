// gmsh keeps its model in library-wide state; this guard opens it for one function's work and
// always closes it, so no model survives the call. gmsh also sets the process's OpenMP thread
// count to its own option General.NumThreads (1 by default) when it starts; the guard puts the
// caller's count back, or every parallel loop after a mesh was made would run on one thread.
#pragma once

#include <gmsh.h>
#include <omp.h>

namespace snapjump::mesh {

class GmshSession {
 public:
  GmshSession() : threads_(omp_get_max_threads()) {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
  }
  ~GmshSession() {
    gmsh::finalize();
    omp_set_num_threads(threads_);
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  int threads_;
};

}  // namespace snapjump::mesh
