// The clamped cap's quasi-static pressure-volume branch in the axisymmetric model: equilibria of
// axi::Body with its rim face held (the container at rest), no gravity and no plate, under a
// pressure difference dp (outside minus inside) on its inner surface, followed from the natural
// state through buckling to past the inverted state.
//
// The branch is traced by pseudo-arclength continuation in the plane of the normalised cavity
// volume v = V / V0 and pressure q = dp / p_ref: each new point solves the equilibrium together
// with (v - v_k) t_v + (q - q_k) t_q = ds, t being the unit secant of the last two points. This
// passes the maximum of dp (buckling, p_c) and, where the volume turns back too, that turn.
// Newton's method on the bordered system, each correction halved until it lowers the residual
// (where one does); the stiffness from central differences of the forces,
// node colours at a time (two nodes share a colour when no element holds both), and the
// contacts' part node by node (they couple nodes that no element joins).
//
// The contacts are those of the dynamics (axi/contact.hpp), made quasi-static: the inner surface's
// self-contact penalty regularised over its first thousandth of an element's thickness (the plain
// law's stiffness jumps where a node first touches, and undamped Newton cycles across the jump),
// and the container's cone as a penalty of the same law on the inner surface's nodes (in the
// dynamics it acts exactly; a static solve needs a smooth energy). Every converged point is checked
// for folds (fem::FoldedElement stops the branch there, and the branch up to it is kept).
//
// p_c is the first maximum of dp. After it the branch may fall and rise more than once (a partly
// inverted shell can hold at a suction of its own); two of its minima matter under pressure
// control:
//   p_hold, the last minimum before the inverted end: the suction down to which the fully
//     inverted shell stays inverted (below it, it snaps towards its natural shape);
//   p_-, the lowest dp after p_c: below it no buckled equilibrium is left on the branch.
// p_- > 0 means the inverted cap needs suction to stay inverted (monostable); p_- < 0 means it
// stays inverted at dp = 0 and needs overpressure to evert (bistable). Each extremum is refined
// by a parabola through the three points around it. Only axisymmetric states are on the branch:
// a non-axisymmetric mode could lower p_c and raise p_hold.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "axi/body.hpp"

