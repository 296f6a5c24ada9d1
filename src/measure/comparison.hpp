// A measured record (or several) beside a simulated run and the theory's bounds: one table of the
// quantities of the analysis (quantity_table()), each with the record's value, the run's, their
// difference, whether it lies within the record's stated uncertainty, and the theory's range
// (docs/analysis.md, "A record beside a run"). `snapjump compare` and snapjump.compare write it.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "measure/analysis.hpp"
#include "theory/scaling.hpp"

namespace snapjump::measure {

// What the record's instruments can tell, as the lab states it.
struct RecordUncertainty {
  double force_resolution = 12e-3;          // F [N]: the paper's plate resolves 12 mN
  std::optional<double> ring_width;         // r [m]: the width of the contact ring seen
  std::optional<double> length_resolution;  // z, w, e [m]: the lasers'
};

// One analysed record: its analysis and its sensors' sample intervals [s].
struct RecordResult {
  std::string name;
  Analysis analysis;
  double dt_force = 0.0;  // F's own sample interval
  double dt_onset = 0.0;  // the onset column's (w or contact); 0 without an onset
};

// One quantity of the comparison.
struct ComparisonRow {
  std::string key, unit, label;
  std::string run_key;                // the run's quantity beside it (F_star_plate for F_star)
  std::vector<double> values;         // the records' values (those that have one)
  std::optional<double> record;       // their mean
  std::optional<double> spread;       // their sample standard deviation (two or more)
  std::optional<double> uncertainty;  // the record's stated uncertainty of the quantity
  std::string uncertainty_from;       // how: "F's resolution 12 mN", "2 samples of F (0.2 ms)"
  std::optional<double> run;
  std::optional<double> difference;  // record - run
  // |record - run| within max(uncertainty, spread); absent when neither is known or no run value
  std::optional<bool> within;
  std::optional<double> lower, upper;  // the theory's bounds
  std::string bounds_of;               // the theory's quantity ("t_star" for t_star_rise)
  std::optional<bool> in_bounds;       // the record within the bounds (widened by its uncertainty)
  std::string source;                  // the first record's source of it
};

struct Comparison {
  std::vector<std::string> records;
  std::vector<std::string> record_outcomes;
  std::string run_outcome, predicted_outcome;
  std::vector<ComparisonRow> rows;
  std::vector<std::string> notes;
};

Comparison compare(std::span<const RecordResult> records, const Analysis& run,
                   const theory::Prediction& theory, const RecordUncertainty& u);

// {"units": "SI", "records": [..], "outcomes": {"records": [..], "run": .., "theory": ..},
//  "quantities": {"F_star": {"record": .., "spread": .., "n": .., "uncertainty": ..,
//  "uncertainty_from": .., "run": .., "run_key": .., "difference": .., "within": ..,
//  "lower": .., "upper": .., "bounds_of": .., "in_bounds": .., "unit": .., "label": ..,
//  "source": ..}, ..}, "notes": [..]}
nlohmann::json to_json(const Comparison& c);
// One line per quantity: key,unit,record,spread,n,uncertainty,run,difference,within,lower,upper,
// in_bounds,source (SI; empty cells for absent values).
void write_csv(std::ostream& out, const Comparison& c);
// The same for people, in display units.
void write_table(std::ostream& out, const Comparison& c);

}  // namespace snapjump::measure
