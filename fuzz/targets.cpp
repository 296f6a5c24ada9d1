#include "fuzz/targets.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "app/checkpoint.hpp"
#include "config/case.hpp"
#include "config/units.hpp"
#include "measure/analysis.hpp"
#include "measure/time_series.hpp"
#include "mesh/mesh.hpp"
#include "mesh/msh_reader.hpp"
#include "plot/gnuplot.hpp"
#include "plot/snapshots.hpp"
#include "plot/table.hpp"
#include "popper/popper.hpp"
#include "sweep/sweep.hpp"

namespace snapjump::fuzz {
namespace {

namespace fs = std::filesystem;

// Readers that take a path get the bytes in a file of this process's own.
fs::path scratch_file(const char* extension, std::string_view bytes) {
  const fs::path p =
      fs::temp_directory_path() / ("snapjump-fuzz-" + std::to_string(::getpid()) + extension);
  std::ofstream(p, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return p;
}

const units::UnitParser& unit_parser() {
  static const units::UnitParser parser;  // loading the database once, not per input
  return parser;
}

void case_file(std::string_view bytes) {
  try {
    (void)config::parse_case(bytes, "fuzz.toml", {}, &unit_parser());
  } catch (const config::CaseError&) {
  }
}

void series(std::string_view bytes) {
  std::istringstream in{std::string(bytes)};
  try {
    const auto s = measure::TimeSeries::read_csv(in, "fuzz.csv", unit_parser());
    // What was read goes through the analysis too, as `snapjump analyze` does.
    if (!s.empty() && s.has(measure::kForce)) {
      measure::AnalysisOptions o;
      o.R = 0.03;
      (void)measure::analyze(s, o);
    }
  } catch (const measure::SeriesError&) {
  }
}

void table(std::string_view bytes) {
  std::istringstream in{std::string(bytes)};
  try {
    (void)plot::Table::read_csv(in, "fuzz.csv");
  } catch (const plot::PlotInputError&) {
  }
}

void sweep_spec(std::string_view bytes) {
  try {
    (void)sweep::parse_spec(bytes, "fuzz-sweep.toml");
  } catch (const sweep::SweepError&) {
  } catch (const config::CaseError&) {
  }
}

// One popper of each model, made once: decoding restores its state in place.
popper::Popper& popper_of(config::Model model) {
  static std::unique_ptr<popper::Popper> three_d, axi;
  auto& p = model == config::Model::ThreeD ? three_d : axi;
  if (!p) {
    auto c = config::default_case();
    c.numerics.resolution = config::Resolution::Coarse;
    c.numerics.model = model;
    p = std::make_unique<popper::Popper>(c, popper::resolve_numerics(c));
  }
  return *p;
}

void checkpoint_setup() {
  (void)popper_of(config::Model::ThreeD);
  (void)popper_of(config::Model::Axisymmetric);
}

void checkpoint(std::string_view bytes) {
  for (const auto model : {config::Model::ThreeD, config::Model::Axisymmetric}) {
    try {
      (void)app::decode_checkpoint(bytes, popper_of(model), "fuzz checkpoint.bin");
    } catch (const app::CheckpointError&) {
    }
  }
}

void vtu(std::string_view bytes) {
  try {
    (void)plot::read_vtu_points(scratch_file(".vtu", bytes));
  } catch (const plot::PlotInputError&) {
  }
}

void pvd(std::string_view bytes) {
  try {
    (void)plot::read_pvd(scratch_file(".pvd", bytes));
  } catch (const plot::PlotInputError&) {
  }
}

void msh(std::string_view bytes) {
  try {
    (void)mesh::read_msh(scratch_file(".msh", bytes));
  } catch (const mesh::MeshError&) {
  }
}

}  // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"case", case_file},
      {"series", series},
      {"table", table},
      {"sweep", sweep_spec},
      {"checkpoint", checkpoint, checkpoint_setup},
      {"vtu", vtu},
      {"pvd", pvd},
      {"msh", msh},
  };
  return all;
}

const Target* find_target(std::string_view name) {
  for (const auto& t : targets()) {
    if (name == t.name) return &t;
  }
  return nullptr;
}

}  // namespace snapjump::fuzz
