// What the popper's protocol needs from a discretisation of the shell: the shell alone with its
// rim held (buckle, set delta_p_j), then the shell on the plate with its rim glued to the
// container (ground, release, the jump), and what the experiment measures of it. The protocol
// (popper.hpp) drives either discretisation through this interface and knows neither:
//   - MpmShell (3D, the paper's method): quadratic tetrahedra on MPM particles, the plate and the
//     clamp acting through the background grid;
//   - AxiShell: the meridian section with 9-node axisymmetric elements, the plate acting exactly
//     on the outer surface's nodes.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "config/case.hpp"
#include "core/rigid_body.hpp"

namespace snapjump::popper {

struct Numerics;

// What a run reports of a discretisation, apart from what the protocol measures: its header
// lines, summary.json's "numerics" and the ParaView snapshots.
class ShellReport {
 public:
  virtual ~ShellReport() = default;
  // Lines for the run's header (each starts with two spaces and ends with a newline), and the
  // same facts for summary.json's "numerics".
  [[nodiscard]] virtual std::string describe() const = 0;
  [[nodiscard]] virtual nlohmann::json numerics_json() const = 0;
  // A ParaView snapshot of the current state on the plate (.vtu) at time t after the release [s].
  virtual void write_snapshot(const std::filesystem::path& path, double t) const = 0;
};

class ShellModel {
 public:
  virtual ~ShellModel() = default;

  [[nodiscard]] virtual const ShellReport& report() const = 0;

  [[nodiscard]] virtual double shell_mass() const = 0;
  // Cavity under the undeformed shell, to its rim plane [m^3].
  [[nodiscard]] virtual double undeformed_cavity_volume() const = 0;
  // Area that the pressure on the inner surface projects onto: the inner rim circle [m^2].
  [[nodiscard]] virtual double hole_area() const = 0;
  // Apex to the outer rim plane, undeformed [m].
  [[nodiscard]] virtual double undeformed_depth() const = 0;
  // The time step of the physical phase [s].
  [[nodiscard]] virtual double time_step() const = 0;

  // Phases 1-2: the rim held in the air, mass-proportional damping c [1/s], no plate. The
  // pressure difference (outside minus inside) comes from the function given at construction.
  virtual void start_held(double damping) = 0;
  // Phases 1-2 done quasi-statically, where the model has the solver for it (a model without one
  // returns nothing, and the protocol ramps the suction in time): the rim held, the shell's
  // pressure-volume branch followed from the natural state by continuation, through its buckling
  // maximum wherever it lies (the suction raised until the shell inverts, as the protocol has
  // it: the dynamic ramp's buckle_factor is no bound here) and on to the inverted segment, where
  // the shell is put at rest in the equilibrium of suction dp. p_ref: the pressure scale
  // (Zoelly's p_c). Where the inverted segment's lowest suction lies above dp, the shell is left
  // at the foot of that segment (QuasiStaticBuckle::dp), for the dynamics to lower the suction
  // from there; where the segment turns down at a maximum on the way up to dp, or stops being
  // stable on the way, at that maximum or its last stable state, for the dynamics to snap it
  // under that suction and raise the suction from there; with through_snaps, past such maxima
  // along the branch to its next stable equilibrium at dp (axi::BranchOptions::through_snaps), and
  // at the highest of them where the branch ends before. Throws fem::FoldedElement when the
  // branch folds an element before it gets there.
  struct QuasiStaticBuckle {
    bool reached = false;  // an end state was found (at dp, or at the foot above it)
    bool foot = false;     // at the foot of an inverted segment whose lowest suction exceeds dp
    // Or at a maximum of the inverted segment below dp, where the shell snaps under that
    // suction (axi::StaticBranch::snaps_below_end).
    bool snaps = false;
    // With snaps: not at a maximum but at the last stable state of that segment, past which its
    // equilibria are unstable under pressure control (axi::StaticBranch::
    // loses_stability_below_end).
    bool loses_stability = false;
    bool stable = false;  // and is stable under pressure control
    double dp = 0.0;      // the suction of that end state [Pa]
    // The branch's buckling maximum, its lowest suction after it (below which no buckled state
    // is left) and the lowest suction that holds the fully inverted shell [Pa] (NaN: not found).
    double p_c = 0.0, p_minus = 0.0, p_hold = 0.0;
    std::string note;                   // why it stopped, when it did not reach dp
    std::vector<double> passed_maxima;  // with through_snaps: the maxima gone past [Pa]
  };
  // `at_point` is called at each converged point of the branch (a stop hook may throw from it).
  virtual std::optional<QuasiStaticBuckle> buckle_quasi_statically(
      double dp, double p_ref, bool through_snaps, const std::function<void()>& at_point) {
    (void)dp;
    (void)p_ref;
    (void)through_snaps;
    (void)at_point;
    return std::nullopt;
  }
  // Phase 3 on: the shell lowered onto the plate (its lowest point where the plate meets it),
  // its rim glued to the container from now on, the plate acting with Coulomb friction mu,
  // gravity on. The container's z is 0 there.
  virtual void start_on_plate(core::RigidBody& container, double mu, double damping) = 0;
  virtual void set_damping(double c) = 0;
  virtual void step() = 0;
  [[nodiscard]] virtual double time() const = 0;
  [[nodiscard]] virtual double dt() const = 0;
  [[nodiscard]] virtual long steps() const = 0;
  virtual void reset_time() = 0;
  virtual void zero_velocities() = 0;

