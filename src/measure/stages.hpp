// The stages of measure::analyze (internal to the measure layer). analyze() runs them in order
// on one Context; each stage reads what the earlier ones found and sets its quantities with their
// sources (Context::put), so that the one quantity table (quantity_table()) can say where every
// number came from.
//
//   prepare            notes of the reader, R and its plausibility
//   find_onset         the contact transition: w / R < 0.03, or a contact column's disk
//   snap_from_transition / snap_from_force
//                      the snap's window, F*, the launch, the landing, the force's rise
//   heights            H, H_l, H_s from z
//   flight             T = landing - launch, H_flight (from z, or from T and the case's masses)
//   settle_no_snap     whether a record without a snap has gone on long enough
//   onset_in_gaps      warnings for an onset inside a sensor's dropout
//   check_tare         F held below zero: the plate's zero is off
//   decide             the flights, the outcome and its check against the series
//   prefactors         with a case: alpha_r, alpha_e, alpha_F, alpha_t ...
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "measure/analysis.hpp"

namespace snapjump::measure::stages {

// A plate's reading below this fraction of F* (and of the net weight) is about zero.
inline constexpr double kQuiet = 0.1;
// A sustained negative force below this fraction of F's range (or the noise) says F's zero is off.
inline constexpr double kTareFraction = 0.05;

struct Context {
  Context(const TimeSeries& s, const AnalysisOptions& o, const config::Case* c, Analysis& a);

  const TimeSeries& series;
  const AnalysisOptions& options;
  const config::Case* c;
  Analysis& a;
  std::span<const double> t, F;
  std::size_t n;
  // The plate's noise from F's sample-to-sample changes, and the least turn that ends the walk
  // along a rise (noise_multiple times it).
  double plate_noise = 0.0;
  double rise_floor = 0.0;

  std::optional<std::size_t> onset;  // the first sample at or after the onset
  std::string onset_columns;         // "t, w" or "t, contact"
  bool can_tell = false;             // the record can tell an outcome (any basis)
  bool snap_seen = false;            // an onset, or from the force alone a snap's peak
  bool snap_settled = false;         // a snap without a launch, on long enough to call it Snap
  bool force_trusted = true;         // F's zero is not off
  std::optional<std::size_t> landing;
  // The net weight the plate carries [N]: the case's popper.net_weight, else F_rest.
  std::optional<double> weight;

  // Sets a quantity of the table and its source.
  void put(std::string_view key, double value, std::string source);
  // weight_fraction times the weight: the most any threshold that tells a flight may be.
  [[nodiscard]] std::optional<double> threshold_cap() const;
};

// Two sources as one: "t, w" and "t, F, z" -> "t, w, F, z" (columns once each; what follows a ';',
// the case's keys, joined).
std::string merge_sources(std::string_view a, std::string_view b);

// The launch rule's thresholds on F.
struct LaunchRule {
  const AnalysisOptions* options = nullptr;
  std::optional<double> noise;  // the noise of F behind the default threshold [N]
  std::optional<double> cap;    // Context::threshold_cap()
  // The launch threshold for a force peak F_peak: the option, or max(relative_threshold F_peak,
  // noise_multiple noise), at most cap.
  [[nodiscard]] double level(double F_peak) const;
  // The ceiling F stays below in flight, a plate ringing on about zero: the level raised by the
  // deepest dip below zero, at most to kQuiet F_peak (and the cap).
  [[nodiscard]] double flight_ceiling(double level, double deepest, double F_peak) const;
  // F back above this after a flight is a landing.
  [[nodiscard]] double landing_ceiling(double F_peak) const;
};

struct Launch {
  std::size_t peak;  // the force peak before it
  double t;          // the crossing [s]
};
// The launch from sample `first` on, crossings looked for up to `last` (docs/analysis.md,
// "Launch"); warnings about rejected crossings go into `warnings`.
std::optional<Launch> find_launch(const TimeSeries& s, const LaunchRule& rule, std::size_t first,
                                  std::size_t last, std::vector<std::string>& warnings);
// The first sample at or after `from` (and min_flight_time after t_launch) at which F is back
// above `ceiling`; nothing when the record ends first.
std::optional<std::size_t> landing_after(const Context& x, std::size_t from, double t_launch,
                                         double ceiling);

void prepare(Context& x);
void find_onset(Context& x);
void snap_from_transition(Context& x);
void snap_from_force(Context& x);
void heights(Context& x);
void flight(Context& x);
void settle_no_snap(Context& x);
void onset_in_gaps(Context& x);
void check_tare(Context& x);
void decide(Context& x);
void prefactors(Context& x);

}  // namespace snapjump::measure::stages
