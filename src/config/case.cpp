#include "config/case.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>

#include "config/files.hpp"
#include "config/plausibility.hpp"
#include "config/text.hpp"

namespace snapjump::config {
namespace {

using units::Dimension;

constexpr double kDeg = std::numbers::pi / 180.0;

constexpr KeySpec kKeys[] = {
    {"shell", "R", "R", Dimension::Length, true, std::nullopt, "", "30 mm",
     "mid-surface radius of curvature", +[](Case& c) { return &c.shell.R; }},
    {"shell", "h", "h", Dimension::Length, true, std::nullopt, "", "2 mm", "shell thickness",
     +[](Case& c) { return &c.shell.h; }},
    {"shell", "phi", "phi", Dimension::Angle, false, 80.0 * kDeg, "80 deg", "80 deg",
     "polar angle of the rim, measured from the apex", +[](Case& c) { return &c.shell.phi; }},
    {"material", "E", "E", Dimension::Pressure, true, std::nullopt, "", "1.2 MPa",
     "Young's modulus", +[](Case& c) { return &c.material.E; }},
    {"material", "nu", "nu", Dimension::Dimensionless, false, 0.45, "0.45", "0.45",
     "Poisson's ratio", +[](Case& c) { return &c.material.nu; }},
    {"material", "rho", "rho", Dimension::Density, false, 1160.0, "1160 kg/m^3", "1160 kg/m^3",
     "density", +[](Case& c) { return &c.material.rho; }},
    {"material", "gent_jm", "gent-jm", Dimension::Dimensionless, false, std::nullopt, "", "20",
     "Gent's locking value Jm of I1 - 3 (needed by material.law = \"Gent\"; no default: it is "
     "the rubber's own, from its stress-stretch curve)",
     nullptr, +[](Case& c) { return &c.material.gent_jm; }},
    {"popper", "net_weight", "net-weight", Dimension::Force, true, std::nullopt, "", "0.48 N",
     "net weight mg: the popper's weight less the counterweight's",
     +[](Case& c) { return &c.popper.net_weight; }},
    {"popper", "mass", "popper-mass", Dimension::Mass, false, kDefaultPopperMass,
     "300 g (net_weight / g when heavier: no counterweight)", "300 g",
     "the popper's own mass: shell + container + the rail's shafts (an estimate, docs/popper.md)",
     +[](Case& c) { return &c.popper.mass; }},
    {"popper", "wire_stiffness", "wire-stiffness", Dimension::Stiffness, false, std::nullopt, "",
     "3 kN/m", "axial stiffness of the wire to the counterweight (a rigid wire when absent)",
     nullptr, +[](Case& c) { return &c.popper.wire_stiffness; }},
    {"friction", "mu", "mu", Dimension::Dimensionless, false, 0.3, "0.3", "0.3",
     "Coulomb friction coefficient between shell and plate",
     +[](Case& c) { return &c.friction.mu; }},
    {"gas", "container_volume", "container-volume", Dimension::Volume, false, 200e-6, "200 mL",
     "200 mL", "volume of the rigid container above the rim plane",
     +[](Case& c) { return &c.gas.container_volume; }},
    {"gas", "p0", "p0", Dimension::Pressure, false, 101325.0, "101325 Pa", "101325 Pa",
     "atmospheric pressure", +[](Case& c) { return &c.gas.p0; }},
    {"gas", "alpha_n", "alpha-n", Dimension::ValveAcceleration, false, 1.0e-3, "1.0e-3 Pa^-1 s^-2",
     "1.0e-3 Pa^-1 s^-2", "valve law: d2Jn/dt2 = -alpha_n delta_p",
     +[](Case& c) { return &c.gas.alpha_n; }},
    {"gas", "beta_n", "beta-n", Dimension::ValveRate, false, 5.0e-5, "5.0e-5 Pa^-1 s^-1",
     "5.0e-5 Pa^-1 s^-1", "valve law: dJn/dt(0) = -beta_n delta_p(0)",
     +[](Case& c) { return &c.gas.beta_n; }},
    {"protocol", "delta_p_j", "delta-p-j", Dimension::Pressure, false, std::nullopt, "", "3 kPa",
     "pressure difference (outside - inside) at release", nullptr,
     +[](Case& c) { return &c.protocol.delta_p_j; }},
    {"protocol", "delta_p_j_over_pc", "delta-p-j-over-pc", Dimension::Dimensionless, false, 0.5,
     "0.5", "0.5", "delta_p_j as a fraction of Zoelly's p_c (when delta_p_j is not given)",
     +[](Case& c) { return &c.protocol.delta_p_j_over_pc; }},
    {"numerics", "grid_spacing", "grid-spacing", Dimension::Length, false, std::nullopt, "",
     "0.25 mm", "MPM grid spacing (from the resolution preset when absent: h/4, h/4, h/8)", nullptr,
     +[](Case& c) { return &c.numerics.grid_spacing; }},
    {"numerics", "element_size", "element-size", Dimension::Length, false, std::nullopt, "", "1 mm",
     "target mesh element size (from the resolution preset when absent)", nullptr,
     +[](Case& c) { return &c.numerics.element_size; }},
    {"numerics", "rim_element_size", "rim-element-size", Dimension::Length, false, std::nullopt, "",
     "1 mm",
     "3D: element size next to the rim, where the inverted cap folds (with numerics.rim_band; "
     "uniform at element_size when absent)",
     nullptr, +[](Case& c) { return &c.numerics.rim_element_size; }},
    {"numerics", "rim_band", "rim-band", Dimension::Length, false, std::nullopt, "", "4 mm",
     "3D: arc length from the rim over which numerics.rim_element_size holds; beyond it the "
     "elements grow by 30 % of the distance up to element_size",
     nullptr, +[](Case& c) { return &c.numerics.rim_band; }},
    {"numerics", "contact_element_size", "contact-element-size", Dimension::Length, false,
     std::nullopt, "", "2 mm",
     "3D: element size around the apex, where the plate's contact spreads (with "
     "numerics.contact_band)",
     nullptr, +[](Case& c) { return &c.numerics.contact_element_size; }},
    {"numerics", "contact_band", "contact-band", Dimension::Length, false, std::nullopt, "",
     "18 mm", "3D: arc length from the apex over which numerics.contact_element_size holds",
     nullptr, +[](Case& c) { return &c.numerics.contact_band; }},
    {"numerics", "crease_fan", "crease-fan", Dimension::Length, false, std::nullopt, "", "1.5 mm",
     "axisymmetric: arc length from the rim along the inner surface of a crease's root, given a "
     "fan of three elements so that a crease closed there folds no element (none when absent)",
     nullptr, +[](Case& c) { return &c.numerics.crease_fan; }},
    {"numerics", "crease_fan_band", "crease-fan-band", Dimension::Length, false, std::nullopt, "",
     "1.5 mm",
     "axisymmetric: with numerics.crease_fan, fans at every second inner-surface node within "
     "this arc length about it, where the crease's root is known only to within it",
     nullptr, +[](Case& c) { return &c.numerics.crease_fan_band; }},
    {"numerics", "crease_seed", "crease-seed", Dimension::Length, false, std::nullopt, "",
     "3.35 mm",
     "axisymmetric: arc length from the rim along the inner surface of a seeded crease's root, "
     "given a rosette of four elements (none when absent)",
     nullptr, +[](Case& c) { return &c.numerics.crease_seed; }},
    {"numerics", "second_crease_seed", "second-crease-seed", Dimension::Length, false, std::nullopt,
     "", "2.1 mm",
     "axisymmetric: with numerics.crease_seed, the arc length from the rim of a second seeded "
     "root, its own rosette notched as deep (none when absent)",
     nullptr, +[](Case& c) { return &c.numerics.second_crease_seed; }},
    {"numerics", "crease_seed_depth", "crease-seed-depth", Dimension::Length, false, std::nullopt,
     "", "25 um",
     "axisymmetric: with numerics.crease_seed, how far its node is moved into the solid, a notch "
     "where the crease can start (0 when absent)",
     nullptr, +[](Case& c) { return &c.numerics.crease_seed_depth; }},
    {"numerics", "time_step_factor", "time-step-factor", Dimension::Dimensionless, false,
     std::nullopt, "", "0.5",
     "3D elastic time step factor: dt = factor * smallest node spacing / p-wave speed (0.5 when "
     "absent; build/cfl_scan coarse mpm finds 0.6 stable and 0.7 not)",
     nullptr, +[](Case& c) { return &c.numerics.time_step_factor; }},
    {"numerics", "end_time", "end-time", Dimension::Time, false, std::nullopt, "", "0.5 s",
     "cap on the simulated time after the release: the run ends at the apex of the flight, at "
     "the latest here (a cap from the case when absent: docs/popper.md); with --resume, a later "
     "cap to continue a run that went to its own",
     nullptr, +[](Case& c) { return &c.numerics.end_time; }},
};

// Keys that are not scalar quantities.
constexpr std::string_view kResolutionKey = "resolution";
constexpr std::string_view kLayersKey = "elements_through_thickness";
constexpr std::string_view kModelKey = "model";
constexpr std::string_view kBulkKey = "bulk_integration";
constexpr std::string_view kLawKey = "law";
constexpr std::string_view kMeshKey = "mesh";
constexpr std::string_view kFanLayerKey = "fan_layer";
constexpr std::string_view kInvertedSnapsKey = "inverted_snaps";
constexpr std::string_view kTitleKey = "title";

constexpr std::string_view kDefaultCase =
    R"(# The paper's Fig. 2(a) popper: (R, h) = (30, 2.0) mm, mg = 0.48 N.
title = "Fig. 2(a) popper, (R, h) = (30, 2.0) mm, mg = 0.48 N"

[shell]
R = "30 mm"
h = "2.0 mm"
phi = "80 deg"

[material]
E = "1.2 MPa"

[popper]
net_weight = "0.48 N"
)";

struct Entry {
  double si = 0.0;
  std::string text;    // as the user wrote it, for messages
  std::string origin;  // "case.toml:3" or "--R"
  bool bare = false;   // a number without a unit for a quantity that has one: read in SI
};

// Whether `text` is a bare number for k: a quantity with a unit written without one.
bool bare(const KeySpec& k, std::string_view text) {
  return k.dimension != Dimension::Dimensionless && units::is_bare_number(text);
}

std::string full_key(const KeySpec& k) { return fmt::format("{}.{}", k.table, k.name); }

const KeySpec* find_key(std::string_view table, std::string_view name) {
  for (const auto& k : kKeys) {
    if (k.table == table && k.name == name) return &k;
  }
  return nullptr;
}

const KeySpec& spec(std::string_view table, std::string_view name) {
  const auto* k = find_key(table, name);
  if (k == nullptr) throw std::logic_error("unknown case key");
  return *k;
}

bool known_table(std::string_view table) {
  return std::any_of(std::begin(kKeys), std::end(kKeys),
                     [&](const KeySpec& k) { return k.table == table; });
}

std::string keys_of(std::string_view table) {
  std::string out;
  for (const auto& k : kKeys) {
    if (k.table != table) continue;
    if (!out.empty()) out += ", ";
    out += k.name;
  }
  if (table == "numerics")
    out += fmt::format(", {}, {}, {}, {}, {}", kModelKey, kResolutionKey, kLayersKey, kBulkKey,
                       kFanLayerKey);
  if (table == "shell") out += fmt::format(", {}", kMeshKey);
  if (table == "material") out += fmt::format(", {}", kLawKey);
  if (table == "protocol") out += fmt::format(", {}", kInvertedSnapsKey);
  return out;
}

std::string tables() {
  std::string out;
  for (const auto& k : kKeys) {
    const auto t = fmt::format("[{}]", k.table);
    if (out.find(t) == std::string::npos) out += (out.empty() ? "" : ", ") + t;
  }
  return out;
}

std::string at(std::string_view source, const toml::source_region& region) {
  if (region.begin.line == 0) return std::string(source);
  return fmt::format("{}:{}", source, region.begin.line);
}

class Reader {
 public:
  Reader(std::string_view source, const units::UnitParser& parser)
      : source_(source), parser_(parser) {}

