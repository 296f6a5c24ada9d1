// A popper "case": everything that describes one simulated or predicted experiment, in SI.
//
// Read from a TOML case file (see README.md, "Case files") and/or command-line overrides, checked
// once here so that every later stage can trust it. Any error names the key, where it came from
// (file and line, or the flag), and what was expected.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config/input_error.hpp"
#include "config/units.hpp"

namespace snapjump::config {

inline constexpr double kStandardGravity = 9.80665;  // m/s^2
// popper.mass when the case does not give it (docs/popper.md, "Assumptions") [kg].
inline constexpr double kDefaultPopperMass = 0.300;

struct Shell {
  double R = 0.0;    // mid-surface radius of curvature [m]
  double h = 0.0;    // thickness [m]
  double phi = 0.0;  // polar angle of the rim, from the apex [rad]
  // A designer's own shell: a gmsh .msh file (quadratic tetrahedra with the physical groups of
  // docs/shells.md), as an absolute path (a case file's relative path is resolved against its
  // folder). Empty: the spherical cap of R, h, phi. With a mesh, R and h still set the scales
  // (the grid spacing h / cells, Zoelly's p_c of the protocol, the onset w / R < 0.03).
  std::string mesh;
};

// The shell's material law (fem/constitutive.hpp): the paper's compressible neo-Hookean solid, or
// Gent's, which stiffens as the chains near their locking stretch. E and nu are the small-strain
// moduli under either.
enum class Law { NeoHookean, Gent };
std::string_view to_string(Law l);
std::optional<Law> parse_law(std::string_view text);
inline constexpr std::string_view kLawChoices = R"("neo-Hookean" or "Gent")";

struct Material {
  double E = 0.0;    // Young's modulus [Pa]
  double nu = 0.0;   // Poisson's ratio [-]
  double rho = 0.0;  // density [kg/m^3]
  Law law = Law::NeoHookean;
  std::optional<double> gent_jm;  // Gent's locking value of I1 - 3 [-] (law = Gent only)
};

// The apparatus (paper, Fig. 1(d)): the popper (shell, acrylic container, the rail's two shafts
// sliding in air bushings) hangs on a wire over pulleys to a counterweight. Their weights differ
// by the net weight; their masses add up to the inertia the plate's force accelerates.
struct Popper {
  double net_weight = 0.0;  // the paper's mg: weight of the popper minus the counterweight [N]
  double mass = 0.0;        // the popper's own mass: shell + container + the rail's shafts [kg]
  // Axial stiffness of the wire between popper and counterweight [N/m]; absent: a rigid wire.
  std::optional<double> wire_stiffness;
  // mass - net_weight / g [kg].
  [[nodiscard]] double counterweight() const;
  // mass + counterweight: the inertia of the apparatus with a rigid wire, the theory's m in
  // t_c = sqrt(m R / (E h^2)) [kg].
  [[nodiscard]] double moving_mass() const;
};

struct Friction {
  double mu = 0.0;  // Coulomb coefficient between shell and plate [-]
};

struct Gas {
  double container_volume = 0.0;  // rigid container volume above the rim plane [m^3]
  double p0 = 0.0;                // atmospheric pressure [Pa]
  double alpha_n = 0.0;           // valve law d2Jn/dt2 = -alpha_n dp [1/(Pa s^2)]
  double beta_n = 0.0;            // valve law dJn/dt(0) = -beta_n dp(0) [1/(Pa s)]
};

// The pressure difference (outside minus inside) held at release, either absolute or as a
// fraction of Zoelly's buckling pressure p_c of the case (resolved by the theory library).
// How the axisymmetric preparation passes a maximum of the inverted segment below delta_p_j
// (a crease's nucleation): in time, the suction raised from that maximum by the dynamics; or
// along the branch, the shell snapping at constant suction onto the branch's later part and
// followed on it to delta_p_j (axi::BranchOptions::through_snaps).
enum class InvertedSnaps { InTime, AlongBranch };
std::string_view to_string(InvertedSnaps s);
// "in time", "along the branch"; nullopt for anything else.
std::optional<InvertedSnaps> parse_inverted_snaps(std::string_view text);
inline constexpr std::string_view kInvertedSnapsChoices = R"("in time" or "along the branch")";

struct Protocol {
  std::optional<double> delta_p_j;  // [Pa], when given absolutely
  double delta_p_j_over_pc = 0.0;   // used when delta_p_j is not given
  InvertedSnaps inverted_snaps = InvertedSnaps::InTime;
};

enum class Resolution { Coarse, Default, Fine };
std::string_view to_string(Resolution r);
// "coarse", "default", "fine"; nullopt for anything else.
std::optional<Resolution> parse_resolution(std::string_view text);
// The words each of these parsers reads, for messages.
inline constexpr std::string_view kResolutionChoices = R"("coarse", "default" or "fine")";

// The discretisation of the shell: the paper's 3D MPM, or the axisymmetric finite elements.
enum class Model { ThreeD, Axisymmetric };
std::string_view to_string(Model m);
// "3d", "axisymmetric"; nullopt for anything else.
std::optional<Model> parse_model(std::string_view text);
inline constexpr std::string_view kModelChoices = R"("3d" or "axisymmetric")";

// Where the elements integrate the bulk part of the energy, lambda/2 (ln J)^2: with the rest
// (full; the 3D model's default, the paper's element) or at fewer points (reduced; the
// axisymmetric model's default): 3D at each tetrahedron's centroid, axisymmetric at 2 x 2 Gauss
// points instead of 3 x 3. Reduced keeps the elements from locking as nu approaches 1/2.
enum class BulkIntegration { Full, Reduced };
std::string_view to_string(BulkIntegration b);
// "full", "reduced"; nullopt for anything else.
std::optional<BulkIntegration> parse_bulk_integration(std::string_view text);
inline constexpr std::string_view kBulkIntegrationChoices = R"("full" or "reduced")";

// What a resolution preset sets where the case does not: the one table of the presets, read by
// the cap mesher (element size, layers) and the popper (grid, axisymmetric elements).
struct ResolutionPreset {
  // 3D: in-surface element size over the bending length sqrt(h R) (numerics.element_size
  // overrides it); the default is sized so that the default popper's jump runs in minutes on two
  // cores, coarse serves sweeps, fine is the convergence check.
  double element_size_over_sqrt_hR;
  int layers;  // 3D: quadratic elements through h (numerics.elements_through_thickness)
  // 3D: the grid spacing is h over this many cells (numerics.grid_spacing); the default stays at
  // h/4 for the cost of the sparse grid's blocks at finer cells (docs/popper.md).
  double grid_cells_per_thickness;
  // Axisymmetric: elements through h (numerics.elements_through_thickness); along the meridian
  // twice as long as thick, or numerics.element_size long.
  int axi_through;
};
const ResolutionPreset& preset(Resolution r);

struct Numerics {
  Model model = Model::ThreeD;
  // The model's own when absent (3D full, axisymmetric reduced).
  std::optional<BulkIntegration> bulk_integration;
  Resolution resolution = Resolution::Default;
  std::optional<double> element_size;  // [m]; from the resolution preset when absent
  // A graded 3D cap (mesh::CapSpec): elements of rim_element_size within rim_band of the rim and
  // of contact_element_size within contact_band of the apex (arc lengths on the mid-surface),
  // growing from there to element_size. Each pair is given whole or not at all.
  std::optional<double> rim_element_size, rim_band;          // [m]
  std::optional<double> contact_element_size, contact_band;  // [m]
  // Axisymmetric: the inner surface's node nearest this arc length from the rim is a crease's
  // root, with a fan of three elements (axi::MeshSpec::crease_fan_from_rim); none when absent.
  std::optional<double> crease_fan;  // [m]
  // And every second inner corner node within this arc length about it (a band of roots).
  std::optional<double> crease_fan_band;  // [m]
  // Axisymmetric: every inner corner node a crease's root, the first 1 or 2 layers of elements
  // through h tiled into fans (axi::MeshSpec::fan_layer); the structured mesh when absent or 0.
  std::optional<int> fan_layer;
  // Axisymmetric: a seeded crease, the inner corner node nearest this arc length from the rim
  // given a rosette of four elements and moved into the solid by crease_seed_depth
  // (axi::MeshSpec::crease_seeds_from_rim); none when absent.
  std::optional<double> crease_seed;  // [m]
  // And a second one, its own rosette, notched by the same depth (a shell that creases twice).
  std::optional<double> second_crease_seed;  // [m]
  std::optional<double> crease_seed_depth;   // [m]; 0 when absent
  std::optional<double> grid_spacing;        // [m]; from the resolution preset (a fraction of h)
  // Quadratic elements across h; from the resolution preset when absent (3D: coarse and default
  // 1, fine 2; axisymmetric: 2, 4, 8).
  std::optional<int> elements_through_thickness;
  // [s] after the release: the cap on a run, which ends at the apex of the flight at the latest
  // here; popper::default_end when absent.
  std::optional<double> end_time;
  // 3D elastic time step factor; popper::kTimeStepFactor when absent.
  std::optional<double> time_step_factor;
};

struct Case {
  std::string title;
  Shell shell;
  Material material;
  Popper popper;
  Friction friction;
  Gas gas;
  Protocol protocol;
  Numerics numerics;
  std::string source;                      // the file, or "built-in default case"
  std::vector<std::string> defaults_used;  // "material.nu = 0.45", one per defaulted key
  // Values given outside the file (flags, a sweep's settings): {"shell.h", "2 mm"}. The title
  // says so, so that a case file's title does not name a popper the flags have changed.
  std::vector<std::pair<std::string, std::string>> overridden;
  // What the reader noticed in given values it accepted, for the command line to say: each number
  // written without a unit for a quantity that has one (read in SI), and each value outside what
  // a popper can plausibly be (config/plausibility.hpp). Each message names where the value was
  // written, the key and what it was read as; a value outside its range is not also a bare one.
  std::vector<std::string> bare_numbers;
  std::vector<std::string> implausible;
};

// Bad input. what() is the whole message, naming the key and where it was written.
class CaseError : public InputError {
 public:
  using InputError::InputError;
};

// A value given outside the file, e.g. on the command line: key "shell.R", text "30mm",
// origin "--R" (used in messages).
struct Override {
  std::string key;
  std::string text;
  std::string origin;
};

// One scalar key of the case format: where it lives, its dimension, its default.
struct KeySpec {
  std::string_view table;  // "shell"
  std::string_view name;   // "R"
  std::string_view flag;   // "R" for --R
  units::Dimension dimension;
  bool required;                     // must be in a case file
  std::optional<double> default_si;  // used when absent and not required
  std::string_view default_text;     // how the default is shown ("0.45", "80 deg")
  std::string_view example;          // a typical value with its unit ("2 mm")
  std::string_view help;
  // Where the value lives in a Case: a field that always holds one, or one that holds a value only
  // when the case gives it. Exactly one is set; the reader and to_toml() go through them.
  double* (*field)(Case&) = nullptr;
  std::optional<double>* (*optional_field)(Case&) = nullptr;
};

// All scalar keys of the case format, in the order of the documentation.
std::span<const KeySpec> quantity_keys();
// The key spec of a dotted key such as "shell.h"; nullptr for an unknown key.
const KeySpec* find_quantity_key(std::string_view dotted);

// Reads and checks a case file. Throws CaseError.
Case load_case_file(const std::filesystem::path& path, std::span<const Override> overrides = {},
                    const units::UnitParser* parser = nullptr);

// Parses case text; `source` names it in messages. Throws CaseError.
Case parse_case(std::string_view toml_text, std::string_view source,
                std::span<const Override> overrides = {},
                const units::UnitParser* parser = nullptr);

// The paper's Fig. 2(a) popper, (R, h) = (30, 2.0) mm, mg = 0.48 N, with overrides applied.
Case default_case(std::span<const Override> overrides = {},
                  const units::UnitParser* parser = nullptr);

// The text of the built-in default case (the same as examples/default.toml).
std::string_view default_case_text();

// The case as a case file with every value in SI with its unit, "0.03 m" (defaults written out),
// so that a run can be repeated or resumed exactly: parse_case(to_toml(c)) gives back the same
// values.
std::string to_toml(const Case& c);

}  // namespace snapjump::config
