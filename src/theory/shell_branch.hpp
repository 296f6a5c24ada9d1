// The quasi-static pressure-volume branch of a clamped spherical cap under a uniform follower
// pressure, from an axisymmetric large-rotation thin-shell model of its own (it shares no code
// with the finite-element solvers): the buckling pressure p_c (the first maximum of the pressure
// along the branch) and p_- (the least pressure after it, on the way to the inverted cap).
//
// Model. The mid-surface meridian, parametrised by the reference arclength s0 in [0, R phi] from
// the apex, deforms to (r(s0), z(s0)), z along the axis and measured from the plane of the rim.
// Kirchhoff kinematics of a shell of revolution (Reissner's strain measures):
//   meridian stretch   lambda_s = |(r', z')|            eps_s = lambda_s - 1
//   hoop stretch       lambda_t = r / r0                eps_t = lambda_t - 1
//   meridian angle     beta with (r', z') = lambda_s (cos beta, -sin beta)
//   bending strains    k_s = d(beta - beta0)/ds0,       k_t = (sin beta - sin beta0) / r0
// ( )' = d/ds0, subscript 0 the natural cap. The strain energy is that of a thin isotropic
// linear-elastic shell in these strains,
//   U = 2 pi Int [ C/2 (eps_s^2 + eps_t^2 + 2 nu eps_s eps_t)
//                + D/2 (k_s^2 + k_t^2 + 2 nu k_s k_t) ] r0 ds0,
// C = E h / (1 - nu^2), D = E h^3 / (12 (1 - nu^2)); rotations and meridian strains are not
// restricted to be small. The pressure difference dp (outside minus inside, positive towards the
// centre of curvature) acts normal to the deformed surface; with the rim fixed it is
// conservative, its potential being dp V, where V is the volume enclosed between the deformed
// MID-surface and the plane of the rim (V0 > 0 for the natural cap, about -V0 for the mirror-
// inverted one). Equilibria are the stationary points of U + dp V; along the branch
// dU = -dp dV.
//
// Discretisation. C1 Hermite cubics in s0 for r and z on a uniform mesh (nodal r, r', z, z'),
// so the curvature is square-integrable element by element and no shear or rotation field is
// needed (no locking): a conforming Ritz discretisation of the energy above. The reference
// quantities (r0, stretch, angle and curvature of the natural meridian) are taken from the same
// interpolation of the exact circle, so the discrete natural cap is exactly stress-free. Five Gauss
// points per element; the volume (a polynomial in s0) is then integrated exactly. Boundary
// conditions: apex r = 0, z' = 0; rim r, z fixed and the tangent direction fixed (clamp), its
// length free.
//
// Continuation. Volume control with the pressure as the Lagrange multiplier, generalised to
// pseudo-arclength so that the branch passes limit points in the pressure (p_c is one) and in the
// volume (the branch of a deep cap does turn back in volume just after buckling). The arclength
// is measured in the normalised (V / V0, dp / p_cl) plane plus the root-mean-square nodal
// displacement over the cap's rise H: at the buckling of a deep cap the pressure maximum is
// nearly a corner (a mode grows at almost constant volume and pressure, the cap's interior being
// close to a complete sphere at Zoelly's pressure), and the projection on (V, dp) alone would
// lose the regularity of the parametrisation there. Tangent predictor, Newton corrector on the
// full bordered system with exact second derivatives (forward-mode automatic differentiation of
// the energy density), step halving on failure, on a turn of the tangent over 0.2 rad or on a
// change of sign of the bordered Jacobian's determinant (which marks a step that cut across a
// nearly bifurcating corner onto a neighbouring branch), step growth on easy steps. p_c and p_-
// are refined by a parabola through the three branch points around each extremum.
// p_cl = 2 E h^2 / (R^2 sqrt(3 (1 - nu^2))) (Zoelly).
#pragma once

#include <string>
#include <vector>

namespace snapjump::theory {

struct ShellBranchSpec {
  double R = 0.0;    // mid-surface radius [m]
  double h = 0.0;    // thickness [m]
  double phi = 0.0;  // polar half-angle of the rim [rad]
  double E = 0.0;    // Young's modulus [Pa]
  double nu = 0.0;   // Poisson ratio
  int segments = 0;  // elements along the meridian; 0: six per sqrt(R h), at least 32, which
                     // converges p_c and p_- to 0.5 % (0.01 % for the paper's shells)
};

struct BranchPoint {
  double volume = 0.0;         // V [m^3], mid-surface to rim plane
  double dp = 0.0;             // pressure difference, outside minus inside [Pa]
  double apex_z = 0.0;         // apex displacement along the axis [m] (negative: towards rim)
  double strain_energy = 0.0;  // U [J]
};

struct ShellBranch {
  std::vector<BranchPoint> points;  // from the natural state (V0, 0) on
  double p_c = 0.0;                 // first maximum of dp along the branch [Pa]
  double p_minus = 0.0;             // least dp after p_c up to the end of the branch [Pa]
  double V0 = 0.0;                  // volume of the natural cap [m^3] (discrete, see above)
  double p_cl = 0.0;                // Zoelly's pressure [Pa]
  int segments = 0;                 // elements used
  bool reached_inverted = false;    // the branch reached V <= -V0
  std::string note;                 // what the continuation did
};

// Traces the branch from the natural state to V <= -V0. Throws std::invalid_argument on bad
// input (R, h, E not positive, h >= R, phi outside (0, pi), nu outside (-1, 0.5], segments < 0
// or 1..3), std::runtime_error when the continuation fails before p_c and p_- are found; a
// failure after them returns the branch so far with reached_inverted = false and says why in
// note.
ShellBranch trace_shell_branch(const ShellBranchSpec& spec);

// One node of the meridian: reference arclength from the apex and the reference and deformed
// positions (z from the plane of the rim) [m].
struct MeridianNode {
  double s0 = 0.0, r0 = 0.0, z0 = 0.0, r = 0.0, z = 0.0;
};

struct ShellState {
  std::vector<MeridianNode> nodes;
  double dp = 0.0, volume = 0.0, strain_energy = 0.0;
};

// The equilibrium on the natural branch at a prescribed pressure dp: for dp > 0 the branch is
// traced up to dp (std::runtime_error if it reaches its pressure maximum first), for dp <= 0 (an
// inflated cap, no limit point) it is reached by load steps. Bad input as trace_shell_branch.
ShellState solve_shell_at_pressure(const ShellBranchSpec& spec, double dp);

}  // namespace snapjump::theory
