// The shell as a finite-element body: Total Lagrangian 10-node tetrahedra with the paper's
// compressible neo-Hookean energy (or another law of
// fem/constitutive.hpp), lumped masses by diagonal scaling, gravity, the pressure
// follower load on the inner faces and the enclosed cavity volume.
//
// The body knows nothing about grids or time stepping: given current node positions it returns
// forces, energies and volumes. Node data are structure-of-arrays (mesh::Points).
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/wide.hpp"
#include "fem/constitutive.hpp"
#include "mesh/mesh.hpp"

namespace snapjump::fem {

// Which material law (fem/constitutive.hpp) the body's shear part follows.
enum class LawKind { neo_hookean, gent };

struct Material {
  double mu = 0.0;      // shear modulus at small strain [Pa]
  double lambda = 0.0;  // first Lame constant at small strain [Pa]
  double rho = 0.0;     // reference density [kg/m^3]
  LawKind law = LawKind::neo_hookean;
  double gent_jm = 0.0;  // Gent's locking value of I1 - 3 (law == gent)
  // Lame constants from Young's modulus and Poisson's ratio; needs -1 < nu < 1/2.
  static Material from_young(double E, double nu, double rho);
  // The same moduli under Gent's law with locking value jm > 0.
  [[nodiscard]] Material with_gent(double jm) const;
  [[nodiscard]] double p_wave_speed() const;  // sqrt((lambda + 2 mu) / rho), at small strain
};

// f(shear law, volumetric part) for m's law: the one place a Material becomes law objects.
// mu and lambda are the small-strain moduli for every law: Gent's shear part adds 2 mu / Jm to
// the first Lame constant at small strain, so its volumetric part takes lambda - 2 mu / Jm.
template <typename Fn>
decltype(auto) with_law(const Material& m, Fn&& f) {
  if (m.law == LawKind::gent) {
    return f(law::Gent{m.mu, m.gent_jm}, law::LogVolumetric{m.lambda - 2.0 * m.mu / m.gent_jm});
  }
  return f(law::NeoHookean{m.mu}, law::LogVolumetric{m.lambda});
}

// m's strain energy density psi(F) and its first Piola stress P = dpsi/dF (fem/constitutive.hpp;
// the neo-Hookean law: psi = mu/2 (tr(F^T F) - 3) - mu ln J + lambda/2 (ln J)^2,
// P = mu (F - F^-T) + lambda ln J F^-T). F row-major 3x3. first_piola_stress returns false and
// energy_density +inf where det F <= 0 or the law is not defined at F.
bool first_piola_stress(const Material& m, const double F[9], double P[9]);
double energy_density(const Material& m, const double F[9]);

// An element turned inside out (det F <= 0) or a non-finite force: the step cannot go on.
class InvertedElement : public std::runtime_error {
 public:
  InvertedElement(int element, double x, double y, double z);
  int element;
  double x, y, z;  // current position of its first corner
};

// An element whose det F is not positive somewhere inside it, found by its Bernstein bound
// (fem/fold_check.hpp) though its quadrature points may all be positive: a fold through itself.
class FoldedElement : public std::runtime_error {
 public:
  // det_f: the smallest det F found (or the bound where none was found at or below 0); (x, y, z)
  // the current position of that point; what: how it was found.
  FoldedElement(int element, double det_f, double x, double y, double z, const std::string& what);
  // The same fold, its message led by where it was met (context: what the model was doing).
  FoldedElement(const std::string& context, const FoldedElement& fold);
  int element;
  double det_f;
  double x, y, z;
};

// Where the bulk part of the energy, lambda/2 (ln J)^2, is integrated. `full`: at the four
// points of the degree-2 rule with the rest (the paper's element). `centroid`: at one point per
// element, the rest at four (selective integration: one volume constraint per element instead of
// four, which keeps the ten-node tetrahedron from locking as nu approaches 1/2; the same split
// the axisymmetric body makes). On an element whose deformation is homogeneous the two agree.
enum class BulkRule { full, centroid };

class Body {
 public:
  Body(mesh::Mesh mesh, const Material& material, BulkRule bulk = BulkRule::full);

  [[nodiscard]] const mesh::Mesh& mesh() const { return mesh_; }
  [[nodiscard]] const Material& material() const { return material_; }
  [[nodiscard]] BulkRule bulk_rule() const { return bulk_; }
  [[nodiscard]] std::size_t num_nodes() const { return mesh_.nodes.size(); }
  [[nodiscard]] std::size_t num_elements() const { return mesh_.tets.size(); }
  [[nodiscard]] const std::vector<double>& mass() const { return mass_; }
  [[nodiscard]] double total_mass() const { return total_mass_; }
  [[nodiscard]] double reference_volume() const { return volume_; }
  // The volume as the force quadrature (degree 2) sees it; equals reference_volume() on
  // straight-sided elements and differs slightly on curved ones.
  [[nodiscard]] double quadrature_volume() const;
  // Smallest distance between two nodes of one element, in the reference configuration.
  [[nodiscard]] double min_node_spacing() const { return min_spacing_; }
  // dt = factor * min_node_spacing / p_wave_speed (the elastic time step factor).
  [[nodiscard]] double stable_time_step(double factor) const;
  // The highest natural frequency of the free, undeformed body (lumped masses), by power
  // iteration [rad/s]: central differences are stable for dt < 2 / omega_max.
  [[nodiscard]] double highest_frequency() const;
  // The same of the body linearised about the state x: power iteration on M^-1 K(x), K applied
  // by differences of the internal forces. `mode`, when given with one vector per node, starts
  // the iteration (a warm start from a nearby state) and receives its last vector.
  [[nodiscard]] double highest_frequency(const mesh::Points& x, mesh::Points* mode = nullptr) const;