  [[nodiscard]] virtual double kinetic_energy() const = 0;
  [[nodiscard]] virtual double strain_energy() const = 0;
  // Throws fem::FoldedElement where an element's det F is not positive somewhere inside it
  // (between its quadrature points too: fem/fold_check.hpp). The protocol calls it every
  // millisecond of a stepped preparation phase, at the end of each preparation phase and at every
  // sample of the series.
  virtual void check_folds() const = 0;
  // Where the inner surface (the cavity's wall) is compressed along itself most: the ratio of its
  // principal stretches there, the measure a crease criterion reads (axi/surface_stretch.hpp),
  // and its distance from the rim face along the undeformed surface [m]; and in how many separate
  // places the inner surface touches itself (closed creases). Nothing where the model does not
  // resolve the surface's strain (the 3D mesh: one element through h).
  struct SurfaceCompression {
    double ratio = 1.0, from_rim = 0.0;
    int closed_creases = 0;
  };
  [[nodiscard]] virtual std::optional<SurfaceCompression> inner_surface_compression() const = 0;
  // Of the shell's weight, g along -z [J].
  [[nodiscard]] virtual double potential_energy(double g) const = 0;
  [[nodiscard]] virtual double cavity_volume() const = 0;
  [[nodiscard]] virtual double apex_z() const = 0;            // outer surface on the axis
  [[nodiscard]] virtual double outer_rim_z() const = 0;       // outer rim circle
  [[nodiscard]] virtual double outer_rim_radius() const = 0;  // of the reference shape [m]
  // The plate's reaction in the last step [N].
  [[nodiscard]] virtual double plate_force() const = 0;
  // Where the plate carries load, as the camera sees it: the outermost radius of the outer
  // surface it pushed in the last step, and whether it pushed the apex.
  struct Contact {
    bool any = false, apex = false;
    double r = 0.0;
  };
  [[nodiscard]] virtual Contact contact() const = 0;

  // The state on the plate (clock, positions, velocities and whatever the model carries), to
  // continue a stopped run; load_state() is called on a model built from the same case, after
  // which it is on the plate, glued to `container`.
  virtual void save_state(std::ostream& out) const = 0;
  virtual void load_state(std::istream& in, core::RigidBody& container, double mu) = 0;
};

// The discretisation that the case's numerics.model names; delta_p gives the pressure difference
// on the inner surface at each step. Throws config::CaseError.
std::unique_ptr<ShellModel> make_shell_model(const config::Case& c, const Numerics& n,
                                             std::function<double()> delta_p);

}  // namespace snapjump::popper
