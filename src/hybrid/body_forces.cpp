#include "hybrid/body_forces.hpp"

namespace snapjump::hybrid {

Particles particles_of(const fem::Body& body) {
  Particles p = Particles::at_rest(body.mesh().nodes, body.mass());
  for (int a : body.mesh().clamped) p.tags[a] |= mpm::kTagClamped;
  return p;
}

}  // namespace snapjump::hybrid