  void read_document(const toml::table& doc, Case& c) {
    for (auto&& [key, node] : doc) {
      const auto name = key.str();
      if (name == kTitleKey) {
        const auto* s = node.as_string();
        if (s == nullptr) fail(node.source(), "title must be a string");
        c.title = text::capped_title(s->get());
        continue;
      }
      const auto* table = node.as_table();
      if (table == nullptr || !known_table(name)) {
        fail(key.source(), fmt::format("unknown {} '{}'; a case file has {} and a title",
                                       table ? "table" : "key", text::excerpt(name), tables()));
      }
      read_table(name, *table, c);
    }
  }

  void apply(const Override& o) {
    const auto* k = find_quantity_key(o.key);
    if (k == nullptr) {
      throw CaseError(fmt::format("{}: unknown case key '{}'", o.origin, text::excerpt(o.key)));
    }
    entries_[full_key(*k)] =
        Entry{convert(*k, o.text, o.origin), o.text, o.origin, bare(*k, o.text)};
  }

  [[nodiscard]] const Entry* find(const KeySpec& k) const {
    const auto it = entries_.find(full_key(k));
    return it == entries_.end() ? nullptr : &it->second;
  }

  // The value of `k`, or its default (recorded in defaults_used), or nullopt.
  std::optional<double> value(const KeySpec& k, Case& c) const {
    if (const auto* e = find(k)) return e->si;
    if (k.required) {
      throw CaseError(fmt::format(
          "{}: missing required value {} ({}, {}, e.g. \"{}\"); add it under [{}]", source_,
          full_key(k), k.help, units::dimension_name(k.dimension), k.example, k.table));
    }
    if (k.default_si)
      c.defaults_used.push_back(fmt::format("{} = {}", full_key(k), k.default_text));
    return k.default_si;
  }

