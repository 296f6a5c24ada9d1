// The clamped cap's quasi-static pressure-volume branch in the axisymmetric model
// (axi/static_branch.hpp): p_c, p_- and, with --csv, every point (V / V0, dp / p_c Zoelly, apex
// displacement, Newton iterations, deepest self-contact crossing, the inner surface's crease
// measure and where it is, axi/surface_stretch.hpp, and how many separate regions touch).
//
//   build/static_branch [--no-contacts] [--csv FILE] [--step DS] [--end V_OVER_V0] [--grading G]
//                       [--end-dp DP_OVER_P_ZOELLY [--through-snaps]] [--crease-fan FROM_RIM_mm
//                       [--crease-fan-band mm] | --fan-layer LAYERS | --seed FROM_RIM_mm DEPTH_mm
//                       ...] THROUGH ALONG [R_mm h_mm [PHI_deg [NU]]]
// --seed may be given more than once (one rosette each; the last depth notches them all).
#include "axi/static_branch.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "axi/body.hpp"
#include "fem/surface_instability.hpp"
#include "theory/scaling.hpp"

namespace {

using namespace snapjump;

constexpr double kE = 1.2e6, kRho = 1160.0;

int run(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  axi::BranchOptions o;
  std::string csv;
  std::vector<double> pos;
  double end_dp = std::numeric_limits<double>::quiet_NaN();
  double grading = 1.0, fan = 0.0, band = 0.0;
  int fan_layer = 0;
  std::vector<double> seeds;
  double seed_depth = 0.0;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--no-contacts") {
      o.contacts = false;
    } else if (args[i] == "--through-snaps") {
      o.through_snaps = true;
    } else if (args[i] == "--seed" && i + 2 < args.size()) {
      seeds.push_back(std::stod(args[++i]) * 1e-3);
      seed_depth = std::stod(args[++i]) * 1e-3;
    } else if (args[i] == "--fan-layer" && i + 1 < args.size()) {
      fan_layer = std::stoi(args[++i]);
    } else if (args[i] == "--csv" && i + 1 < args.size()) {
      csv = args[++i];
    } else if (args[i] == "--step" && i + 1 < args.size()) {
      o.step = std::stod(args[++i]);
    } else if (args[i] == "--grading" && i + 1 < args.size()) {
      grading = std::stod(args[++i]);
    } else if (args[i] == "--crease-fan-band" && i + 1 < args.size()) {
      band = std::stod(args[++i]) * 1e-3;
    } else if (args[i] == "--crease-fan" && i + 1 < args.size()) {
      fan = std::stod(args[++i]) * 1e-3;
    } else if (args[i] == "--end-dp" && i + 1 < args.size()) {
      end_dp = std::stod(args[++i]);
    } else if (args[i] == "--end" && i + 1 < args.size()) {
      o.end_volume = std::stod(args[++i]);
    } else {
      pos.push_back(std::stod(args[i]));
    }
  }
  if (pos.size() < 2) {
    std::fprintf(stderr,
                 "usage: static_branch [--no-contacts] [--csv FILE] [--step DS] [--end V/V0] "
                 "[--grading G] [--end-dp DP [--through-snaps]] [--crease-fan FROM_RIM_mm "
                 "[--crease-fan-band mm] | "
                 "--fan-layer LAYERS | --seed FROM_RIM_mm DEPTH_mm ...] "
                 "THROUGH ALONG [R_mm h_mm "
                 "[PHI_deg [NU]]]\n");
    return 2;
  }
  const double R = pos.size() > 2 ? pos[2] * 1e-3 : 0.030;
  const double h = pos.size() > 3 ? pos[3] * 1e-3 : 0.002;
  const double phi = (pos.size() > 4 ? pos[4] : 80.0) * std::numbers::pi / 180.0;
  const double nu = pos.size() > 5 ? pos[5] : 0.45;
  const axi::Body body({.R = R,
                        .h = h,
                        .phi = phi,
                        .through = static_cast<int>(pos[0]),
                        .along = static_cast<int>(pos[1]),
                        .rim_grading = grading,
                        .crease_fan_from_rim = fan,
                        .crease_fan_band = band,
                        .fan_layer = fan_layer,
                        .crease_seeds_from_rim = seeds,
                        .crease_seed_depth = seed_depth},
                       fem::Material::from_young(kE, nu, kRho));
  const double pc = theory::zoelly_pressure(kE, h, R, nu);
  o.p_ref = pc;
  o.end_dp = end_dp * pc;
  std::FILE* out = csv.empty() ? nullptr : std::fopen(csv.c_str(), "w");
  if (out)
    std::fprintf(
        out,
        "v,dp_over_pc,apex_z_mm,iterations,contact_depth_um,crease_ratio,crease_from_rim_mm,"
        "contact_regions\n");
  double V0 = body.cavity_volume(body.nodes());
  o.progress = [&](const axi::BranchPoint& p) {
    if (out) {
      std::fprintf(out, "%.8g,%.8g,%.8g,%d,%.4g,%.5g,%.4g,%d\n", p.volume / V0, p.dp / pc,
                   1e3 * p.apex_z, p.iterations, 1e6 * p.contact_depth, p.crease_ratio,
                   1e3 * p.crease_from_rim, p.contact_regions);
    }
  };
  const auto t0 = std::chrono::steady_clock::now();
  const auto b = axi::trace_static_branch(body, o);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (out) std::fclose(out);
  fmt::print(
      "(R, h) = ({:g}, {:g}) mm, phi {:g} deg, nu {:g}, {} x {} elements, contacts {}: {} points, "
      "{:.1f} s, rim grading {:g}\n",
      1e3 * R, 1e3 * h, phi * 180 / std::numbers::pi, nu, body.spec().along, body.spec().through,
      o.contacts ? "on" : "off", b.points.size(), wall, grading);
  if (fan_layer > 0) {
    fmt::print("  fan layer of {} layers: three elements at every inner corner node, {} elements\n",
               fan_layer, body.num_elements());
  }
  if (body.crease_root() >= 0) {
    fmt::print("  crease fan at the inner node {:.4g} mm from the rim ({} fans)\n",
               1e3 * body.crease_root_from_rim(), body.crease_fans());
  }
  for (const int node : body.crease_seeds()) {
    fmt::print(
        "  seeded crease: a rosette of four elements at the inner node {:.4g} mm from the rim, "
        "notched {:.3g} um\n",
        1e3 * body.from_rim(node), 1e6 * seed_depth);
  }
  fmt::print("  p_c = {:.6g} Pa = {:.5f} p_Zoelly at V / V0 = {:.4f}\n", b.p_c, b.p_c / pc, b.v_c);
  fmt::print("  p_- = {:.6g} Pa = {:.5f} p_Zoelly at V / V0 = {:.4f}\n", b.p_minus, b.p_minus / pc,
             b.v_minus);
  fmt::print("  p_hold = {:.6g} Pa = {:.5f} p_Zoelly at V / V0 = {:.4f}\n", b.p_hold, b.p_hold / pc,
             b.v_hold);
  fmt::print(
      "  last point V / V0 = {:.4f}, dp = {:.5f} p_Zoelly, {}stable under pressure control\n",
      b.points.back().volume / V0, b.points.back().dp / pc, b.stable ? "" : "not ");
  fmt::print("  {}\n", b.reached_end       ? "reached the end"
                       : b.snaps_below_end ? "stopped at a maximum of dp below the end's: a snap "
                                             "under pressure control"
                       : b.loses_stability_below_end
                           ? "stopped at the last stable point below the end's dp: the next is "
                             "unstable under pressure control"
                           : b.stop_reason);
  if (o.through_snaps) {
    std::string passed;
    for (const double m : b.passed_maxima) passed += fmt::format(" {:.5f}", m / pc);
    fmt::print(
        "  through snaps: passed the inverted maxima (p_Zoelly){}; the state at {:.5f} "
        "p_Zoelly{}\n",
        passed.empty() ? " none" : passed, b.state_dp / pc,
        b.reached_end || b.stop_reason.empty() ? "" : fmt::format(" ({})", b.stop_reason));
  }
  const auto biot = fem::biot_instability(body.material());
  fmt::print(
      "  the inner surface's crease measure at the last point: {:.4g} at {:.3g} mm from the rim "
      "(an incompressible neo-Hookean surface creases from {:g}; this law's smooth surface "
      "wrinkles from {:.4g}, Biot)\n",
      b.points.back().crease_ratio, 1e3 * b.points.back().crease_from_rim,
      fem::kNeoHookeanCreaseRatio, biot.ratio);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
