// The cap as an axisymmetric solid: its meridian section (polar angle 0..phi, radius R - h/2 ..
// R + h/2 about the centre of curvature at the origin, apex on the negative z axis) meshed with
// structured 9-node quadrilaterals, several through h. Large deformation, Total Lagrangian, the
// 3D body's material law (fem/constitutive.hpp, the same source), with the hoop stretch
// rho / rho_0 as the third principal stretch.
//
// Volumetric locking at nu near 1/2: the law's shear part (neo-Hookean:
// mu/2 (tr(F^T F) - 3) - mu ln J) is integrated with 3 x 3 Gauss points, its volumetric part
// lambda/2 (ln J)^2 with 2 x 2 (selective reduced integration; with a 9-node element this acts as
// four discontinuous pressures per element). Only the quadrature of the volumetric part differs
// from the 3D body's.
//
// Node data are (rho, z) pairs in the meridian plane; masses, forces and energies are those of
// the whole ring (the factor 2 pi rho_0 is in the quadrature weights).
#pragma once

#include <array>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "axi/quadratic.hpp"
#include "fem/body.hpp"

namespace snapjump::axi {

struct MeshSpec {
  double R = 0.0;    // mid-surface radius [m]
  double h = 0.0;    // thickness [m]
  double phi = 0.0;  // polar angle of the rim [rad]
  int through = 4;   // elements through h
  int along = 0;     // elements along the meridian
  // The first element's meridian length over the last's (apex over rim; 1: uniform), the lengths
  // in geometric progression, so that the elements shrink towards the clamp, where the inverted
  // shell folds.
  double rim_grading = 1.0;
  // The bulk part at 2 x 2 Gauss points (true) or at the full 3 x 3 rule with the rest (false:
  // the 3D model's default integration, which locks at nu near 1/2).
  bool reduced_bulk = true;
  // A crease's root [m]: the inner surface's corner node nearest this arc length from the rim
  // (on the reference inner surface) is given a fan of three elements, where the two
  // structured elements at a surface node leave it two. A closed crease turns the surface
  // through 180 degrees at its root, so the material there opens from a half-plane to a whole
  // one: two elements' corners must each open to 180 degrees (det F = 0), three to about 120.
  // 0: no fan. Needs two or more elements through h; the node lies between the first element
  // and the last.
  double crease_fan_from_rim = 0.0;
  // And every second corner node within this arc length about that one [m]: a band of roots,
  // where the crease's place is known only to within it. 0: the one node.
  double crease_fan_band = 0.0;
  // Every corner node of the inner surface a crease's root: the first fan_layer layers of
  // elements through h (1 or 2; 0: none) tiled, column by column, into three 9-node elements
  // (one on the inner surface, one under the layers above, one diamond about each corner node
  // between columns), so that three elements meet at each inner corner node between the axis
  // and the rim. The layer's ends lie on the axis and on the rim face, where the extra edge it
  // needs is a boundary's. Not with crease_fan_from_rim.
  int fan_layer = 0;
  // Seeded creases' roots [m]: the inner surface's corner node nearest each arc length from the
  // rim (on the reference inner surface) is given a rosette of four elements, whose corners
  // there are about 45 degrees, in a block of four elements along by two layers through h; and
  // it is moved into the solid, along the reference surface's normal, by crease_seed_depth [m],
  // a notch where a crease can start (real surfaces have flaws; a smooth mesh has none). A
  // closed crease turns the surface through 180 degrees at its root: the rosette's four
  // corners open from 45 to about 90 degrees, each able to go to 180. Empty: none. Needs two or
  // more elements through h, two along on either side, elements no longer than deep, rosettes
  // whose blocks do not overlap, and neither a crease fan nor a fan layer.
  std::vector<double> crease_seeds_from_rim = {};
  double crease_seed_depth = 0.0;
};

// Meridian positions (structure of arrays).
struct Points {
  std::vector<double> r, z;
  [[nodiscard]] std::size_t size() const { return r.size(); }
};

class Body {
 public:
  Body(const MeshSpec& spec, const fem::Material& material);