  // "case.toml:4: shell.h = "35 mm"" for messages about a value.
  [[nodiscard]] std::string where(const KeySpec& k) const {
    if (const auto* e = find(k)) {
      return fmt::format("{}: {} = {}", e->origin, full_key(k), text::excerpt(e->text));
    }
    return fmt::format("{}: {} (default {})", source_, full_key(k), k.default_text);
  }

  [[noreturn]] void fail(const toml::source_region& region, const std::string& what) const {
    throw CaseError(fmt::format("{}: {}", at(source_, region), what));
  }

 private:
  // A string key's value as parse reads it; anything else (not a string, an unknown word) fails
  // naming the key and the words parse reads.
  template <typename Parse>
  auto parsed_string(const toml::node& node, const toml::key& key, std::string_view table,
                     Parse parse, std::string_view choices) const {
    const auto* s = node.as_string();
    const auto v = parse(s ? std::string_view(s->get()) : std::string_view());
    if (!v) fail(key.source(), fmt::format("{}.{} must be {}", table, key.str(), choices));
    return *v;
  }

  void read_table(std::string_view table_name, const toml::table& table, Case& c) {
    for (auto&& [key, node] : table) {
      const auto name = key.str();
      const auto origin = at(source_, key.source());
      if (table_name == "numerics" && name == kResolutionKey) {
        c.numerics.resolution =
            parsed_string(node, key, table_name, parse_resolution, kResolutionChoices);
        continue;
      }
      if (table_name == "numerics" && name == kModelKey) {
        c.numerics.model = parsed_string(node, key, table_name, parse_model, kModelChoices);
        continue;
      }
      if (table_name == "protocol" && name == kInvertedSnapsKey) {
        c.protocol.inverted_snaps =
            parsed_string(node, key, table_name, parse_inverted_snaps, kInvertedSnapsChoices);
        continue;
      }
      if (table_name == "material" && name == kLawKey) {
        c.material.law = parsed_string(node, key, table_name, parse_law, kLawChoices);
        continue;
      }
      if (table_name == "numerics" && name == kBulkKey) {
        c.numerics.bulk_integration =
            parsed_string(node, key, table_name, parse_bulk_integration, kBulkIntegrationChoices);
        continue;
      }
      if (table_name == "shell" && name == kMeshKey) {
        const auto* s = node.as_string();
        if (s == nullptr || s->get().empty()) {
          fail(key.source(), "shell.mesh must be the path of a gmsh .msh file, e.g. \"cap.msh\"");
        }
        if (text::has_control_characters(s->get())) {
          fail(key.source(),
               fmt::format("shell.mesh '{}' holds control characters", text::excerpt(s->get())));
        }
        std::filesystem::path p(s->get());
        if (p.is_relative() && source_ != "built-in default case") {
          p = std::filesystem::path(std::string(source_)).parent_path() / p;
        }
        std::error_code ec;
        const auto absolute = std::filesystem::absolute(p, ec);
        c.shell.mesh = (ec ? p : absolute).lexically_normal().string();
        continue;
      }
      if (table_name == "numerics" && name == kFanLayerKey) {
        const auto* i = node.as_integer();
        if (i == nullptr || i->get() < 0 || i->get() > 2) {
          fail(key.source(),
               "numerics.fan_layer must be 0, 1 or 2: the layers of elements through h tiled so "
               "that every inner corner node is a crease's root (0: none)");
        }
        c.numerics.fan_layer = static_cast<int>(i->get());
        continue;
      }
      if (table_name == "numerics" && name == kLayersKey) {
        const auto* i = node.as_integer();
        if (i == nullptr || i->get() < 1 || i->get() > 16) {
          fail(key.source(), "numerics.elements_through_thickness must be an integer from 1 to 16");
        }
        c.numerics.elements_through_thickness = static_cast<int>(i->get());
        continue;
      }
      const auto* k = find_key(table_name, name);
      if (k == nullptr) {
        fail(key.source(), fmt::format("unknown key '{}' in [{}]; it takes {}", text::excerpt(name),
                                       table_name, keys_of(table_name)));
      }
      std::string text;
      double si = 0.0;
      // A TOML number has no unit.
      bool is_bare = k->dimension != Dimension::Dimensionless;
      if (const auto* s = node.as_string()) {
        text = fmt::format("\"{}\"", s->get());
        si = convert(*k, s->get(), origin);
        is_bare = bare(*k, s->get());
      } else if (const auto* i = node.as_integer()) {
        text = fmt::format("{}", i->get());
        si = convert(*k, text, origin);
      } else if (const auto* f = node.as_floating_point()) {
        text = fmt::format("{}", f->get());
        if (!std::isfinite(f->get())) {
          fail(key.source(), fmt::format("{} = {} is not a finite number", full_key(*k), text));
        }
        si = convert(*k, text, origin);
      } else {
        fail(key.source(), fmt::format("{} must be a number or a string with a unit (e.g. \"{}\")",
                                       full_key(*k), k->example));
      }
      entries_[full_key(*k)] = Entry{si, text, origin, is_bare};
    }
  }

