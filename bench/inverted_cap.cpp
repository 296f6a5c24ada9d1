// Does the inverted cap snap back by itself? The popper's phases 1-2 with the rim held in the air
// (no plate, no gas law): raise the suction to 1.4 p_c until the shell inverts, then bring the
// pressure difference to a final value (default 0: no suction) and let it settle for 0.15 s.
// Prints whether the shell stays inverted (bistable at that pressure) and where its lowest point
// is. The answer depends on how finely the fold next to the clamped rim is resolved
// (docs/axisymmetric.md, "The inverted cap at rest"). `3d-reduced` is the 3D body with its
// bulk energy at one point per element (fem::BulkRule::centroid), free of volumetric locking;
// `axisymmetric-full` the axisymmetric body with its bulk energy at the full 3 x 3 rule.
//
// Every millisecond (--check-every MS) and at the end of each phase the elements are checked for
// folds (fem/fold_check.hpp): the first fold ends the probe with its time, pressure and element,
// unless
// --keep-going, which counts the checks that found one and goes on (to see where a folded shell
// ends up). --no-rim-contacts turns off the axisymmetric model's contacts at the rim (the
// container's face and the inner surface against itself, axi/contact.hpp), to measure what they do.
// For the 3D body: --face puts the container's face around the rim, as the popper's held phase
// has it (core::ContainerFace; without it nothing stops the shell folding up past the rim),
// --graded grades the cap as docs/popper.md's example (1 mm within 4 mm of the
// rim, 2 mm within 18 mm of the apex, ELEMENT_SIZE between), --time-step-factor F sets the
// explicit step's factor (default 0.4), --damping-factor D multiplies the damping (3: the popper's
// held phases), and --step-limit prints at every check the step over the
// current state's stability limit, dt omega_max(x) / 2 (fem::Body::highest_frequency at x): above
// 1 central differences are unstable in that state.
//
//   build/inverted_cap [--keep-going] [--no-rim-contacts] axisymmetric|axisymmetric-full THROUGH
//   ALONG [FINAL_DP_OVER_PC] [R_mm h_mm [PHI_deg]]
//   build/inverted_cap [--keep-going] [--check-every MS] [--damping-factor D] [--face] [--graded]
//   [--time-step-factor F] [--step-limit] 3d|3d-reduced LAYERS ELEMENT_SIZE_mm
//   [FINAL_DP_OVER_PC] [R_mm h_mm [PHI_deg]]
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <numbers>
#include <string>
#include <vector>

#include "axi/body.hpp"
#include "axi/dynamics.hpp"
#include "core/container_face.hpp"
#include "fem/body.hpp"
#include "fem/explicit.hpp"
#include "mesh/cap_mesher.hpp"
#include "theory/scaling.hpp"

namespace {

using namespace snapjump;

constexpr double kE = 1.2e6, kNu = 0.45, kRho = 1160.0;

struct Result {
  bool inverted = false;       // the apex above the rim at the end of the 1.4 p_c phase
  double apex_over_rim = 0.0;  // apex height above the outer rim [m], at the end
  double lowest_r = 0.0, lowest_below_rim = 0.0;
};

// Runs the protocol's pressure history on a driver with step(), time(), the state's summary and
// the fold check (fem::FoldedElement; called every millisecond and at the end of each phase); p is
// the pressure difference the driver reads.
template <typename Step, typename Time, typename State, typename Check>
Result run(double& p, double pc, double final_dp, double every, Step step, Time time, State state,
           Check check) {
  double next_check = every;
  const auto checked_step = [&] {
    step();
    if (time() >= next_check) {
      next_check += every;
      check();
    }
  };
  while (time() < 0.1) {
    p = 1.4 * pc * std::min(1.0, time() / 0.02);
    checked_step();
  }
  check();
  const bool inverted = state().apex_over_rim > 0.0;
  const double t0 = time();
  while (time() < t0 + 0.15) {
    const double f = std::min(1.0, (time() - t0) / 0.05);
    p = 1.4 * pc + f * (final_dp * pc - 1.4 * pc);
    checked_step();
  }
  check();
  Result r = state();
  r.inverted = inverted;
  return r;
}

// The fold checks of one probe: the first fold ends it, or (keep_going) is counted.
struct FoldLog {
  bool keep_going = false;
  int checks = 0, folded = 0;
  std::string first;
  // Runs check(); a fold is rethrown with the time and pressure, or counted.
  template <typename Check>
  void run(Check check, double t, double p_over_pc) {
    ++checks;
    try {
      check();
    } catch (const fem::FoldedElement& e) {
      const auto what =
          fmt::format("at t = {:.4f} s, delta_p = {:.3g} p_c: {}", t, p_over_pc, e.what());
      if (!keep_going) throw std::runtime_error(what);
      if (folded++ == 0) first = what;
    }
  }
  [[nodiscard]] std::string summary() const {
    if (folded == 0) return fmt::format("no fold in {} checks", checks);
    return fmt::format("a folded element at {} of {} checks, the first {}", folded, checks, first);
  }
};

}  // namespace