namespace snapjump::axi {

struct BranchPoint {
  double volume = 0.0;         // cavity volume [m^3]
  double dp = 0.0;             // pressure difference, outside minus inside [Pa]
  double apex_z = 0.0;         // displacement of the outer apex node along z [m]
  int iterations = 0;          // Newton iterations it took
  double contact_depth = 0.0;  // the deepest self-contact crossing there [m]
  int contact_regions = 0;     // separate regions of the inner surface touching (closed creases)
  // The inner surface's largest crease measure there (axi/surface_stretch.hpp: the ratio of its
  // principal stretches where it is compressed along itself) and that point's distance from the
  // rim face along the undeformed surface [m] (NaN where no point is compressed).
  double crease_ratio = 1.0, crease_from_rim = 0.0;
};

struct BranchOptions {
  double p_ref = 0.0;        // pressure scale [Pa] (e.g. the classical p_c); must be > 0
  double step = 0.02;        // first and largest arclength step in (v, q)
  double min_step = 1e-5;    // below this the continuation gives up
  double end_volume = -1.0;  // stop once v = V / V0 falls below this
  // Or, past p_c and a minimum, on the inverted side (V < 0), stop once dp rises to end_dp [Pa]
  // (or at a maximum below it that follows a minimum on the inverted side, snaps_below_end, or
  // where that segment's equilibria stop being stable, loses_stability_below_end)
  // (NaN: not used), and solve for the equilibrium at exactly end_dp (StaticBranch::state). Where
  // that minimum already lies above end_dp, the segment rising from it holds no equilibrium at
  // end_dp: the branch stops at its first point (StaticBranch::end_above, the state at that
  // point's dp), from which a lower suction snaps the shell back.
  double end_dp = std::numeric_limits<double>::quiet_NaN();
  // With end_dp: past a maximum of the inverted segment below end_dp (a limit point: a crease's
  // nucleation, or its closed root moving on by an element), or where that segment stops being
  // stable, go on along the branch instead of stopping: a shell under a slowly rising suction
  // snaps there at constant dp onto the branch's later part, and is taken on to end_dp where the
  // branch next rises through it stable under pressure control (as the trace takes it through
  // buckling). A crossing of end_dp whose equilibrium is not stable is passed. Where the trace
  // ends before end_dp (where no equilibrium is found, or at a fold below that maximum, a state
  // the shell snaps over), its state is the one at the highest such maximum (snaps_below_end),
  // from which a suction raised in time snaps the shell. The maxima passed: passed_maxima.
  bool through_snaps = false;
  // Stop, not reaching the end, where v falls below -1 (the cavity as large as it was, on the
  // other side of the rim's plane) before the branch's first maximum: a cap that turns inside out
  // under a suction that only rises never snaps.
  bool stop_inverted_without_buckling = false;
  int max_points = 5000;
  bool contacts = true;     // self-contact and the container's cone
  double tolerance = 1e-8;  // Newton: |residual| below this times p_ref times the rim's area
  bool check_folds = true;  // at every converged point
  // Each point of the branch as it is kept, once the next is found (a point may be taken again
  // with a shorter step, or replaced by the equilibrium at exactly end_dp, before that); the
  // last when the trace ends. The branch's points are the points reported, in order.
  std::function<void(const BranchPoint&)> progress;
};

struct StaticBranch {
  std::vector<BranchPoint> points;
  double V0 = 0.0;  // the natural cavity volume [m^3]
  double p_c = std::numeric_limits<double>::quiet_NaN();
  double p_minus = std::numeric_limits<double>::quiet_NaN();  // NaN: not reached
  double p_hold = std::numeric_limits<double>::quiet_NaN();   // NaN: the end not reached
  double v_c = std::numeric_limits<double>::quiet_NaN();      // v = V / V0 at each
  double v_minus = std::numeric_limits<double>::quiet_NaN();
  double v_hold = std::numeric_limits<double>::quiet_NaN();
  bool reached_end = false;  // v fell below end_volume, or dp rose to end_dp
  // It stopped at the foot of an inverted segment whose minimum lies above end_dp.
  bool end_above = false;
  // The inverted segment rising from a minimum on the inverted side towards end_dp turned down
  // at a maximum of dp below end_dp: a limit point, where a shell under pressure control snaps
  // (where the inner surface creases, the crease's nucleation, which is subcritical). The branch
  // stopped at that maximum.
  bool snaps_below_end = false;
  // Or, on that segment below end_dp, the next point was no longer stable under pressure control
  // without a maximum of dp: a bifurcation (where the inner surface wrinkles past its Biot
  // instability, for one). The branch stopped at the last stable point, from which a shell under
  // a rising suction leaves it in time.
  bool loses_stability_below_end = false;
  std::string stop_reason;  // why it stopped, when it did not reach the end
  // The fold that stopped it, if one did (at the last point).
  std::optional<fem::FoldedElement> fold;
  // With BranchOptions::through_snaps, the suctions of the inverted segment's maxima below end_dp
  // that the trace went past [Pa], in order.
  std::vector<double> passed_maxima;
  // The nodes' positions at the last point (at end_dp when that ended it; with through_snaps and
  // end_dp not reached, at the highest maximum passed), and the suction there [Pa].
  Points state;
  double state_dp = std::numeric_limits<double>::quiet_NaN();
  // Whether that state is stable under pressure control: its stiffness at fixed dp positive
  // definite.
  bool stable = false;
};

// Throws std::invalid_argument for unusable options.
StaticBranch trace_static_branch(const Body& body, const BranchOptions& options);

}  // namespace snapjump::axi