  double convert(const KeySpec& k, std::string_view text, std::string_view origin) const {
    try {
      return parser_.parse(text, k.dimension);
    } catch (const units::UnitError& e) {
      throw CaseError(fmt::format("{}: {}: {}", origin, full_key(k), e.what()));
    }
  }

  std::string source_;
  const units::UnitParser& parser_;
  std::map<std::string, Entry> entries_;
};

// The value with the unit of the key's example ("40 mm" for shell.R), for hints.
std::string with_example_unit(const KeySpec& k, double value) {
  const auto space = k.example.find(' ');
  return fmt::format("{:.6g} {}", value,
                     space == std::string_view::npos ? "" : k.example.substr(space + 1));
}

// Case::bare_numbers and Case::implausible, from the values given.
void note_readings(const Reader& r, Case& c) {
  for (const auto& k : kKeys) {
    const auto* e = r.find(k);
    if (e == nullptr) continue;
    const auto read_as = fmt::format("{:.6g} {}", e->si, units::si_unit(k.dimension));
    const auto hint =
        fmt::format("write its unit if another is meant, e.g. \"{}\"", with_example_unit(k, e->si));
    const auto* range = plausible_range(full_key(k));
    if (range != nullptr && !range->holds(e->si)) {
      c.implausible.push_back(
          fmt::format("{} is read as {}{}, outside {}, what {} can plausibly be: {}{}", r.where(k),
                      read_as, e->bare ? " (a number without a unit is in SI)" : "", range->text,
                      range->what, range->why, e->bare ? "; " + hint : ""));
    } else if (e->bare) {
      c.bare_numbers.push_back(
          fmt::format("{} has no unit and is read in SI, as {}; {}", r.where(k), read_as, hint));
    }
  }
}

void check(bool ok, const std::string& message) {
  if (!ok) throw CaseError(message);
}

// protocol.delta_p_j given absolutely replaces its fraction of p_c: the fraction is then neither
// read (nor defaulted) nor written.
bool replaced_by_absolute_value(const KeySpec& k, const Case& c) {
  return k.table == "protocol" && k.name == "delta_p_j_over_pc" && c.protocol.delta_p_j;
}

Case build(const Reader& r, Case c) {
  const auto positive = [&](std::string_view t, std::string_view n, double v) {
    check(v > 0.0, fmt::format("{} must be positive", r.where(spec(t, n))));
  };

  const auto* dpj = r.find(spec("protocol", "delta_p_j"));
  const auto* dpj_ratio = r.find(spec("protocol", "delta_p_j_over_pc"));
  if (dpj != nullptr && dpj_ratio != nullptr) {
    throw CaseError(fmt::format(
        "{}: give protocol.delta_p_j or protocol.delta_p_j_over_pc, not both", dpj->origin));
  }
  // Every quantity into its field, in the table's order (the order of the defaults' list;
  // protocol.delta_p_j comes before its fraction).
  for (const auto& k : kKeys) {
    if (k.optional_field != nullptr) {
      if (const auto* e = r.find(k)) *k.optional_field(c) = e->si;
    } else if (!replaced_by_absolute_value(k, c)) {
      *k.field(c) = *r.value(k, c);
    }
  }
  if (r.find(spec("popper", "mass")) == nullptr) {
    // A popper heavier than the default is loaded with weights and needs no counterweight.
    c.popper.mass = std::max(c.popper.mass, c.popper.net_weight / kStandardGravity);
  }

  // Physical admissibility, each message naming the key.
  positive("shell", "R", c.shell.R);
  positive("shell", "h", c.shell.h);
  check(c.shell.h < c.shell.R, fmt::format("{} must be smaller than shell.R ({} m)",
                                           r.where(spec("shell", "h")), c.shell.R));
  check(c.shell.phi > 0.0 && c.shell.phi < std::numbers::pi,
        fmt::format("{} must lie strictly between 0 and 180 deg (a bare number is in radians: "
                    "write \"80 deg\" for degrees)",
                    r.where(spec("shell", "phi"))));
  positive("material", "E", c.material.E);
  // nu = 1/2 (incompressible) is admitted: the shell theory holds there. The compressible
  // neo-Hookean body of the simulator needs nu < 1/2 and says so itself.
  check(c.material.nu > -1.0 && c.material.nu <= 0.5,
        fmt::format("{} must lie in (-1, 0.5]", r.where(spec("material", "nu"))));
  positive("material", "rho", c.material.rho);
  if (c.material.law == Law::Gent) {
    check(c.material.gent_jm.has_value(),
          "material.law = \"Gent\" needs material.gent_jm, the rubber's locking value of I1 - 3 "
          "(no default)");
    if (c.material.gent_jm) positive("material", "gent_jm", *c.material.gent_jm);
  } else {
    check(!c.material.gent_jm.has_value(),
          fmt::format("{} is a parameter of Gent's law: give material.law = \"Gent\" with it",
                      r.where(spec("material", "gent_jm"))));
  }
  positive("popper", "net_weight", c.popper.net_weight);
  positive("popper", "mass", c.popper.mass);
  check(c.popper.mass * kStandardGravity >= c.popper.net_weight * (1.0 - 1e-12),
        fmt::format("{} must be at least net_weight / g = {:.6g} kg: the counterweight, whose "
                    "weight is the popper's less the net weight, cannot be negative",
                    r.where(spec("popper", "mass")), c.popper.net_weight / kStandardGravity));
  if (c.popper.wire_stiffness) positive("popper", "wire_stiffness", *c.popper.wire_stiffness);
  check(c.friction.mu >= 0.0,
        fmt::format("{} must not be negative", r.where(spec("friction", "mu"))));
  positive("gas", "container_volume", c.gas.container_volume);
  positive("gas", "p0", c.gas.p0);
  positive("gas", "alpha_n", c.gas.alpha_n);
  check(c.gas.beta_n >= 0.0,
        fmt::format("{} must not be negative", r.where(spec("gas", "beta_n"))));
  if (c.protocol.delta_p_j) {
    check(*c.protocol.delta_p_j >= 0.0 && *c.protocol.delta_p_j < c.gas.p0,
          fmt::format("{} must lie in [0, p0): it is how far the inside is below atmosphere",
                      r.where(spec("protocol", "delta_p_j"))));
  } else {
    check(c.protocol.delta_p_j_over_pc >= 0.0,
          fmt::format("{} must not be negative", r.where(spec("protocol", "delta_p_j_over_pc"))));
  }
  if (!c.shell.mesh.empty()) {
    std::error_code ec;
    check(std::filesystem::is_regular_file(c.shell.mesh, ec),
          fmt::format("{}: shell.mesh = \"{}\": no such file", c.source, c.shell.mesh));
  }
  if (c.numerics.element_size) positive("numerics", "element_size", *c.numerics.element_size);
  const auto graded_pair = [&](std::string_view size, const std::optional<double>& s,
                               std::string_view band, const std::optional<double>& b) {
    check(s.has_value() == b.has_value(),
          fmt::format("numerics.{} and numerics.{} go together: give both or neither", size, band));
    if (s) positive("numerics", size, *s);
    if (b) positive("numerics", band, *b);
  };
  graded_pair("rim_element_size", c.numerics.rim_element_size, "rim_band", c.numerics.rim_band);
  graded_pair("contact_element_size", c.numerics.contact_element_size, "contact_band",
              c.numerics.contact_band);
  if (c.numerics.grid_spacing) positive("numerics", "grid_spacing", *c.numerics.grid_spacing);
  if (c.numerics.crease_fan) positive("numerics", "crease_fan", *c.numerics.crease_fan);
  check(!(c.numerics.fan_layer.value_or(0) > 0 && c.numerics.crease_fan),
        "numerics.fan_layer makes every inner corner node a crease's root: give no "
        "numerics.crease_fan with it");
  if (c.numerics.crease_fan_band) {
    positive("numerics", "crease_fan_band", *c.numerics.crease_fan_band);
    check(c.numerics.crease_fan.has_value(),
          "numerics.crease_fan_band spreads the fans about numerics.crease_fan: give both");
  }
  if (c.numerics.crease_seed) positive("numerics", "crease_seed", *c.numerics.crease_seed);
  check(
      !(c.numerics.crease_seed && (c.numerics.crease_fan || c.numerics.fan_layer.value_or(0) > 0)),
      "numerics.crease_seed gives one node a rosette of its own: give neither numerics.crease_fan "
      "nor numerics.fan_layer with it");
  if (c.numerics.second_crease_seed) {
    positive("numerics", "second_crease_seed", *c.numerics.second_crease_seed);
    check(c.numerics.crease_seed.has_value(),
          "numerics.second_crease_seed is a second rosette beside numerics.crease_seed: give both");
  }
  if (c.numerics.crease_seed_depth) {
    check(*c.numerics.crease_seed_depth >= 0.0 && std::isfinite(*c.numerics.crease_seed_depth),
          "numerics.crease_seed_depth must be zero or positive");
    check(c.numerics.crease_seed.has_value(),
          "numerics.crease_seed_depth notches the node of numerics.crease_seed: give both");
  }
  if (c.numerics.end_time) positive("numerics", "end_time", *c.numerics.end_time);
  if (c.numerics.time_step_factor) {
    positive("numerics", "time_step_factor", *c.numerics.time_step_factor);
    check(*c.numerics.time_step_factor <= 1.0,
          fmt::format("{} must not exceed 1 (the explicit step is unstable beyond about 0.6; "
                      "build/cfl_scan)",
                      r.where(spec("numerics", "time_step_factor"))));
  }
  note_readings(r, c);
  return c;
}

}  // namespace

