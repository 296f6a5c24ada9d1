// Prints Zoelly's buckling pressure of the paper's default popper through the installed library:
// p_c = 2 E (h/R)^2 / sqrt(3 (1 - nu^2)) = 6896 Pa for E = 1.2 MPa, h/R = 2/30, nu = 0.45.
#include <cmath>
#include <cstdio>

#include "config/case.hpp"
#include "theory/scaling.hpp"

int main() {
  const auto c = snapjump::config::default_case();
  const auto p = snapjump::theory::predict(c, snapjump::theory::contact_constants());
  std::printf("p_c %.1f Pa\n", p.zoelly_pc);
  return std::abs(p.zoelly_pc - 6896.1) < 1.0 ? 0 : 1;
}