int main(int argc_all, char** argv_all) {
  FoldLog folds;
  bool rim_contacts = true, graded = false, step_limit = false, face = false;
  double step_factor = 0.4, every = 1e-3, damping_factor = 1.0;
  std::vector<char*> positional;
  for (int i = 0; i < argc_all; ++i) {
    const std::string a = argv_all[i];
    if (a == "--keep-going") {
      folds.keep_going = true;
    } else if (a == "--no-rim-contacts") {
      rim_contacts = false;
    } else if (a == "--graded") {
      graded = true;
    } else if (a == "--face") {
      face = true;
    } else if (a == "--step-limit") {
      step_limit = true;
    } else if (a == "--damping-factor" && i + 1 < argc_all) {
      damping_factor = std::atof(argv_all[++i]);
    } else if (a == "--check-every" && i + 1 < argc_all) {
      every = 1e-3 * std::atof(argv_all[++i]);
    } else if (a == "--time-step-factor" && i + 1 < argc_all) {
      step_factor = std::atof(argv_all[++i]);
    } else {
      positional.push_back(argv_all[i]);
    }
  }
  const int argc = static_cast<int>(positional.size());
  char** argv = positional.data();
  if (argc < 4) {
    fmt::print(
        stderr,
        "usage: {0} [--keep-going] [--no-rim-contacts] axisymmetric|axisymmetric-full THROUGH "
        "ALONG [FINAL_DP_OVER_PC] [R_mm h_mm [PHI_deg]]\n"
        "       {0} [--keep-going] [--check-every MS] [--damping-factor D] [--face] [--graded] "
        "[--time-step-factor F] [--step-limit] 3d|3d-reduced LAYERS ELEMENT_SIZE_mm "
        "[FINAL_DP_OVER_PC] [R_mm h_mm [PHI_deg]]\n",
        argv[0]);
    return 2;
  }
  try {
    const std::string model = argv[1];
    const double final_dp = argc > 4 ? std::atof(argv[4]) : 0.0;
    const double R = argc > 6 ? 1e-3 * std::atof(argv[5]) : 0.030;
    const double h = argc > 6 ? 1e-3 * std::atof(argv[6]) : 0.002;
    const double phi = (argc > 7 ? std::atof(argv[7]) : 80.0) * std::numbers::pi / 180.0;
    const double pc = theory::zoelly_pressure(kE, h, R, kNu);
    const auto material = fem::Material::from_young(kE, kNu, kRho);
    // The popper's preparation damping (its held phases use PreparationSettings::held_damping
    // = 3 times it: --damping-factor 3), times --damping-factor.
    const double damping = damping_factor * 0.3 * std::sqrt(kE / kRho) / R;
    double p = 0.0;
    Result r;
    std::string mesh;
    if (model == "axisymmetric" || model == "axisymmetric-full") {
      const bool full = model == "axisymmetric-full";
      const int through = std::atoi(argv[2]), along = std::atoi(argv[3]);
      const axi::Body body(
          {.R = R, .h = h, .phi = phi, .through = through, .along = along, .reduced_bulk = !full},
          material);
      axi::Dynamics d(body, 0.3 * 2.0 / body.highest_frequency());
      d.set_pressure([&p] { return p; });
      d.set_damping(3.0 * damping);
      d.set_rim_contacts(rim_contacts);
      const auto& x = d.positions();
      r = run(
          p, pc, final_dp, every, [&] { d.step(); }, [&] { return d.time(); },
          [&] {
            Result s;
            const double rim = x.z[body.outer().back()];
            s.apex_over_rim = x.z[body.apex()] - rim;
            double lowest = rim;
            for (int a : body.outer()) {
              if (x.z[a] < lowest) {
                lowest = x.z[a];
                s.lowest_r = x.r[a];
              }
            }
            s.lowest_below_rim = rim - lowest;
            return s;
          },
          [&] { folds.run([&] { body.check_folds(x); }, d.time(), p / pc); });
      mesh = fmt::format("axisymmetric{}, {} through h x {} along ({:.3g} mm along){}",
                         full ? " (bulk at 3 x 3 points)" : "", through, along,
                         1e3 * R * phi / along, rim_contacts ? "" : ", no contacts at the rim");
    } else if (model == "3d" || model == "3d-reduced") {
      const bool reduced = model == "3d-reduced";
      const int layers = std::atoi(argv[2]);
      const double size = 1e-3 * std::atof(argv[3]);
      mesh::CapSpec spec{.R = R, .h = h, .phi = phi, .element_size = size, .layers = layers};
      if (graded) {
        spec.rim_size = 1e-3;
        spec.rim_band = 4e-3;
        spec.contact_size = 2e-3;
        spec.contact_band = 18e-3;
      }
      const fem::Body body(mesh::make_cap_mesh(spec), material,
                           reduced ? fem::BulkRule::centroid : fem::BulkRule::full);
      fem::ExplicitOptions o;
      o.time_step_factor = step_factor;
      if (face) o.container_face = core::container_face(R, h, phi);
      o.damping = damping;
      o.pressure = [&p](double) { return p; };
      fem::ExplicitDriver d(body, o);
      mesh::Points mode;  // the power iteration's last vector, for --step-limit's next check
      if (step_limit) {
        fmt::print("reference state: dt omega_max / 2 = {:.3f}\n",
                   0.5 * d.dt() * body.highest_frequency(body.mesh().nodes, &mode));
      }
      const auto& m = body.mesh();
      std::vector<char> outer(body.num_nodes(), 0);
      for (int a : m.outer) outer[a] = 1;
      r = run(
          p, pc, final_dp, every, [&] { d.step(); }, [&] { return d.time(); },
          [&] {
            const auto& x = d.positions();
            double rim = 0.0;
            int n = 0;
            for (int a : m.clamped) {
              if (outer[a]) {
                rim += x.z[a];
                ++n;
              }
            }
            rim /= n;
            Result s;
            s.apex_over_rim = x.z[m.apex] - rim;
            double lowest = rim;
            for (int a : m.outer) {
              if (x.z[a] < lowest) {
                lowest = x.z[a];
                s.lowest_r = std::hypot(x.x[a], x.y[a]);
              }
            }
            s.lowest_below_rim = rim - lowest;
            return s;
          },
          [&] {
            if (step_limit) {
              const double omega = body.highest_frequency(d.positions(), &mode);
              fmt::print("t = {:.4f} s, delta_p = {:.3g} p_c: dt omega_max / 2 = {:.3f}\n",
                         d.time(), p / pc, 0.5 * d.dt() * omega);
            }
            folds.run([&] { body.check_folds(d.positions()); }, d.time(), p / pc);
          });
      mesh = fmt::format("3D{}, {} layers, element size {:.3g} mm{}, {} nodes, dt = {:.3g} us{}",
                         reduced ? " (bulk at the centroid)" : "", layers, 1e3 * size,
                         mesh::grading_summary(spec), body.num_nodes(), 1e6 * d.dt(),
                         face ? ", the container's face around the rim" : "");
    } else {
      fmt::print(stderr, "model must be axisymmetric, axisymmetric-full, 3d or 3d-reduced\n");
      return 2;
    }
    const std::string head = fmt::format("(R, h) = ({:.3g}, {:.3g}) mm, phi = {:.3g} deg, {}",
                                         1e3 * R, 1e3 * h, phi * 180.0 / std::numbers::pi, mesh);
    if (!r.inverted) {
      fmt::print("{}: did not invert under 1.4 p_c in 0.1 s (nothing to snap back); {}\n", head,
                 folds.summary());
      return 0;
    }
    fmt::print(
        "{}: at delta_p = {:.2f} p_c the shell {} (apex {:.2f} mm above the outer rim; lowest "
        "outer point at r = {:.2f} mm, {:.2f} mm below the rim); {}\n",
        head, final_dp, r.apex_over_rim > 0 ? "stays inverted" : "snaps back",
        1e3 * r.apex_over_rim, 1e3 * r.lowest_r, 1e3 * r.lowest_below_rim, folds.summary());
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  return 0;
}