std::optional<Resolution> parse_resolution(std::string_view text) {
  for (const auto r : {Resolution::Coarse, Resolution::Default, Resolution::Fine}) {
    if (text == to_string(r)) return r;
  }
  return std::nullopt;
}

std::string_view to_string(Resolution r) {
  switch (r) {
    case Resolution::Coarse:
      return "coarse";
    case Resolution::Default:
      return "default";
    case Resolution::Fine:
      return "fine";
  }
  return "default";
}

std::optional<InvertedSnaps> parse_inverted_snaps(std::string_view text) {
  for (const auto s : {InvertedSnaps::InTime, InvertedSnaps::AlongBranch}) {
    if (text == to_string(s)) return s;
  }
  return std::nullopt;
}

std::string_view to_string(InvertedSnaps s) {
  return s == InvertedSnaps::AlongBranch ? "along the branch" : "in time";
}

std::optional<Model> parse_model(std::string_view text) {
  for (const auto m : {Model::ThreeD, Model::Axisymmetric}) {
    if (text == to_string(m)) return m;
  }
  return std::nullopt;
}

std::string_view to_string(Model m) { return m == Model::Axisymmetric ? "axisymmetric" : "3d"; }

const ResolutionPreset& preset(Resolution r) {
  static constexpr ResolutionPreset kCoarse{.element_size_over_sqrt_hR = 1.0 / 1.5,
                                            .layers = 1,
                                            .grid_cells_per_thickness = 4.0,
                                            .axi_through = 2};
  static constexpr ResolutionPreset kDefault{.element_size_over_sqrt_hR = 1.0 / 2.0,
                                             .layers = 1,
                                             .grid_cells_per_thickness = 4.0,
                                             .axi_through = 4};
  static constexpr ResolutionPreset kFine{.element_size_over_sqrt_hR = 1.0 / 2.5,
                                          .layers = 2,
                                          .grid_cells_per_thickness = 8.0,
                                          .axi_through = 8};
  switch (r) {
    case Resolution::Coarse:
      return kCoarse;
    case Resolution::Fine:
      return kFine;
    case Resolution::Default:
      break;
  }
  return kDefault;
}

