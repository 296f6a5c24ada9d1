// How large an elastic time step factor (dt = factor * smallest node spacing / p-wave speed) a
// popper's cap tolerates.
//   cfl_scan [coarse|default|fine]       the explicit finite elements alone: 4000 steps under a
//                                        pressure load
//   cfl_scan [coarse|default|fine] mpm   the whole MPM step (forces, transfers, clamp, plate with
//                                        friction, rigid container): the cap under 3 kPa, driven
//                                        apex first into the plate at 2 m/s (the fastest speed the
//                                        popper's time step allows for) and held there, 6000 steps
// A factor is stable when the run ends with finite, bounded kinetic energy and no step error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "config/case.hpp"
#include "fem/explicit.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/cap_mesher.hpp"
#include "mpm/stepper.hpp"
#include "popper/popper.hpp"

namespace {

using namespace snapjump;

constexpr double kFactors[] = {0.4, 0.5, 0.6, 0.7, 0.8, 1.0};

void scan_fem(const fem::Body& body) {
  for (const double factor : kFactors) {
    fem::ExplicitOptions o;
    o.time_step_factor = factor;
    o.pressure = [](double t) { return 3000.0 * std::min(1.0, t / 0.002); };
    fem::ExplicitDriver d(body, o);
    bool stable = true;
    try {
      for (int k = 0; k < 4000; ++k) d.step();
      stable = std::isfinite(d.kinetic_energy()) && d.kinetic_energy() < 1.0;
    } catch (const std::exception&) {
      stable = false;
    }
    std::printf("factor %.1f (dt %.3g us): %s\n", factor, 1e6 * d.dt(),
                stable ? "stable" : "unstable");
  }
}

void scan_mpm(const fem::Body& body, double dx) {
  constexpr double kSpeed = 2.0;  // m/s, the popper's expected top speed (mpm_shell.cpp)
  for (const double factor : kFactors) {
    // The cap hangs apex down (the popper's orientation), its apex 0.2 mm above the plate.
    hybrid::BodyForces forces(body, 9.80665, [](double) { return 3000.0; });
    auto particles = hybrid::particles_of(body);
    const double zmin = *std::min_element(particles.x.z.begin(), particles.x.z.end());
    for (std::size_t i = 0; i < particles.size(); ++i) {
      particles.x.z[i] += 0.0002 - zmin;
      particles.v.z[i] = -kSpeed;
    }
    const double dt = body.stable_time_step(factor);
    mpm::Stepper s(std::move(particles), forces, {dt, dx, 0.5});
    mpm::RigidBody container;
    container.mass = 0.3;
    container.vz = -kSpeed;
    s.add_rule(std::make_unique<mpm::ClampRule>(container));
    s.add_rule(std::make_unique<mpm::PlateRule>(0.3));
    s.add_rigid_body(container);
    // Driven down at 2 m/s for 2 mm, then held (the container's velocity set each step).
    const double stop = 0.002 / kSpeed;
    std::string verdict = "stable";
    double peak = 0.0;
    try {
      for (int k = 0; k < 6000; ++k) {
        container.vz = s.time() < stop ? -kSpeed : 0.0;
        container.applied_force = 0.0;
        s.step();
        container.vz = s.time() < stop ? -kSpeed : 0.0;  // prescribed, whatever the clamp did
        peak = std::max(peak, s.kinetic_energy());
      }
      const double ke = s.kinetic_energy();
      if (!std::isfinite(ke) || ke > 1.0) verdict = "unstable (kinetic energy grows)";
    } catch (const std::exception& e) {
      verdict = std::string("unstable: ") + e.what();
    }
    std::printf("factor %.1f (dt %.3g us, %.1f ms): %s; largest kinetic energy %.3g J\n", factor,
                1e6 * dt, 6e6 * dt, verdict.c_str(), peak);
  }
}

}  // namespace

int main(int argc, char** argv) {
  auto c = config::default_case();
  const std::string preset = argc > 1 ? argv[1] : "coarse";
  const bool mpm = argc > 2 && std::string(argv[2]) == "mpm";
  if (const auto r = config::parse_resolution(preset)) c.numerics.resolution = *r;
  const auto numerics = popper::resolve_numerics(c);
  const fem::Body body(mesh::make_cap_mesh(numerics.cap),
                       fem::Material::from_young(c.material.E, c.material.nu, c.material.rho));
  std::printf("%s cap: %zu elements, smallest node spacing %.3g mm%s\n", preset.c_str(),
              body.num_elements(), 1e3 * body.min_node_spacing(),
              mpm ? ", whole MPM step" : ", finite elements alone");
  if (mpm) {
    std::printf("grid spacing %.3g mm\n", 1e3 * numerics.dx);
    scan_mpm(body, numerics.dx);
  } else {
    scan_fem(body);
  }
  return 0;
}