  [[nodiscard]] const MeshSpec& spec() const { return spec_; }
  [[nodiscard]] const fem::Material& material() const { return material_; }
  [[nodiscard]] std::size_t num_nodes() const { return nodes_.size(); }
  [[nodiscard]] std::size_t num_elements() const { return elements_.size(); }
  [[nodiscard]] const Points& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<std::array<int, 9>>& elements() const { return elements_; }
  // Lumped masses of the rings (diagonal scaling of the consistent mass) [kg].
  [[nodiscard]] const std::vector<double>& mass() const { return mass_; }
  [[nodiscard]] double total_mass() const { return total_mass_; }
  // The solid of revolution's volume as the quadrature sees it [m^3].
  [[nodiscard]] double reference_volume() const { return volume_; }

  // Node sets: on the axis (rho = 0), on the rim face (glued to the container), on the outer
  // surface (meets the plate) from the axis to the rim, on the inner surface (the cavity's wall)
  // from the axis to the rim; the outer node on the axis.
  [[nodiscard]] const std::vector<int>& axis() const { return axis_; }
  [[nodiscard]] const std::vector<int>& rim() const { return rim_; }
  [[nodiscard]] const std::vector<int>& outer() const { return outer_; }
  [[nodiscard]] const std::vector<int>& inner() const { return inner_; }
  [[nodiscard]] int apex() const { return outer_.front(); }
  // The fan's root node nearest MeshSpec::crease_fan_from_rim, or -1 without one.
  [[nodiscard]] int crease_root() const { return crease_root_; }
  // How many fans the mesh has (MeshSpec::crease_fan_band).
  [[nodiscard]] int crease_fans() const { return crease_fans_; }
  // Its arc length from the rim on the reference inner surface [m]; NaN without one.
  [[nodiscard]] double crease_root_from_rim() const { return from_rim(crease_root_); }
  // The seeded creases' roots (MeshSpec::crease_seeds_from_rim), from the rim inwards.
  [[nodiscard]] const std::vector<int>& crease_seeds() const { return crease_seeds_; }
  // The one nearest the rim, or -1 without one.
  [[nodiscard]] int crease_seed() const {
    return crease_seeds_.empty() ? -1 : crease_seeds_.front();
  }
  // The arc length from the rim, on the reference inner surface, at a node's polar angle [m];
  // NaN for -1.
  [[nodiscard]] double from_rim(int node) const;

  // f = -dW/dx at positions x (overwrites f). Throws fem::InvertedElement.
  void internal_forces(const Points& x, Points& f) const;
  [[nodiscard]] double strain_energy(const Points& x) const;
  // Throws fem::FoldedElement for the lowest-numbered element whose det F is not proven positive
  // over the whole element at positions x: the meridian determinant by its Bernstein bound
  // (fem/fold_check.hpp), the hoop stretch by the radius of every node off the axis.
  void check_folds(const Points& x) const;
  // Volume between the current inner surface and the plane of its rim (exact for the quadratic
  // curve): the integral of pi rho^2 dz along the inner surface from the axis to the rim.
  [[nodiscard]] double cavity_volume(const Points& x) const;
  // f += the follower load of a pressure difference dp (outside minus inside) on the current
  // inner surface, -dp * integral of N_a n dA with n out of the cavity. Its resultant along z is
  // dp times the area of the inner rim circle: the container's hole takes the opposite.
  void add_pressure_forces(const Points& x, double dp, Points& f) const;
  // Visits the inner surface's quadrature points (three Gauss points on each of its quadratic
  // segments, from the axis to the rim) at positions x: visit(k, w, L, rho, dr, dz) with the
  // segment's first inner node k (its nodes are inner()[k .. k + 2]), the Gauss weight w, the
  // three shape functions L there, the radius rho and the derivatives of rho and z along the
  // segment's parameter. Exact for the volume, the pressure load and the area of the quadratic
  // curve.
  template <typename Visit>
  void for_each_inner_point(const Points& x, Visit visit) const;
  // The highest frequency of the undeformed body with free nodes but the axis's radial motion,
  // by power iteration on M^-1 K (K from differences of the internal forces) [rad/s].
  [[nodiscard]] double highest_frequency() const;

