#include "app/contact_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli.hpp"
#include "contact/contact.hpp"
#include "theory/prefactors.hpp"
#include "theory/scaling.hpp"

namespace snapjump::app {
namespace {

void write_json(std::ostream& out, const contact::Constants& c, const theory::Prefactors& b,
                double nu, double kappa) {
  using nlohmann::json;
  const auto range = [](theory::Range r) { return json{{"lower", r.lo}, {"upper", r.hi}}; };
  const json doc = {
      {"units", "rescaled: x = r / l, e_hat = sqrt(kappa) e / h, N = kappa F R / (E h^3)"},
      {"reissner_slope", c.reissner_slope},
      {"N_plus", {{"N", c.N_plus}, {"a", c.a_plus}, {"e_hat", c.e_hat_plus}, {"paper", 76.94}}},
      {"n2", {{"ridge", c.n2}, {"large_rings", c.n2_ring_extrapolated}, {"paper", 20.83}}},
      {"N_minus", {{"N", c.N_minus}, {"a", c.a_minus}, {"e_hat", c.e_hat_minus}, {"paper", 46.8}}},
      {"e_hat_ring_law_at_N_plus", c.e_hat_ring_law_at_plus},
      {"mirror_energy_prefactor",
       {{"cap_height", c.mirror_energy_prefactor_cap_height},
        {"apex_displacement", c.mirror_energy_prefactor}}},
      {"ring_branch_min_N", c.ring_N_min},
      {"nu", nu},
      {"kappa", kappa},
      {"bounds",
       {{"alpha_r", range(b.alpha_r)},
        {"alpha_e", range(b.alpha_e)},
        {"alpha_F", range(b.alpha_F)},
        {"alpha_t", range(b.alpha_t)}}},
      {"checks",
       {{"max_residual", c.max_residual},
        {"max_offgrid_residual", c.max_offgrid_residual},
        {"min_disk_gap", c.min_disk_gap},
        {"min_ring_gap", c.min_ring_gap}}},
  };
  out << doc.dump(2) << '\n';
}

void write_table(std::ostream& out, const contact::Constants& c, const theory::Prefactors& b,
                 double nu, double kappa, const std::string& curves) {
  fmt::print(out,
             "snapjump contact: a spherical shell pushed by a rigid plane (axisymmetric "
             "shallow shell)\n");
  fmt::print(out,
             "rescaled units: x = r / l, e_hat = sqrt(kappa) e / h, N = kappa F R / (E h^3), "
             "kappa = 12 (1 - nu^2)\n\n");
  fmt::print(out, "  {:<52} {:>10.5f}   closed form 8 (Reissner)\n",
             "slope dN/de_hat at small load", c.reissner_slope);
  fmt::print(out, "  {:<52} {:>10.4f}   paper 76.94; a = {:.4f}, e_hat = {:.4f}\n",
             "N+  end of the disk branch (contact disk buckles)", c.N_plus, c.a_plus, c.e_hat_plus);
  fmt::print(out, "  {:<52} {:>10.4f}   paper 20.83; large rings give {:.4f}\n",
             "n(2) ridge boundary layer, N_ring = n(2) sqrt(e_hat)", c.n2, c.n2_ring_extrapolated);
  fmt::print(out, "  {:<52} {:>10.4f}   paper 46.8; a = {:.4f}, e_hat = {:.4f}\n",
             "N-  disk branch meets the ring law", c.N_minus, c.a_minus, c.e_hat_minus);
  fmt::print(out, "  {:<52} {:>10.4f}\n", "e_hat on the ring law at N+, (N+ / n(2))^2",
             c.e_hat_ring_law_at_plus);
  fmt::print(out, "  {:<52} {:>10.4f}   ring states need N >= this\n",
             "lowest force on the computed ring branch", c.ring_N_min);
  fmt::print(out, "  {:<52} {:>10.4f}   U = C E h^5/2 H^3/2 / ((1-nu^2)^3/4 R)\n",
             "mirror-buckling energy prefactor C (cap height H)",
             c.mirror_energy_prefactor_cap_height);
  fmt::print(out, "\nprefactor bounds at nu = {} (kappa = {:.4g}):\n", nu, kappa);
  fmt::print(out, "  alpha_r  {:.4f} .. {:.4f}   disk contact radius at N- .. at N+\n",
             b.alpha_r.lo, b.alpha_r.hi);
  fmt::print(out, "  alpha_e  {:.4f} .. {:.4f}   e_hat at N- .. ring law at N+\n", b.alpha_e.lo,
             b.alpha_e.hi);
  fmt::print(out, "  alpha_F  {:.4f} .. {:.4f}   N- .. N+\n", b.alpha_F.lo, b.alpha_F.hi);
  fmt::print(out, "  alpha_t  {:.4f} .. {:.4f}   sqrt(3 alpha_e / alpha_F) at the two points\n",
             b.alpha_t.lo, b.alpha_t.hi);
  fmt::print(out,
             "\nchecks: max residual {:.1e}, max residual between nodes {:.1e}, "
             "min gap to the plane {:.1e} (disk) {:.1e} (ring)\n",
             c.max_residual, c.max_offgrid_residual, c.min_disk_gap, c.min_ring_gap);
  if (!curves.empty()) fmt::print(out, "branches written to {}\n", curves);
}

}  // namespace

ContactCommand::ContactCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "contact",
      "Solve the shell-plane contact problem: N+, n(2), N-, the mirror-buckling energy and the "
      "prefactor bounds at a Poisson ratio.");
  cmd_->add_option("--nu", nu_, "Poisson's ratio for the bounds (default 0.5)");
  cmd_->add_option("--format", format_, "output: table or json")
      ->check(CLI::IsMember({"table", "json"}));
  cmd_->add_option("--curves", curves_,
                   "write the disk and ring branches N(e_hat) to this CSV file");
}

bool ContactCommand::parsed() const { return cmd_->parsed(); }

int ContactCommand::run(std::ostream& out, std::ostream& err) const {
  if (!(nu_ > -1.0 && nu_ <= 0.5)) {
    fmt::print(err, "error: --nu {} must lie in (-1, 0.5]\n", nu_);
    return kExitBadInput;
  }
  const auto c = contact::compute_constants();
  const auto tc = theory::from_solver(c);
  const auto b = theory::prefactor_bounds(tc, nu_);
  const double kappa = theory::kappa(nu_);
  if (!curves_.empty()) {
    std::ofstream csv(curves_);
    if (!csv) {
      fmt::print(err, "error: --curves: cannot write {}\n", curves_);
      return kExitFailure;
    }
    contact::write_curves_csv(csv, contact::disk_branch(), contact::ring_branch());
    if (!csv) {
      fmt::print(err, "error: --curves: writing {} failed\n", curves_);
      return kExitFailure;
    }
  }
  if (format_ == "json") {
    write_json(out, c, b, nu_, kappa);
  } else {
    write_table(out, c, b, nu_, kappa, curves_);
  }
  return kExitOk;
}

}  // namespace snapjump::app
