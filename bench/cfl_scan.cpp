// How large a time step factor the explicit finite-element driver tolerates on a popper's cap:
// runs 4000 steps under a pressure load at several factors and says which stay bounded.
// Usage: cfl_scan [coarse|default|fine] (default: coarse).
#include <cmath>
#include <cstdio>
#include <string>

#include "config/case.hpp"
#include "fem/explicit.hpp"
#include "mesh/cap_mesher.hpp"

int main(int argc, char** argv) {
  using namespace snapjump;
  auto c = config::default_case();
  const std::string preset = argc > 1 ? argv[1] : "coarse";
  if (const auto r = config::parse_resolution(preset)) c.numerics.resolution = *r;
  const fem::Body body(mesh::make_cap_mesh(mesh::cap_spec(c)),
                       fem::Material::from_young(c.material.E, c.material.nu, c.material.rho));
  std::printf("%s cap: %zu elements, smallest node spacing %.3g mm\n", preset.c_str(),
              body.num_elements(), 1e3 * body.min_node_spacing());
  for (const double cfl : {0.4, 0.5, 0.6, 0.7, 0.8, 1.0}) {
    fem::ExplicitOptions o;
    o.cfl = cfl;
    o.pressure = [](double t) { return 3000.0 * std::min(1.0, t / 0.002); };
    fem::ExplicitDriver d(body, o);
    bool stable = true;
    try {
      for (int k = 0; k < 4000; ++k) d.step();
      stable = std::isfinite(d.kinetic_energy()) && d.kinetic_energy() < 1.0;
    } catch (const std::exception&) {
      stable = false;
    }
    std::printf("factor %.1f (dt %.3g us): %s\n", cfl, 1e6 * d.dt(),
                stable ? "stable" : "unstable");
  }
  return 0;
}
