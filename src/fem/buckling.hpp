// Quasi-static buckling of the clamped shell under a slowly rising pressure difference: the
// preparation phase "lower delta_p until the shell inverts", and a validation of the body
// against Zoelly's buckling pressure.
#pragma once

#include <functional>

#include "fem/explicit.hpp"

namespace snapjump::fem {

struct BuckleOptions {
  // The pressure rises from 0 to p_fast in fast_time, then on to p_max in ramp_time.
  double p_fast = 0.0;     // [Pa]
  double fast_time = 0.0;  // [s]
  double p_max = 0.0;      // the ramp ends here [Pa]
  double ramp_time = 0.0;  // time from p_fast to p_max [s]
  double damping = 0.0;    // mass-proportional damping [1/s]
  double hold_time = 0.0;  // after the snap, time held at the snap pressure [s]
  double time_step_factor = 0.5;
  // The onset of the snap is declared when the cavity volume shrinks faster than onset_factor
  // times its quasi-static rate (measured during the first half of the slow ramp). From then on
  // the pressure is held.
  double onset_factor = 5.0;
  // Called every `report_every` steps with the driver and the current pressure.
  std::function<void(const ExplicitDriver&, double)> report;
  int report_every = 1000;
};

struct BuckleResult {
  bool snapped = false;
  double snap_pressure = 0.0;   // pressure at the onset of the snap [Pa]
  bool inverted = false;        // at the end, the outer apex lies above the outer rim plane
  double apex_rise = 0.0;       // upward displacement of the outer apex at the end [m]
  double volume_ratio = 1.0;    // cavity volume at the end / initial cavity volume
  double kinetic_energy = 0.0;  // at the end [J]
  double time = 0.0;
  long steps = 0;
  mesh::Points positions;  // final node positions
};

// Ramps the pressure (fast to p_fast, then slowly to p_max); at the onset of the snap holds the
// pressure reached for hold_time. The rim stays clamped where it is. Throws InvertedElement if
// an element turns inside out.
BuckleResult buckle_under_pressure(const Body& body, const BuckleOptions& options);

}  // namespace snapjump::fem
