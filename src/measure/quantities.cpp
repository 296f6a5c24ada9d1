// The analysis' quantities: one table (key, unit, label, definition), read by to_json, by
// `snapjump analyze` and `snapjump compare` for their tables and CSV, and so by Python.
#include <algorithm>
#include <array>

#include "measure/analysis.hpp"

namespace snapjump::measure {
namespace {

using A = Analysis;

constexpr std::array kTable{
    QuantitySpec{"t_onset", "s", "transition onset t (w/R < 0.03)",
                 "first time w / R < 0.03 (interpolated), or the first row whose contact is disk",
                 &A::t_onset, 1e-3, "ms", true},
    QuantitySpec{"R", "m", "R   shell radius used for w / R", "the option R, or the case's shell.R",
                 &A::R, 1e-3, "mm", false},
    QuantitySpec{"r_star", "m", "r*  contact radius at the onset", "r interpolated to the onset",
                 &A::r_star, 1e-3, "mm", true},
    QuantitySpec{"e_star", "m", "e*  indentation at the onset",
                 "e (the rim's approach to the plate) interpolated to the onset", &A::e_star, 1e-3,
                 "mm", true},
    QuantitySpec{"e_apex_star", "m", "    apex displacement at the onset",
                 "e_apex (apex relative to the rim, e* + w) at the onset", &A::e_apex_star, 1e-3,
                 "mm", false},
    QuantitySpec{"F_rest", "N", "F_rest resting force before the snap",
                 "median of F from the record's start to the foot of the snap's rise", &A::F_rest,
                 1.0, "N", true},
    QuantitySpec{"t_force_rise", "s", "foot of the force's rise to F*",
                 "where F, walking back from F*, falls below a tenth of the rise above its base",
                 &A::t_force_rise, 1e-3, "ms", true},
    QuantitySpec{"F_star", "N", "F*  peak plate force of the snap",
                 "largest F from the foot of its rise to the snap's end (the first launch)",
                 &A::F_star, 1.0, "N", true},
    QuantitySpec{"t_F_star", "s", "    time of F*", "the sample of F*", &A::t_F_star, 1e-3, "ms",
                 false},
    QuantitySpec{"F_star_plate", "N", "    F* through a 170 Hz force plate",
                 "F through a second-order plate (plate_frequency), its peak over the snap",
                 &A::F_star_plate, 1.0, "N", false},
    QuantitySpec{"force_noise", "N", "noise of F",
                 "robust spread of F in flight after the peak (or of its sample-to-sample changes)",
                 &A::force_noise, 1.0, "N", false},
    QuantitySpec{"force_threshold", "N", "force threshold used for the launch",
                 "max(0.02 F*, 4 noise), at most half the net weight", &A::force_threshold, 1.0,
                 "N", true},
    QuantitySpec{"t_launch", "s", "launch t (F back to about 0)",
                 "first crossing of F below the threshold after F* that stays below for 5 ms",
                 &A::t_launch, 1e-3, "ms", true},
    QuantitySpec{"t_star", "s", "t*  onset to launch", "t_launch - t_onset", &A::t_star, 1e-3, "ms",
                 true},
    QuantitySpec{"t_star_rise", "s", "t*_rise  force rise to launch",
                 "t_launch - t_force_rise: a force-plate record's t*", &A::t_star_rise, 1e-3, "ms",
                 true},
    QuantitySpec{"t_landing", "s", "landing t (back on the plate)",
                 "first sample after the flight with F back above the launch's ceiling",
                 &A::t_landing, 1e-3, "ms", true},
    QuantitySpec{"flight_time", "s", "T   flight, launch to landing", "t_landing - t_launch",
                 &A::flight_time, 1e-3, "ms", true},
    QuantitySpec{"H_flight", "m", "H_flight rise of the flight above the launch",
                 "highest z of the flight less z at the launch, or a T^2 / 8 without z",
                 &A::H_flight, 1e-3, "mm", true},
    QuantitySpec{"flight_deceleration", "m/s^2", "    deceleration a in flight",
                 "g, or with the case's masses net_weight / (popper + counterweight)",
                 &A::flight_deceleration, 1.0, "m/s^2", false},
    QuantitySpec{"H", "m", "H   highest container position", "max z up to the landing", &A::H, 1e-3,
                 "mm", true},
    QuantitySpec{"H_l", "m", "H_l container position at the onset", "z at the onset", &A::H_l, 1e-3,
                 "mm", true},
    QuantitySpec{"H_s", "m", "H_s = H - H_l", "H - H_l", &A::H_s, 1e-3, "mm", true},
    QuantitySpec{"delta_p_onset", "Pa", "delta_p at the onset", "delta_p at the onset",
                 &A::delta_p_onset, 1e3, "kPa", true},
    QuantitySpec{"t_lift_off", "s", "lift-off of the record's highest flight",
                 "the launch rule from anywhere in the record", &A::t_lift_off, 1e-3, "ms", false},
    QuantitySpec{"flight_rise", "m", "    rise of z in that flight",
                 "highest z of that flight less z at its lift-off", &A::flight_rise, 1e-3, "mm",
                 false},
    QuantitySpec{"flight_threshold", "m", "    least rise of z that makes a flight",
                 "max(4 sigma_z, g (5 ms)^2 / 8)", &A::flight_threshold, 1e-3, "mm", false},
    QuantitySpec{"alpha_r", "1", "alpha_r = r* / sqrt(h R)", "r* / sqrt(h R)", &A::alpha_r, 1.0, "",
                 false},
    QuantitySpec{"alpha_e", "1", "alpha_e = e* / h", "e* / h", &A::alpha_e, 1.0, "", false},
    QuantitySpec{"alpha_F", "1", "alpha_F = F* / (E h^3 / R)", "F* / (E h^3 / R)", &A::alpha_F, 1.0,
                 "", false},
    QuantitySpec{"alpha_F_plate", "1", "    with F* through the plate",
                 "F_star_plate / (E h^3 / R)", &A::alpha_F_plate, 1.0, "", false},
    QuantitySpec{"alpha_t", "1", "alpha_t = t* / sqrt(m R / (E h^2))",
                 "t* / sqrt(m R / (E h^2)), m = popper + counterweight", &A::alpha_t, 1.0, "",
                 false},
    QuantitySpec{"alpha_t_own", "1", "    with the popper's own mass",
                 "t* / sqrt(m_p R / (E h^2)), m_p = the popper alone", &A::alpha_t_own, 1.0, "",
                 false},
    QuantitySpec{"alpha_t_net", "1", "    with m = mg / g",
                 "t* / sqrt((mg / g) R / (E h^2)), the net weight's mass", &A::alpha_t_net, 1.0, "",
                 false},
    QuantitySpec{"alpha_t_rise", "1", "    with t*_rise (force rise to launch)",
                 "t_star_rise / sqrt(m R / (E h^2)), m = popper + counterweight", &A::alpha_t_rise,
                 1.0, "", false},
    QuantitySpec{"H_s_scaled", "1", "H_s / (E h^4 / (mg R))", "H_s / (E h^4 / (m g R))",
                 &A::H_s_scaled, 1.0, "", false},
    QuantitySpec{"F_star_over_mg", "1", "F* / mg", "F* / (m g), m g = net weight",
                 &A::F_star_over_mg, 1.0, "", false},
};

// The record table's columns: the first fourteen in the order the table has always had.
constexpr std::array<std::string_view, 18> kRecordKeys{
    "t_onset", "r_star",  "e_star", "F_star",        "t_launch",    "t_star",
    "H",       "H_l",     "H_s",    "delta_p_onset", "alpha_r",     "alpha_e",
    "alpha_F", "alpha_t", "F_rest", "t_star_rise",   "flight_time", "H_flight"};

}  // namespace

std::span<const QuantitySpec> quantity_table() { return kTable; }

const QuantitySpec* find_quantity(std::string_view key) {
  const auto it = std::find_if(kTable.begin(), kTable.end(),
                               [&](const QuantitySpec& q) { return q.key == key; });
  return it == kTable.end() ? nullptr : &*it;
}

std::span<const std::string_view> record_table_keys() { return kRecordKeys; }

std::string Analysis::source(std::string_view key) const {
  const auto it = sources.find(key);
  return it == sources.end() ? std::string() : it->second;
}

}  // namespace snapjump::measure
