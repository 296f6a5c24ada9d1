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
  GmshSession() {
    gmsh::initialize();
    try {
      gmsh::option::setNumber("General.Terminal", 0);
      gmsh::option::setNumber("General.Verbosity", 1);
    } catch (...) {
      gmsh::finalize();
      throw;  // threads_ (constructed first) still puts the thread count back
    }
  }
  ~GmshSession() { gmsh::finalize(); }  // then threads_ puts the thread count back
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  // Saves the OpenMP thread count before gmsh starts and restores it when the session ends,
  // whichever way it ends.
  struct ThreadCount {
    int n = omp_get_max_threads();
    ThreadCount() = default;
    ThreadCount(const ThreadCount&) = delete;
    ThreadCount& operator=(const ThreadCount&) = delete;
    ~ThreadCount() { omp_set_num_threads(n); }
  };
  ThreadCount threads_;
};

}  // namespace snapjump::mesh
