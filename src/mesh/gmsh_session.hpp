// gmsh keeps its model in library-wide state; this guard opens it for one function's work and
// always closes it, so no model survives the call. gmsh also sets the process's OpenMP thread
// count to its own option General.NumThreads (1 by default) when it starts; the guard puts the
// caller's count back, or every parallel loop after a mesh was made would run on one thread.
// Two more things gmsh does when it starts are undone or avoided: it reads the user's own option
// files (~/.gmshrc and the like, a script), which would make a mesh depend on who runs snapjump,
// so they are not read; and it adds the executable's folder to PATH and sets PYTHONPATH to it,
// so the environment is put back as it was (otherwise PATH grows by a folder at every session:
// a process that reads many meshes ends up with megabytes of it, docs/robustness.md).
#pragma once

#include <gmsh.h>
#include <omp.h>

#include <cstdlib>
#include <optional>
#include <string>

namespace snapjump::mesh {

class GmshSession {
 public:
  GmshSession() {
    {
      const Environment before;
      gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    }
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
  // The environment variables gmsh sets when it starts, saved and put back.
  class Environment {
   public:
    Environment() : path_(get("PATH")), python_path_(get("PYTHONPATH")) {}
    ~Environment() {
      put("PATH", path_);
      put("PYTHONPATH", python_path_);
    }
    Environment(const Environment&) = delete;
    Environment& operator=(const Environment&) = delete;

   private:
    static std::optional<std::string> get(const char* name) {
      const char* v = std::getenv(name);
      return v ? std::optional<std::string>(v) : std::nullopt;
    }
    static void put(const char* name, const std::optional<std::string>& v) {
      if (v) {
        ::setenv(name, v->c_str(), 1);
      } else {
        ::unsetenv(name);
      }
    }
    std::optional<std::string> path_, python_path_;
  };

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
