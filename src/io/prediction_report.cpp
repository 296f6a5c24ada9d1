#include "io/prediction_report.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "config/text.hpp"
#include "io/csv.hpp"

namespace snapjump::io {
namespace {

ReportRow exact(std::string group, std::string key, std::string label, double v,
                std::string si_unit, std::string unit, double unit_si) {
  return {std::move(group),   std::move(key),  std::move(label), v, v,
          std::move(si_unit), std::move(unit), unit_si};
}

ReportRow range(std::string group, std::string key, std::string label, theory::Range r,
                std::string si_unit, std::string unit, double unit_si) {
  return {std::move(group),   std::move(key),  std::move(label), r.lo, r.hi,
          std::move(si_unit), std::move(unit), unit_si};
}

// NaN is an end the theory gives no value for (theory::Prediction::beyond_range).
std::string number(double v) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.4g}", v);
}

}  // namespace

std::vector<ReportRow> prediction_rows(const theory::Prediction& p) {
  const std::string g = "geometry", l = "loads", s = "scales", a = "prefactors",
                    q = "characteristic quantities", o = "outcome criteria";
  return {
      exact(g, "rim_radius", "rim radius R sin(phi)", p.rim_radius, "m", "mm", 1e-3),
      exact(g, "cap_depth", "cap depth R (1 - cos phi)", p.cap_depth, "m", "mm", 1e-3),
      exact(g, "shell_volume", "shell material volume", p.shell_volume, "m^3", "cm^3", 1e-6),
      exact(g, "shell_mass", "shell mass", p.shell_mass, "kg", "g", 1e-3),
      exact(g, "cavity_volume", "volume under the inner surface", p.cavity_volume, "m^3", "mL",
            1e-6),
      exact(l, "net_weight", "net weight mg", p.net_weight, "N", "N", 1.0),
      exact(l, "popper_mass", "popper's own mass m_p", p.popper_mass, "kg", "g", 1e-3),
      exact(l, "counterweight", "counterweight m_p - mg / g", p.counterweight, "kg", "g", 1e-3),
      exact(l, "moving_mass", "moving mass m = m_p + counterweight", p.moving_mass, "kg", "g",
            1e-3),
      exact(l, "p_c", "Zoelly buckling pressure p_c", p.zoelly_pc, "Pa", "kPa", 1e3),
      exact(l, "delta_p_j", "pressure difference at release delta_p_j", p.delta_p_j, "Pa", "kPa",
            1e3),
      exact(s, "r_c", "r_c = sqrt(h R)", p.r_c, "m", "mm", 1e-3),
      exact(s, "e_c", "e_c = h", p.e_c, "m", "mm", 1e-3),
      exact(s, "F_c", "F_c = E h^3 / R", p.F_c, "N", "N", 1.0),
      exact(s, "t_c", "t_c = sqrt(m R / (E h^2))", p.t_c, "s", "ms", 1e-3),
      range(a, "alpha_r", "alpha_r", p.alpha.alpha_r, "1", "", 1.0),
      range(a, "alpha_e", "alpha_e", p.alpha.alpha_e, "1", "", 1.0),
      range(a, "alpha_F", "alpha_F", p.alpha.alpha_F, "1", "", 1.0),
      range(a, "alpha_t", "alpha_t = sqrt(3 alpha_e / alpha_F)", p.alpha.alpha_t, "1", "", 1.0),
      range(q, "r_star", "r*  contact radius at the onset", p.r_star, "m", "mm", 1e-3),
      range(q, "e_star", "e*  apex displacement at the onset", p.e_star, "m", "mm", 1e-3),
      range(q, "F_star", "F*  peak plate force", p.F_star, "N", "N", 1.0),
      range(q, "t_star", "t*  onset to launch", p.t_star, "s", "ms", 1e-3),
      range(q, "H_l", "H_l lift up to the transition", p.H_l, "m", "mm", 1e-3),
      range(q, "H_s", "H_s flight from the snap", p.H_s, "m", "mm", 1e-3),
      range(q, "H", "H = H_l + H_s  jump height", p.H, "m", "mm", 1e-3),
      exact(o, "inverted_energy", "U   energy of the inverted shell", p.inverted_energy, "J", "mJ",
            1e-3),
      range(o, "jump_margin", "F*/mg  (Jump needs > 1)", p.jump_margin, "1", "", 1.0),
      range(o, "snap_margin", "U/(mg H_l)  (No snap when < 1)", p.snap_margin, "1", "", 1.0),
  };
}