 private:
  template <bool kEnergy>
  double element_loop(const Points& x, Points* f) const;
  template <bool kEnergy, typename Shear>
  double element_loop(const Points& x, Points* f, const Shear& shear,
                      const fem::law::LogVolumetric& volumetric) const;

  MeshSpec spec_;
  fem::Material material_;
  Points nodes_;
  std::vector<std::array<int, 9>> elements_;
  // Per element and quadrature point: N (9), dN/dR and dN/dZ (9 each), rho_0, weight
  // (Gauss weight x det x 2 pi rho_0). The full rule (3 x 3) and the reduced rule (2 x 2).
  struct Rule {
    int points = 0;
    std::vector<double> N, dR, dZ, rho0, weight;
  };
  Rule full_, reduced_;
  std::vector<double> mass_;
  double total_mass_ = 0.0;
  double volume_ = 0.0;
  std::vector<int> axis_, rim_, outer_, inner_;
  int crease_root_ = -1, crease_fans_ = 0;
  std::vector<int> crease_seeds_;

  // A point of the lattice at fractional lattice coordinates (u along, v through; the nodes at
  // integers), on the reference arcs.
  [[nodiscard]] std::array<double, 2> lattice_point(double u, double v,
                                                    const std::vector<double>& theta) const;
  // Node indices for the points of a block of the lattice (u from i0 to i0 + width, v from 0 to
  // 4, in lattice units): the lattice's own node on the block's boundary, else a node made on
  // the first call for that point.
  std::function<int(const std::array<double, 2>&)> block_nodes(int i0, int width,
                                                               const std::vector<double>& theta);
  // The arc length from the rim [m] of element e's first inner corner node (lattice (2e, 0)), on
  // the reference inner surface.
  [[nodiscard]] double corner_from_rim(int e, const std::vector<double>& theta) const;
  // The element index e in [first, last] whose first inner corner node (lattice (2e, 0)) lies
  // nearest the arc length from_rim [m] from the rim; -1 when the range is empty.
  [[nodiscard]] int nearest_inner_corner(double from_rim, int first, int last,
                                         const std::vector<double>& theta) const;
  void add_crease_fans(const std::vector<double>& theta);
  void add_fan_block(int root, const std::vector<double>& theta);
  void add_fan_layer(const std::vector<double>& theta);
  void add_crease_seeds(const std::vector<double>& theta);
  void add_rosette(int root, const std::vector<double>& theta);
  void drop_unused_nodes();
};

template <typename Visit>
void Body::for_each_inner_point(const Points& x, Visit visit) const {
  const auto g = gauss(3);
  for (std::size_t k = 0; k + 2 < inner_.size(); k += 2) {
    for (int p = 0; p < 3; ++p) {
      const auto L = lagrange(g.x[p]);
      const auto dL = lagrange_d(g.x[p]);
      double rho = 0, dr = 0, dz = 0;
      for (int m = 0; m < 3; ++m) {
        rho += L[m] * x.r[inner_[k + m]];
        dr += dL[m] * x.r[inner_[k + m]];
        dz += dL[m] * x.z[inner_[k + m]];
      }
      visit(k, g.w[p], L, rho, dr, dz);
    }
  }
}

// The arc length from the rim along the reference inner surface (radius R - h/2) to the polar
// angle theta [m].
inline double inner_arc_from_rim(const MeshSpec& spec, double theta) {
  return (spec.R - 0.5 * spec.h) * (spec.phi - theta);
}

// The polar angles of the element corners along the meridian, 0 to spec.phi (along + 1 values).
std::vector<double> corner_angles(const MeshSpec& spec);

// Elements along the meridian for a number through h: the elements' meridian length twice their
// thickness.
int elements_along(double R, double h, double phi, int through);

}  // namespace snapjump::axi
