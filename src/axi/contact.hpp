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
  // Each segment's box of its three nodes widened by the depth limit, made once per add_forces:
  // a node outside it cannot have crossed the segment.
  struct Box {
    double lo_r, hi_r, lo_z, hi_z;
  };
  mutable std::vector<Box> boxes_;
  mutable double deepest_ = 0.0;
  mutable int touching_ = 0;
  mutable int regions_ = 0;
};

// The penalty's default stiffness: the P-wave modulus over the thickness of one element, so that
// a contact spring is about as stiff as the element it presses on (the explicit step keeps its
// margin) and a contact pressure p crosses by p / (lambda + 2 mu) of an element's thickness.
double default_contact_stiffness(const Body& body);

}  // namespace snapjump::axi
