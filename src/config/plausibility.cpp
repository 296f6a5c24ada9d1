#include "config/plausibility.hpp"

namespace snapjump::config {
namespace {

// The paper's poppers, for scale: (R, h) = (25 .. 30, 1.0 .. 2.5) mm, E = 1.2 MPa, silicone of
// 1160 kg/m^3, net weights 0.08 .. 3 N, a container of about 200 mL.
constexpr PlausibleRange kRanges[] = {
    {"shell.R", 1e-3, 1.0, "1 mm .. 1 m", "a popper's shell radius",
     "a popper's cap is moulded for a bench (the paper's: 25 and 30 mm), not under a millimetre "
     "nor of metres"},
    {"shell.h", 1e-4, 1.0, "0.1 mm .. 1 m", "a shell's thickness",
     "a cast elastomer layer is at least about 0.1 mm thick (the paper's: 1 to 2.5 mm), and "
     "h < R"},
    {"material.E", 1e3, 1e10, "1 kPa .. 10 GPa", "a shell's Young's modulus",
     "from the softest gels a cap keeps its shape in to stiff plastics (the paper's silicone: "
     "1.2 MPa)"},
    {"material.rho", 10.0, 25e3, "10 .. 25000 kg/m^3", "a shell's density",
     "from foams to the densest metals (the paper's silicone: 1160 kg/m^3)"},
    {"popper.net_weight", 1e-3, 1e3, "1 mN .. 1 kN", "a popper's net weight",
     "from a tenth of a gram to a hundred kilograms on the rail (the paper's: 0.08 to 3 N)"},
    {"popper.mass", 1e-4, 200.0, "0.1 g .. 200 kg", "a popper's own mass",
     "from a shell alone to the heaviest popper the net weight admits (1 kN / g = 102 kg)"},
    {"gas.container_volume", 1e-7, 1.0, "0.1 mL .. 1 m^3", "a container's volume",
     "from a syringe's dead volume to a barrel (the paper's: about 200 mL)"},
};

}  // namespace

std::span<const PlausibleRange> plausible_ranges() { return kRanges; }

const PlausibleRange* plausible_range(std::string_view key) {
  for (const auto& r : kRanges) {
    if (r.key == key) return &r;
  }
  return nullptr;
}

}  // namespace snapjump::config
