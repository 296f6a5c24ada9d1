// The theory's prediction for one case as a table for people, or JSON / CSV for programs.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "theory/scaling.hpp"

namespace snapjump::io {

// One reported quantity: bounds in SI, plus the unit it is shown in on the table.
struct ReportRow {
  std::string group;     // "geometry", "scales", ...
  std::string key;       // machine name, e.g. "r_star"
  std::string label;     // "r*  contact radius at the transition onset"
  double lo = 0.0;       // SI
  double hi = 0.0;       // SI; equal to lo for exact quantities
  std::string si_unit;   // "m"
  std::string unit;      // display unit on the table, "mm"
  double unit_si = 1.0;  // SI value of one display unit
  [[nodiscard]] bool exact() const { return lo == hi; }
};

std::vector<ReportRow> prediction_rows(const theory::Prediction& p);

void write_table(std::ostream& out, const config::Case& c, const theory::Prediction& p);
// The case's values in SI (and the defaults it used), for JSON reports.
nlohmann::json case_to_json(const config::Case& c);
nlohmann::json to_json(const config::Case& c, const theory::Prediction& p);
void write_json(std::ostream& out, const config::Case& c, const theory::Prediction& p);
void write_csv(std::ostream& out, const theory::Prediction& p);

}  // namespace snapjump::io
