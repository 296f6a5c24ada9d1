#include "mpm/body_forces.hpp"

namespace snapjump::mpm {

Particles particles_of(const fem::Body& body) {
  Particles p = Particles::at_rest(body.mesh().nodes, body.mass());
  for (int a : body.mesh().clamped) p.tags[a] |= kTagClamped;
  return p;
}

}  // namespace snapjump::mpm
