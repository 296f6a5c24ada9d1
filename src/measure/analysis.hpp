// The paper's characteristic quantities of one popper run, from a time series (simulated or
// measured with the force plate): transition onset, r*, e*, F*, launch, t*, H, H_l, H_s, the
// outcome (Jump / Snap / No snap), and, given the case, the measured prefactors of the scaling
// laws. Definitions and thresholds: docs/analysis.md.
#pragma once

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "config/case.hpp"
#include "measure/time_series.hpp"
#include "theory/scaling.hpp"

namespace snapjump::measure {

// The paper's force plate (Methods): resonant frequency 170 Hz, sampled at 5 kHz.
inline constexpr double kPaperPlateFrequency = 170.0;  // [Hz]

struct AnalysisOptions {
  // Shell radius for the onset criterion w / R < onset_ratio [m]; the case's shell.R when absent.
  std::optional<double> R;
  double onset_ratio = 0.03;  // the paper's w / R < 0.03
  // Launch: F below this [N] for min_flight_time. Default max(0.02 F*, noise_multiple * noise).
  std::optional<double> force_threshold;
  double min_flight_time = 5e-3;        // [s]
  double relative_threshold = 0.02;     // of F*, in the default threshold
  double noise_multiple = 4.0;          // of the noise level, in the default threshold
  double noise_window_fraction = 0.10;  // final part of the record where the noise is estimated
  // The force as a force plate would record it: when set, F is also passed through a plate of
  // this resonant frequency [Hz] (a second-order low-pass of unit static gain and damping ratio
  // plate_damping) and its peak over the snap's window is reported as F_star_plate. For
  // simulated series (the paper's plate: 170 Hz); a measured record has been through its plate.
  std::optional<double> plate_frequency;
  double plate_damping = 0.7;  // an assumption: the paper gives the frequency only
  // How long the record must go on, after the force peak, before a snap without a launch is
  // called Snap, and, after delta_p has reached zero, before no onset is called No snap [s].
  // Shorter records get no outcome ("undetermined", with the reason).
  double settle_time = 50e-3;
  // The record covers the whole experiment: no onset is No snap and no launch Snap, whenever
  // the record ends.
  bool complete = false;
  // Added to F before the analysis [N]: the net weight, for a plate tared with the popper on it.
  double force_offset = 0.0;
  // No threshold on F that tells the popper off the plate (the launch's, the landing's ceiling)
  // exceeds this fraction of the net weight the plate carries (the case's popper.net_weight, or
  // else the resting force F_rest measured before the snap): a force above it is the popper
  // standing on the plate.
  double weight_fraction = 0.5;
  // A record without an onset criterion (no w with R, no contact column) is read from the force
  // alone: a force peak is a snap's when it stands above the resting force by more than this
  // fraction of it and by twice noise_multiple times the plate's noise.
  double snap_fraction = 0.1;
};

// F(t) through a second-order low-pass of resonant frequency f [Hz], damping ratio zeta and unit
// static gain, starting at rest at F[0]; F is taken as linear between samples (RK4 substeps of
// at most 1/20 of the period's radian). Throws SeriesError for f <= 0, zeta <= 0 or times that
// do not increase.
std::vector<double> plate_response(std::span<const double> t, std::span<const double> F, double f,
                                   double zeta);

// How the onset was found.
// ApexGap: first time w / R < onset_ratio; ContactDisk: first row whose contact state is "disk".
enum class OnsetSource { None, ApexGap, ContactDisk };

// What the snap was read from: the contact transition on the plate (an onset criterion: w with R,
// or a contact column), or the plate's force alone (a force-plate record: no onset, t* from the
// force's rise, H from the flight's duration when there is no z).
enum class Basis { Transition, ForceOnly };

struct Analysis {
  Basis basis = Basis::Transition;
  // Transition onset (ring -> disk contact).
  std::optional<double> t_onset;  // [s]
  OnsetSource onset_source = OnsetSource::None;
  std::optional<double> R;       // the radius used for w / R [m]
  std::optional<double> r_star;  // contact radius at the onset [m]
  // Indentation at the onset [m]: how far the plate has pushed into the undeformed shell (the rim's
  // approach to the plate), the plane displacement e of the theory's contact problem.
  std::optional<double> e_star;
  // Apex displacement relative to the rim at the onset [m]: e* + w, since the apex still stands
  // w = 0.03 R above the plate then.
  std::optional<double> e_apex_star;
  // Force peak after the onset.
  std::optional<double> F_star;    // [N]
  std::optional<double> t_F_star;  // time of the peak [s]
  // The peak of F through the force plate (AnalysisOptions::plate_frequency), same window [N].
  std::optional<double> F_star_plate;
  // The foot of the force's rise to F* [s]: with a gradual eversion it comes before the apex
  // criterion fires.
  std::optional<double> t_force_rise;
  // The force on the plate before the snap's rise: the median of F from the record's start to the
  // foot of the rise (the net weight the plate carries) [N].
  std::optional<double> F_rest;
  // Launch: F falls below the threshold and stays below it.
  std::optional<double> force_threshold;  // the one used [N]
  std::optional<double> force_noise;      // the noise estimate behind the default threshold [N]
  std::optional<double> t_launch;         // [s]
  std::optional<double> t_star;           // t_launch - t_onset [s]
  std::optional<double> t_star_rise;      // t_launch - t_force_rise [s]
  // The first sample back on the plate after the launch, when the record goes on that long [s].
  std::optional<double> t_landing;
  // The flight: T = t_landing - t_launch [s], and how far the container rose in it above its
  // height at the launch [m]: from z (its highest z in the flight less z at the launch) when the
  // record has a z column, else from T as a ballistic flight that decelerates at
  // flight_deceleration, H_flight = a T^2 / 8 (flight_rule says which and why).
  std::optional<double> flight_time;
  std::optional<double> H_flight;
  std::optional<double> flight_deceleration;  // [m/s^2]
  std::string flight_rule;
  // Heights of the container.
  std::optional<double> H;    // max z [m]
  std::optional<double> H_l;  // z at the onset [m]
  // delta_p at the onset [Pa]: the suction that still holds the dimple in when the apex comes
  // down shares the load with the plate and lowers F* (docs/popper.md).
  std::optional<double> delta_p_onset;
  std::optional<double> H_s;  // H - H_l [m]
  // The record's highest flight: a stretch off the plate by the launch rule, from anywhere in the
  // record (before the onset too), and how far z rose in it above its height at the lift-off.
  // Absent without a z column or without such a stretch.
  std::optional<double> t_lift_off;   // [s]
  std::optional<double> flight_rise;  // [m]
  // The least rise that says the popper flew: max(noise_multiple sigma_z, g min_flight_time^2 / 8),
  // sigma_z the noise of z (with a z column) [m].
  std::optional<double> flight_threshold;
  // Jump if launched after the onset, Snap if onset without launch, No snap if no onset and no
  // flight, Thrown if the popper flew without the contact transition on the plate before the
  // flight; absent (with the reason in `undetermined`) when the series cannot tell.
  std::optional<theory::Outcome> outcome;
  // Why there is no outcome (a record that ends before the question is settled, a plate whose
  // zero is off, no onset criterion); never empty when the outcome is absent.
  std::string undetermined;
  // With a case: measured prefactors and scaled quantities.
  std::optional<double> alpha_r;        // r* / sqrt(h R)
  std::optional<double> alpha_e;        // e* / h
  std::optional<double> alpha_F;        // F* / (E h^3 / R)
  std::optional<double> alpha_F_plate;  // F_star_plate / (E h^3 / R)
  // t* / sqrt(m R / (E h^2)) with m the theory's inertia, popper + counterweight (a rigid wire).
  std::optional<double> alpha_t;
  // The same with the popper's own mass: the limit of a wire too soft to move the counterweight
  // within t*.
  std::optional<double> alpha_t_own;
  // t_star_rise over the same t_c (a force-plate record's t*, from the force's rise).
  std::optional<double> alpha_t_rise;
  // And with m = mg / g, the mass of the net weight (no counterweight's inertia at all).
  std::optional<double> alpha_t_net;
  std::optional<double> H_s_scaled;      // H_s / (E h^4 / (m g R)), m g = net weight
  std::optional<double> F_star_over_mg;  // F* / (m g)
  std::vector<std::string> warnings;     // anything a reader should know, in plain words
  // Where each quantity present came from: its key (quantity_table()) -> the record's columns and
  // the case's keys it was computed from, e.g. "F_star" -> "t, F".
  std::map<std::string, std::string, std::less<>> sources;
  // The source of a quantity, or "" when it has none.
  [[nodiscard]] std::string source(std::string_view key) const;
};

// One quantity of the analysis: the one table that the JSON, the command line's tables and CSV
// and the Python package read (src/measure/quantities.cpp).
struct QuantitySpec {
  std::string_view key;         // "F_star", the name in JSON, CSV and Python
  std::string_view unit;        // SI: "s", "m", "N", "Pa", "m/s^2" or "1"
  std::string_view label;       // for a table: "F*  peak plate force of the snap"
  std::string_view definition;  // one line: how it is measured (docs/analysis.md has the rest)
  std::optional<double> Analysis::*field;
  double display_scale;           // shown as value / display_scale ...
  std::string_view display_unit;  // ... in this unit ("ms", "mm", "N", "kPa", "")
  bool core;                      // shown in a record's table even when absent ("-")
};
std::span<const QuantitySpec> quantity_table();
const QuantitySpec* find_quantity(std::string_view key);
// The quantities of `analyze`'s one-row-per-record table, in its column order.
std::span<const std::string_view> record_table_keys();

std::string_view to_string(OnsetSource s);  // "none", "w/R", "contact=disk"
std::string_view to_string(Basis b);        // "transition", "force only"
// "Jump", "Snap", "No snap" (the theory's spelling).
std::string outcome_text(const std::optional<theory::Outcome>& o);

// Analyses a series with columns t and F (required), and w, r, e, z, delta_p, contact when
// present; without w (with R) and contact, from the force alone (Basis::ForceOnly). The stages are
// in src/measure/stages.hpp. Throws SeriesError when t or F is missing, the series has no rows, or
// the options make no sense (R <= 0, ...).
Analysis analyze(const TimeSeries& series, const AnalysisOptions& options = {},
                 const config::Case* c = nullptr);

// What in the analysis contradicts its own outcome, in words, or empty when nothing does: No snap
// for a popper that flew (flight_rise above flight_threshold), Thrown without such a flight, Jump
// without a launch, Snap without an onset, no outcome without its reason. analyze() withdraws an
// outcome that this contradicts (the reason then says why).
std::string contradiction(const Analysis& a);

// The result in SI: {"units": "SI", "basis": "transition", "quantities": {"t_onset": {"value": ..,
// "unit": "s", "label": .., "definition": .., "source": "t, w"}, ..}, "outcome": "Jump",
// "onset_source": .., "flight_rule": .., "warnings": [..]}; absent values are null (and their
// source too).
nlohmann::json to_json(const Analysis& a);
void write_json(std::ostream& out, const Analysis& a);

}  // namespace snapjump::measure