  // Element e's reference shape gradients dN_a/dX at its quadrature point q (of 4), as
  // [node][3], and that point's weight (rule weight * det(dX/dxi)).
  [[nodiscard]] std::array<double, 30> point_gradients(std::size_t e, int q) const;  // 3 x 10
  [[nodiscard]] double point_weight(std::size_t e, int q) const;

  // Working memory of internal_forces and add_pressure_forces: one per caller that calls them
  // every step.
  struct ForceScratch {
    std::vector<double> element_forces;  // [element][node][3]
    std::vector<double> face_normals;    // [inner face][quadrature point][3]
  };
  // f = -dW/dx at positions x (overwrites f; paper, Eq. S10). Throws InvertedElement (the
  // lowest-numbered inverted element). The same bits at any thread count.
  void internal_forces(const mesh::Points& x, mesh::Points& f, ForceScratch& scratch) const;
  void internal_forces(const mesh::Points& x, mesh::Points& f) const;
  // Throws FoldedElement for the lowest-numbered element whose det F is not proven positive over
  // the whole element (its nodes, its quadrature points and every point between:
  // fem/fold_check.hpp) at positions x. The same element at any thread count.
  void check_folds(const mesh::Points& x) const;
  // Strain energy W at positions x. Throws InvertedElement.
  [[nodiscard]] double strain_energy(const mesh::Points& x) const;
  // Strain energy density of each element (its energy over its reference volume) [J/m^3].
  [[nodiscard]] std::vector<double> element_energy_density(const mesh::Points& x) const;

  // f += the follower load of a pressure difference dp (outside minus inside) on the current
  // inner faces: f_a = -dp * integral of N_a n dA, n out of the cavity. Equals -dp dV/dx_a
  // (paper, Eq. S11).
  void add_pressure_forces(const mesh::Points& x, double dp, mesh::Points& f) const;
  void add_pressure_forces(const mesh::Points& x, double dp, mesh::Points& f,
                           ForceScratch& scratch) const;
  // Volume between the current inner surface and the plane of its rim (the rim nodes move
  // rigidly with the container, which keeps that plane flat).
  [[nodiscard]] double cavity_volume(const mesh::Points& x) const;
  // g_a = integral over the inner faces of N_a n dA = dV/dx_a for every node off the rim.
  void cavity_volume_gradient(const mesh::Points& x, mesh::Points& g) const;

  // f_z -= m_a g for every node (gravity on the lumped masses; paper, Eq. S11).
  void add_gravity(double g, mesh::Points& f) const;

  // Whether internal_forces runs the elements' AVX2 version (core/wide.hpp): on where the
  // processor has AVX2 unless turned off here. The results are the same either way.
  void set_wide_vectors(bool on) { wide_ = on && core::has_avx2(); }
  [[nodiscard]] bool wide_vectors() const { return wide_; }

 private:
  // Element e at positions x: its strain energy into out[0] (kEnergy) or its nodal forces into
  // out[0..30). False where a quadrature point is inverted or outside the law's range.
  template <bool kEnergy>
  inline bool element_pass(int e, const mesh::Points& x, double* out) const;
  // The same for a given law (with_law's arguments).
  template <bool kEnergy, typename Shear>
  inline bool element_pass(int e, const mesh::Points& x, const Shear& shear,
                           const law::LogVolumetric& volumetric, double* out) const;
  // element_pass<false> compiled for AVX2 (x86-64 builds only).
  template <typename Shear>
  bool element_forces_wide(int e, const mesh::Points& x, const Shear& shear,
                           const law::LogVolumetric& volumetric, double* out) const;
  // The element loop of internal_forces (an orphaned `omp for`); bad: the lowest failing element.
  template <typename Shear>
  void element_forces(const mesh::Points& x, const Shear& shear,
                      const law::LogVolumetric& volumetric, double* ef,
                      std::atomic<int>& bad) const;
  // Throws std::out_of_range naming `what` unless element e and its point q exist.
  void check_point(std::size_t e, int q, const char* what) const;

  mesh::Mesh mesh_;
  Material material_;
  BulkRule bulk_ = BulkRule::full;
  bool wide_ = core::has_avx2();
  // Reference shape gradients dN/dX, [element][node][3][qp]: the four points' values of one
  // entry side by side, so that the force loop works on the four points at once.
  std::vector<double> grad_;
  std::vector<double> weight_;  // [element][qp] quadrature weight * det(dX/dxi)
  // BulkRule::centroid only: dN/dX at each element's centroid, and the element's quadrature
  // volume (the sum of its four weights) as that point's weight.
  std::vector<double> centroid_grad_;
  std::vector<double> centroid_weight_;
  std::vector<double> mass_;
  double total_mass_ = 0.0;
  double volume_ = 0.0;
  double min_spacing_ = 0.0;
  std::vector<int> inner_rim_;  // rim nodes on the inner faces (they span the rim plane)
  // The elements at each node: node a's are incidence_[incidence_start_[a] ..
  // incidence_start_[a + 1]), each as element * 10 + local node, in element order.
  std::vector<int> incidence_start_;
  std::vector<int> incidence_;
  // The inner faces at each node, likewise (face * 6 + local node, in face order).
  std::vector<int> face_incidence_start_;
  std::vector<int> face_incidence_;
};

}  // namespace snapjump::fem
