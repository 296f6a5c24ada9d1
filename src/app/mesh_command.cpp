#include "app/mesh_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <numbers>

#include "app/cli.hpp"
#include "config/case.hpp"
#include "config/text.hpp"
#include "mesh/cap_mesher.hpp"
#include "mesh/msh_reader.hpp"

namespace snapjump::app {

MeshCommand::MeshCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "mesh",
      "Write the shell the simulator would use as a gmsh .msh file (quadratic tetrahedra, the "
      "physical groups shell, inner, clamped, outer): a starting point to edit in gmsh and name "
      "in a case as [shell] mesh = \"cap.msh\" (docs/shells.md).");
  case_.add_to(*cmd_);
  cmd_->add_option("--resolution", resolution_, "coarse, default or fine")
      ->check(CLI::IsMember({"coarse", "default", "fine"}));
  cmd_->add_option("--output", output_, "the .msh file to write")->required();
}

bool MeshCommand::parsed() const { return cmd_->parsed(); }

int MeshCommand::run(std::ostream& out, std::ostream& err) const {
  auto c = case_.load(err);
  if (const auto r = config::parse_resolution(resolution_)) c.numerics.resolution = *r;
  if (!c.shell.mesh.empty()) {
    throw config::CaseError(fmt::format(
        "mesh: the case already names its mesh ({}); `snapjump mesh` writes the spherical "
        "cap of R, h, phi",
        c.shell.mesh));
  }
  if (std::filesystem::path(output_).extension() != ".msh") {
    throw config::CaseError(
        fmt::format("mesh --output {}: name the file .msh (gmsh's format)", output_));
  }
  const auto spec = mesh::cap_spec(c);
  const auto m = mesh::make_cap_mesh(spec);
  mesh::write_msh(m, output_);
  fmt::print(out,
             "snapjump mesh: {}\n  cap         R = {:.4g} mm, h = {:.4g} mm, phi = {:.4g} deg, "
             "element size {:.3g} mm{}, {} layers ({} resolution)\n  mesh        {} ten-node "
             "tetrahedra, {} nodes; groups shell, inner, clamped, outer\n  written     {}\n",
             text::printable_line(c.title.empty() ? c.source : c.title), 1e3 * spec.R, 1e3 * spec.h,
             spec.phi * 180.0 / std::numbers::pi, 1e3 * spec.element_size,
             mesh::grading_summary(spec), spec.layers, config::to_string(c.numerics.resolution),
             m.tets.size(), m.nodes.size(), output_);
  return kExitOk;
}

}  // namespace snapjump::app
