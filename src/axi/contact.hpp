// Where the axisymmetric shell meets itself and the apparatus.
//
// The container: its rigid bottom face lies in the cone of the rim face (the polar angle phi about
// the centre of curvature, moving with the container), and the rim face itself is clamped to it,
// so from the inner corner of the rim face (s = R - h/2 from the centre) outwards that cone is
// rigid: the clamped face, then the acrylic beyond the hole of diameter 2 R sin(phi). No node of
// the shell may cross it there (axi::Dynamics enforces it exactly, as the plate: RimCone).
//
// The fold: where the inverted shell turns back next to the rim, its inner surface faces itself.
// InnerSelfContact keeps it from passing through itself with a frictionless penalty between each
// inner-surface node and the inner surface's quadratic segments that do not hold it: a node that
// has crossed a segment by a gap g < 0 (on the material's side of it, within one thickness) is
// pushed back by a pressure k |g| over its share of the surface, and the segment's nodes take the
// opposite force through the shape functions at the closest point. The forces are minus the
// gradient of the energy sum (k/2) A_a g^2, so the contact conserves energy and the z resultant
// is zero (each ring pushes the other).
//
// The segments meet at corners (the surface is only continuous there), and each crossing must
// belong to exactly one feature of the surface, or the force would jump as a node slides past a
// corner: where the surface turns towards the material, a node below the corner projects into
// both segments, and takes its gap from the one on its side of the line where the two gaps are
// equal; where it turns away, a wedge below the corner projects into neither, and there the node's
// gap is its distance to the corner node. The gap, and with it the force's size, is then
// continuous as a node slides along the surface (the distance to the surface, not a sum).
//
// A Newton solver needs more: the plain law's stiffness jumps from 0 to k A where a node first
// touches, and Newton's method steps back and forth across that jump without converging (measured
// on the static branch: a cycle of three to five iterations between no contact and a few
// micrometres' crossing). With a smoothing length g0 > 0 the law is regularised over the first
// g0 of a crossing (penalty below): the force rises as k A d^2 / (2 g0), then k A (d - g0 / 2),
// continuous with its derivative.
#pragma once

#include <vector>

#include "axi/body.hpp"
#include "core/container_face.hpp"

namespace snapjump::axi {

// The rim face's cone in the meridian plane (core::ContainerFace, shared with the 3D model).
using RimCone = core::ContainerFace;
RimCone rim_cone(const MeshSpec& spec);

// The penalty at a crossing of depth d >= 0 per unit k A: force (d, or regularised over the
// smoothing length g0 > 0 as above) and energy (its integral from 0 to d).
struct Penalty {
  double force, energy;
};
Penalty penalty(double depth, double smoothing);

class InnerSelfContact {
 public:
  // stiffness: k [Pa/m]; smoothing: g0 [m] (0: the plain law).
  InnerSelfContact(const Body& body, double stiffness, double smoothing = 0.0);

  // f += the contact forces at positions x; returns the penalty energy [J].
  double add_forces(const Points& x, Points& f) const;
  // The deepest crossing found by the last add_forces [m] (0 when none), and how many nodes.
  [[nodiscard]] double deepest() const { return deepest_; }
  [[nodiscard]] int touching() const { return touching_; }
  // And in how many separate regions of the inner surface (touching nodes more than
  // kRegionGap apart along it, two elements' edges, belong to different ones: two creases).
  [[nodiscard]] int regions() const { return regions_; }
  // What add_forces finds at x, without its forces: the deepest crossing [m] and the regions.
  struct Touch {
    double deepest = 0.0;
    int regions = 0;
  };
  [[nodiscard]] Touch touch(const Points& x) const;
  static constexpr std::size_t kRegionGap = 4;
  // The crossings of a free point at (r, z) (one that no segment holds): the sum of depth times
  // the normal into the cavity over them (the push it would feel per unit k A under the plain
  // law) and how many features of the surface it crossed.
  struct PointCrossing {
    double push_r = 0.0, push_z = 0.0;
    int features = 0;
  };
  [[nodiscard]] PointCrossing crossing_at(const Points& x, double r, double z) const;
  [[nodiscard]] double stiffness() const { return k_; }
  [[nodiscard]] double smoothing() const { return smoothing_; }
  // Each inner node's share of the reference inner surface [m^2], in the order of inner().
  [[nodiscard]] const std::vector<double>& areas() const { return area_; }

 private:
  const Body* body_;
  double k_;
  double smoothing_;
  double depth_limit_;
  std::vector<double> area_;  // each inner node's share of the reference inner surface [m^2]
  // Per segment, made once per add_forces: the box of its three nodes widened by the depth limit
  // (a node outside it cannot have crossed the segment) and its unit tangents at its ends.
  struct Segment {
    double lo_r, hi_r, lo_z, hi_z;
    double t[2][2];  // [start, end][r, z]
  };
  mutable std::vector<Segment> segments_;
  void prepare(const Points& x) const;
  [[nodiscard]] bool owns(const Points& x, std::size_t a, double qr, double qz,
                          std::size_t k) const;
  // Calls visit(k, xi, n_r, n_z, depth) for each crossing of a point at q (inner node a, whose own
  // segments it skips; any other value of a: a point no segment holds): the feature's segment from
  // inner node k and the point xi on it, the normal into the cavity there, the depth.
  template <typename Visit>
  void crossings(const Points& x, std::size_t a, double qr, double qz, Visit visit) const;
  mutable double deepest_ = 0.0;
  mutable int touching_ = 0;
  mutable int regions_ = 0;
};

// The penalty's default stiffness: the P-wave modulus over the thickness of one element, so that
// a contact spring is about as stiff as the element it presses on (the explicit step keeps its
// margin) and a contact pressure p crosses by p / (lambda + 2 mu) of an element's thickness.
double default_contact_stiffness(const Body& body);

}  // namespace snapjump::axi
