// gmsh keeps its model in library-wide state; this guard opens it for one function's work and
// always closes it, so no model survives the call.
#pragma once

#include <gmsh.h>

namespace snapjump::mesh {

class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

}  // namespace snapjump::mesh