std::optional<Law> parse_law(std::string_view text) {
  for (const auto l : {Law::NeoHookean, Law::Gent}) {
    if (text == to_string(l)) return l;
  }
  return std::nullopt;
}

std::string_view to_string(Law l) { return l == Law::Gent ? "Gent" : "neo-Hookean"; }

std::optional<BulkIntegration> parse_bulk_integration(std::string_view text) {
  for (const auto b : {BulkIntegration::Full, BulkIntegration::Reduced}) {
    if (text == to_string(b)) return b;
  }
  return std::nullopt;
}

std::string_view to_string(BulkIntegration b) {
  return b == BulkIntegration::Reduced ? "reduced" : "full";
}

std::span<const KeySpec> quantity_keys() { return kKeys; }

std::string_view default_case_text() { return kDefaultCase; }

std::string to_toml(const Case& c) {
  // Written by toml++'s serializer, never by string formatting, so that any title or file name
  // (quotes, newlines, control characters) reads back as it was. A plain number is a double,
  // which the serializer writes in its shortest form that reads back to the same value; a
  // quantity with a unit is a string, that shortest form and the SI unit ("0.03 m"), which the
  // unit parser converts from SI to SI, unchanged.
  // Every quantity from its field.
  std::map<std::string_view, toml::table> tables;
  Case fields = c;  // the accessors take a Case they could change: read them on a copy
  const auto insert = [&](toml::table& t, const KeySpec& k, double v) {
    if (k.dimension == Dimension::Dimensionless) {
      t.insert(k.name, v);
    } else {
      t.insert(k.name, fmt::format("{} {}", v, units::si_unit(k.dimension)));
    }
  };
  for (const auto& k : kKeys) {
    auto& t = tables[k.table];
    if (k.optional_field != nullptr) {
      if (const auto& v = *k.optional_field(fields)) insert(t, k, *v);
    } else if (!replaced_by_absolute_value(k, c)) {
      insert(t, k, *k.field(fields));
    }
  }
  if (c.material.law != Law::NeoHookean) {
    tables["material"].insert("law", std::string(to_string(c.material.law)));
  }
  if (c.protocol.inverted_snaps != InvertedSnaps::InTime) {
    tables["protocol"].insert("inverted_snaps", std::string(to_string(c.protocol.inverted_snaps)));
  }
  auto& shell = tables["shell"];
  if (!c.shell.mesh.empty()) shell.insert("mesh", c.shell.mesh);
  auto& numerics = tables["numerics"];
  numerics.insert("resolution", std::string(to_string(c.numerics.resolution)));
  if (c.numerics.model != Model::ThreeD) {
    numerics.insert("model", std::string(to_string(c.numerics.model)));
  }
  if (c.numerics.bulk_integration) {
    numerics.insert("bulk_integration", std::string(to_string(*c.numerics.bulk_integration)));
  }
  if (c.numerics.fan_layer) {
    numerics.insert("fan_layer", static_cast<std::int64_t>(*c.numerics.fan_layer));
  }
  if (c.numerics.elements_through_thickness) {
    numerics.insert("elements_through_thickness",
                    static_cast<std::int64_t>(*c.numerics.elements_through_thickness));
  }
  toml::table doc{{"title", c.title}};
  for (auto& [name, table] : tables) doc.insert(name, std::move(table));
  // No literal or multi-line strings: every string in double quotes, escaped, on one line.
  constexpr auto flags = toml::format_flags::none;
  std::ostringstream out;
  out << "# written by snapjump from "
      << toml::toml_formatter{toml::value<std::string>(c.source), flags} << ", every value in SI\n"
      << toml::toml_formatter{doc, flags} << '\n';
  return out.str();
}

