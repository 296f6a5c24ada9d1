#include "popper/axi_shell.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include "axi/static_branch.hpp"
#include "axi/surface_stretch.hpp"
#include "io/vtu.hpp"
#include "popper/material.hpp"
#include "popper/state_io.hpp"

namespace snapjump::popper {
namespace {

constexpr double kG = config::kStandardGravity;
constexpr char kAxiMagic[] = "axisymmetric-1";

axi::Body make_body(const config::Case& c, const Numerics& n) {
  return axi::Body(axi::MeshSpec{.R = c.shell.R,
                                 .h = c.shell.h,
                                 .phi = c.shell.phi,
                                 .through = n.axi_through,
                                 .along = n.axi_along,
                                 .reduced_bulk = n.reduced_bulk,
                                 .crease_fan_from_rim = n.axi_crease_fan,
                                 .crease_fan_band = n.axi_crease_fan_band,
                                 .fan_layer = n.axi_fan_layer,
                                 .crease_seeds_from_rim = n.axi_crease_seeds,
                                 .crease_seed_depth = n.axi_crease_seed_depth},
                   body_material(c.material));
}

}  // namespace

AxiShell::AxiShell(const config::Case& c, const Numerics& n, std::function<double()> delta_p)
    : body_(make_body(c, n)),
      omega_max_(body_.highest_frequency()),
      dynamics_(body_, kAxiStabilityFraction * 2.0 / omega_max_) {
  dynamics_.set_pressure(std::move(delta_p));
  const auto& X = body_.nodes();
  hole_area_ = std::numbers::pi * std::pow(X.r[body_.inner().back()], 2);
  depth_outer_ = X.z[body_.outer().back()] - X.z[body_.apex()];
}

std::string AxiShell::describe() const {
  const auto& s = body_.spec();
  std::string text = fmt::format(
      "  model       axisymmetric (9-node elements on the meridian section, the plate exact on "
      "the nodes)\n  mesh        {} x {} elements (along the meridian x through h), {} nodes; "
      "element {:.3g} mm along, {:.3g} mm through\n  bulk energy {}\n  time step   {:.3g} us ({} "
      "of the stability limit 2 / omega_max, omega_max = {:.4g} rad/s)\n",
      s.along, s.through, body_.num_nodes(), 1e3 * s.R * s.phi / s.along, 1e3 * s.h / s.through,
      s.reduced_bulk ? "at 2 x 2 Gauss points, the rest at 3 x 3 (selective, free of locking)"
                     : "at 3 x 3 Gauss points with the rest (numerics.bulk_integration = \"full\")",
      1e6 * dynamics_.dt(), kAxiStabilityFraction, omega_max_);
  if (s.fan_layer > 0) {
    text += fmt::format(
        "  fan layer   the first {} layer{} through h tiled so that three elements meet at every "
        "inner corner node, where a crease may root (numerics.fan_layer): {} elements in all\n",
        s.fan_layer, s.fan_layer > 1 ? "s" : "", body_.num_elements());
  }
  if (body_.crease_root() >= 0) {
    text += fmt::format(
        "  crease fan  a crease's root at the inner surface's node {:.3g} mm from the rim, three "
        "elements around it (numerics.crease_fan){}\n",
        1e3 * body_.crease_root_from_rim(),
        body_.crease_fans() > 1
            ? fmt::format("; {} such roots, every second node within {:.3g} mm about it",
                          body_.crease_fans(), 1e3 * body_.spec().crease_fan_band)
            : std::string());
  }
  if (!body_.crease_seeds().empty()) {
    std::vector<std::string> at;
    for (const int root : body_.crease_seeds())
      at.push_back(fmt::format("{:.3g}", 1e3 * body_.from_rim(root)));
    const bool one = at.size() == 1;
    text += fmt::format(
        "  seeded      {} at the inner surface's node{} {} mm from the rim, a "
        "rosette of four elements around {}, notched {:.3g} um into the solid "
        "(numerics.crease_seed{}, numerics.crease_seed_depth)\n",
        one ? "a crease's root" : "creases' roots", one ? "" : "s", fmt::join(at, " and "),
        one ? "it" : "each", 1e6 * s.crease_seed_depth, one ? "" : ", numerics.second_crease_seed");
  }
  return text;
}

nlohmann::json AxiShell::numerics_json() const {
  const auto& s = body_.spec();
  auto seeds_from_rim = nlohmann::json::array();
  for (const int root : body_.crease_seeds()) seeds_from_rim.push_back(body_.from_rim(root));
  return {
      {"model", "axisymmetric"},
      {"bulk_integration", s.reduced_bulk ? "reduced" : "full"},
      {"elements", body_.num_elements()},
      {"nodes", body_.num_nodes()},
      {"elements_along", s.along},
      {"elements_through", s.through},
      {"crease_fan_from_rim",
       body_.crease_root() < 0 ? nlohmann::json() : nlohmann::json(body_.crease_root_from_rim())},
      {"crease_fans", body_.crease_fans()},
      {"fan_layer", s.fan_layer},
      {"crease_seeds_from_rim", seeds_from_rim},
      {"crease_seed_depth", s.crease_seed_depth},
      {"dt", dynamics_.dt()},
      {"omega_max", omega_max_}};
}

std::optional<ShellModel::SurfaceCompression> AxiShell::inner_surface_compression() const {
  const auto& x = dynamics_.positions();
  const auto worst = axi::largest_compressed_ratio(axi::inner_surface_stretches(body_, x));
  // (1, NaN) where nothing is compressed
  return SurfaceCompression{worst.ratio, worst.from_rim, dynamics_.self_contact().touch(x).regions};
}

void AxiShell::start_held(double damping) {
  dynamics_.hold_rim();
  dynamics_.set_gravity(0.0);
  dynamics_.set_damping(damping);
}

std::optional<ShellModel::QuasiStaticBuckle> AxiShell::buckle_quasi_statically(
    double dp, double p_ref, bool through_snaps, const std::function<void()>& at_point) {
  axi::BranchOptions o;
  o.p_ref = p_ref;
  o.end_dp = dp;
  o.through_snaps = through_snaps;
  o.stop_inverted_without_buckling = true;
  o.end_volume = -std::numeric_limits<double>::max();  // only end_dp ends it
  if (at_point) o.progress = [&](const axi::BranchPoint&) { at_point(); };
  const auto b = axi::trace_static_branch(body_, o);
  dynamics_.mutable_positions() = b.state;
  dynamics_.zero_velocities();
  const auto& last = b.points.back();
  if (b.fold && !b.snaps_below_end) {  // (a fold the shell snaps over does not stop it)
    throw fem::FoldedElement(
        fmt::format("on the quasi-static buckling branch at V / V0 = {:.4f}, delta_p = {:.0f} Pa "
                    "({:.3f} p_c), on the way to {:.0f} Pa",
                    last.volume / b.V0, last.dp, last.dp / p_ref, dp),
        *b.fold);
  }
  return QuasiStaticBuckle{.reached = b.reached_end,
                           .foot = b.end_above,
                           .snaps = b.snaps_below_end || b.loses_stability_below_end,
                           .loses_stability = b.loses_stability_below_end,
                           .stable = b.stable,
                           .dp = b.state_dp,
                           .p_c = b.p_c,
                           .p_minus = b.p_minus,
                           .p_hold = b.p_hold,
                           .note = b.stop_reason,
                           .passed_maxima = b.passed_maxima};
}

void AxiShell::start_on_plate(core::RigidBody& container, double mu, double damping) {
  // Lower the shell until its lowest point touches the plate.
  const auto& x = dynamics_.positions();
  const double lowest = *std::min_element(x.z.begin(), x.z.end());
  dynamics_.translate_z(-lowest);
  dynamics_.zero_velocities();
  rim_offset_ = -lowest;
  glue_to(container, mu, damping, 0.0, 0);
}

void AxiShell::glue_to(core::RigidBody& container, double mu, double damping, double time,
                       long steps) {
  dynamics_.attach(container, mu, rim_offset_);
  dynamics_.set_gravity(kG);
  dynamics_.set_damping(damping);
  dynamics_.restore_clock(time, steps);
}

ShellModel::Contact AxiShell::contact() const {
  Contact c;
  const auto& x = dynamics_.positions();
  for (int a : body_.outer()) {
    if (dynamics_.loaded(a)) {
      c.any = true;
      c.r = std::max(c.r, x.r[a]);
    }
  }
  c.apex = dynamics_.loaded(body_.apex());
  return c;
}

void AxiShell::save_state(std::ostream& out) const {
  out.write(kAxiMagic, sizeof kAxiMagic);
  put(out, dynamics_.time());
  put(out, dynamics_.steps());
  put(out, rim_offset_);
  const auto& x = dynamics_.positions();
  const auto& v = dynamics_.velocities();
  for (const auto* a : {&x.r, &x.z, &v.r, &v.z}) put_vector(out, *a);
}

void AxiShell::load_state(std::istream& in, core::RigidBody& container, double mu) {
  char magic[sizeof kAxiMagic] = {};
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kAxiMagic, sizeof kAxiMagic) != 0) {
    throw std::runtime_error("the checkpoint is not an axisymmetric popper's");
  }
  double time = 0.0;
  long steps = 0;
  get_clock(in, time, steps);
  rim_offset_ = get_finite(in, "rim offset");
  const std::size_t n = body_.num_nodes();
  auto& x = dynamics_.mutable_positions();
  auto& v = dynamics_.mutable_velocities();
  for (auto* a : {&x.r, &x.z, &v.r, &v.z}) get_vector(in, *a, n);
  // The container's z is read after the model's state: the rim follows it from the next step.
  glue_to(container, mu, 0.0, time, steps);
}

void AxiShell::write_snapshot(const std::filesystem::path& path, double t) const {
  io::write_vtu(path, body_, dynamics_.positions(), dynamics_.velocities(), t);
}

}  // namespace snapjump::popper
