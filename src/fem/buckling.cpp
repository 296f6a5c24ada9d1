#include "fem/buckling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace snapjump::fem {

BuckleResult buckle_under_pressure(const Body& body, const BuckleOptions& o) {
  const auto& X = body.mesh().nodes;
  const double V0 = body.cavity_volume(X);
  // The outer rim circle: the lowest clamped node of the outer surface.
  double outer_rim_z = std::numeric_limits<double>::infinity();
  std::vector<char> is_outer(X.size(), 0);
  for (int a : body.mesh().outer) is_outer[a] = 1;
  for (int a : body.mesh().clamped) {
    if (is_outer[a]) outer_rim_z = std::min(outer_rim_z, X.z[a]);
  }

  BuckleResult r;
  double held = -1.0;  // pressure held after the onset of the snap
  double snap_time = 0.0;
  const auto ramp = [&](double t) {
    if (t < o.fast_time) return o.p_fast * t / o.fast_time;
    return o.p_fast + (o.p_max - o.p_fast) * std::min(1.0, (t - o.fast_time) / o.ramp_time);
  };
  ExplicitOptions eo;
  eo.time_step_factor = o.time_step_factor;
  eo.damping = o.damping;
  eo.pressure = [&](double t) { return held >= 0.0 ? held : ramp(t); };
  ExplicitDriver d(body, eo);
  const int apex = body.mesh().apex;
  const double t_slow = o.fast_time, t_end_ramp = o.fast_time + o.ramp_time;
  constexpr int kSample = 20;  // steps between volume samples
  double last_V = V0, last_t = 0.0;
  double ref_rate = 0.0;  // quasi-static -dV/dt during the first half of the slow ramp
  int ref_count = 0;
  while (true) {
    d.step();
    if (held < 0.0 && d.steps() % kSample == 0) {
      const double V = body.cavity_volume(d.positions());
      const double rate = -(V - last_V) / (d.time() - last_t);
      last_V = V;
      last_t = d.time();
      const double t = d.time();
      if (t > t_slow + 0.1 * o.ramp_time && t < t_slow + 0.5 * o.ramp_time) {
        ref_rate += rate;
        ++ref_count;
      } else if (t >= t_slow + 0.5 * o.ramp_time && ref_count > 0 &&
                 rate > o.onset_factor * ref_rate / ref_count) {
        held = ramp(t);
        r.snapped = true;
        r.snap_pressure = held;
        snap_time = t;
      }
    }
    if (o.report && d.steps() % o.report_every == 0) o.report(d, eo.pressure(d.time()));
    if (held >= 0.0 && d.time() >= snap_time + o.hold_time) break;
    if (held < 0.0 && d.time() >= t_end_ramp + o.hold_time) break;
  }
  r.time = d.time();
  r.steps = d.steps();
  r.positions = d.positions();
  r.apex_rise = r.positions.z[apex] - X.z[apex];
  r.inverted = r.positions.z[apex] > outer_rim_z;
  r.volume_ratio = body.cavity_volume(r.positions) / V0;
  r.kinetic_energy = d.kinetic_energy();
  return r;
}

}  // namespace snapjump::fem