void write_table(std::ostream& out, const config::Case& c, const theory::Prediction& p) {
  constexpr double deg = 180.0 / std::numbers::pi;
  fmt::print(out, "snapjump predict: {}\n",
             text::printable_line(c.title.empty() ? c.source : c.title));
  fmt::print(out, "  case          {}\n", c.source);
  fmt::print(out, "  shell         R = {} mm, h = {} mm, phi = {} deg  (h/R = {:.4g})\n",
             number(c.shell.R * 1e3), number(c.shell.h * 1e3), number(c.shell.phi * deg),
             c.shell.h / c.shell.R);
  if (!c.shell.mesh.empty()) {
    fmt::print(out,
               "  shell mesh    {}\n                the closed forms below are those of the "
               "spherical cap of R, h, phi: they\n                predict this shell only as far "
               "as it is that cap (docs/shells.md)\n",
               c.shell.mesh);
  }
  fmt::print(out, "  material      E = {} MPa, nu = {}, rho = {} kg/m^3, {}\n",
             number(c.material.E * 1e-6), number(c.material.nu), number(c.material.rho),
             c.material.law == config::Law::Gent
                 ? fmt::format("Gent's law, Jm = {}", number(*c.material.gent_jm))
                 : std::string("neo-Hookean"));
  fmt::print(out,
             "  popper        mg = {} N, popper {} g + counterweight {} g = m = {} g, wire {}  "
             "(E h^2 / mg = {:.4g})\n",
             number(c.popper.net_weight), number(c.popper.mass * 1e3),
             number(c.popper.counterweight() * 1e3), number(c.popper.moving_mass() * 1e3),
             c.popper.wire_stiffness ? number(*c.popper.wire_stiffness) + " N/m" : "rigid",
             c.material.E * c.shell.h * c.shell.h / c.popper.net_weight);
  fmt::print(out, "  friction      mu = {}\n", number(c.friction.mu));
  if (!c.defaults_used.empty()) {
    // Wrapped list, continuation lines aligned under the first entry.
    std::string line = "  defaults used ";
    const std::string indent(line.size(), ' ');
    for (size_t i = 0; i < c.defaults_used.size(); ++i) {
      const auto item = c.defaults_used[i] + (i + 1 < c.defaults_used.size() ? "," : "");
      if (line.size() + item.size() > 96 && line.size() > indent.size()) {
        fmt::print(out, "{}\n", line);
        line = indent;
      }
      line += (line.size() > indent.size() ? " " : "") + item;
    }
    fmt::print(out, "{}\n", line);
  }
  fmt::print(out, "  bounds from   {}\n", p.constants_source);

  std::string group;
  fmt::print(out, "\n{:<44} {:>11} {:>11}  {}\n", "quantity", "lower", "upper", "unit");
  for (const auto& r : prediction_rows(p)) {
    if (r.group != group) {
      group = r.group;
      fmt::print(out, "{}\n", group);
    }
    const auto lo = number(r.lo / r.unit_si);
    const auto hi = r.exact() ? std::string() : number(r.hi / r.unit_si);
    fmt::print(out, "  {:<42} {:>11} {:>11}  {}\n", r.label, lo, hi, r.unit);
  }
  fmt::print(out, "\npredicted outcome: {}\n", p.outcome_text());
  fmt::print(out, "  Jump needs F* > mg:          F*/mg = {} .. {}\n", number(p.jump_margin.lo),
             number(p.jump_margin.hi));
  fmt::print(out, "  No snap when U < mg H_l:     U/(mg H_l) = {} .. {}\n",
             number(p.snap_margin.lo), number(p.snap_margin.hi));
  if (!p.beyond_range.empty()) {
    fmt::print(out, "  (- : no value beyond the theory's range)\n");
  } else if (!p.outcome.certain()) {
    fmt::print(out, "  (more than one outcome lies within the prefactor bounds)\n");
  }
}

nlohmann::json case_to_json(const config::Case& c) {
  return {{"title", c.title},
          {"source", c.source},
          {"R", c.shell.R},
          {"h", c.shell.h},
          {"phi", c.shell.phi},
          {"mesh", c.shell.mesh.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.shell.mesh)},
          {"E", c.material.E},
          {"nu", c.material.nu},
          {"rho", c.material.rho},
          {"law", std::string(config::to_string(c.material.law))},
          {"gent_jm",
           c.material.gent_jm ? nlohmann::json(*c.material.gent_jm) : nlohmann::json(nullptr)},
          {"net_weight", c.popper.net_weight},
          {"popper_mass", c.popper.mass},
          {"counterweight", c.popper.counterweight()},
          {"moving_mass", c.popper.moving_mass()},
          {"wire_stiffness", c.popper.wire_stiffness ? nlohmann::json(*c.popper.wire_stiffness)
                                                     : nlohmann::json(nullptr)},
          {"mu", c.friction.mu},
          {"container_volume", c.gas.container_volume},
          {"p0", c.gas.p0},
          {"alpha_n", c.gas.alpha_n},
          {"beta_n", c.gas.beta_n},
          {"resolution", std::string(config::to_string(c.numerics.resolution))},
          {"defaults_used", c.defaults_used}};
}

nlohmann::json to_json(const config::Case& c, const theory::Prediction& p) {
  using nlohmann::json;
  // An end without a value (NaN, beyond the theory's range) becomes null.
  const auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json quantities = json::object();
  for (const auto& r : prediction_rows(p)) {
    quantities[r.key] = {{"lower", num(r.lo)}, {"upper", num(r.hi)}, {"unit", r.si_unit}};
  }
  json outcome = json::array();
  if (p.outcome.jump) outcome.push_back("Jump");
  if (p.outcome.snap) outcome.push_back("Snap");
  if (p.outcome.no_snap) outcome.push_back("No snap");
  const json doc = {
      {"case", case_to_json(c)},
      {"units", "SI"},
      {"constants_source", p.constants_source},
      {"quantities", quantities},
      {"outcome", outcome},
      {"outcome_text", p.outcome_text()},
      {"beyond_range", p.beyond_range.empty() ? json(nullptr) : json(p.beyond_range)},
  };
  return doc;
}

void write_json(std::ostream& out, const config::Case& c, const theory::Prediction& p) {
  out << to_json(c, p).dump(2) << '\n';
}

void write_csv(std::ostream& out, const theory::Prediction& p) {
  out << "quantity,lower,upper,unit\n";
  // An end without a value (beyond the theory's range) is an empty cell.
  const auto cell = [](double v) {
    return std::isnan(v) ? std::string() : fmt::format("{:.10g}", v);
  };
  for (const auto& r : prediction_rows(p)) {
    fmt::print(out, "{},{},{},{}\n", r.key, cell(r.lo), cell(r.hi), r.si_unit);
  }
  fmt::print(out, "outcome,{},,\n", csv_field(p.outcome_text()));
}

}  // namespace snapjump::io