double Popper::counterweight() const { return std::max(0.0, mass - net_weight / kStandardGravity); }

double Popper::moving_mass() const { return mass + counterweight(); }

const KeySpec* find_quantity_key(std::string_view dotted) {
  const auto dot = dotted.find('.');
  if (dot == std::string_view::npos) return nullptr;
  return find_key(dotted.substr(0, dot), dotted.substr(dot + 1));
}

Case parse_case(std::string_view toml_text, std::string_view source,
                std::span<const Override> overrides, const units::UnitParser* parser) {
  std::optional<units::UnitParser> own;
  if (parser == nullptr) parser = &own.emplace();
  toml::table doc;
  try {
    doc = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    throw CaseError(fmt::format("{}:{}:{}: not valid TOML: {}", source, e.source().begin.line,
                                e.source().begin.column, text::library_message(e.description())));
  }
  Case c;
  c.source = std::string(source);
  Reader reader(source, *parser);
  reader.read_document(doc, c);
  for (const auto& o : overrides) reader.apply(o);
  auto built = build(reader, std::move(c));
  std::vector<std::string> changed;
  for (const auto& o : overrides) {
    built.overridden.emplace_back(o.key, o.text);
    changed.push_back(fmt::format("{} = {}", o.key, o.text));
  }
  if (!changed.empty() && !built.title.empty()) {
    built.title += fmt::format(" [changed: {}]", fmt::join(changed, ", "));
  }
  return built;
}

Case load_case_file(const std::filesystem::path& path, std::span<const Override> overrides,
                    const units::UnitParser* parser) {
  return parse_case(text::read_file<CaseError>(path, "the case file"), path.string(), overrides,
                    parser);
}

Case default_case(std::span<const Override> overrides, const units::UnitParser* parser) {
  return parse_case(kDefaultCase, "built-in default case", overrides, parser);
}

}  // namespace snapjump::config
