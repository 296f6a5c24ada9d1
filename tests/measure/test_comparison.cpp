// measure::compare: records beside a run and the theory's bounds, checked against numbers worked
// out here by hand (means, sample standard deviations, tolerances from the stated instruments).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "measure/comparison.hpp"

namespace snapjump::measure {
namespace {

const ComparisonRow* row(const Comparison& c, std::string_view key) {
  for (const auto& r : c.rows) {
    if (r.key == key) return &r;
  }
  return nullptr;
}

RecordResult record(const char* name, double F_star, double t_star) {
  RecordResult r;
  r.name = name;
  r.analysis.F_star = F_star;
  r.analysis.t_star = t_star;
  r.analysis.outcome = theory::Outcome::Jump;
  r.analysis.sources["F_star"] = "t, F";
  r.dt_force = 0.2e-3;  // a 5 kHz plate
  r.dt_onset = 1e-3;    // a 1 kHz laser
  return r;
}

TEST(Comparison, SeveralRecordsGiveMeanSpreadAndTheRecordsTolerance) {
  const std::vector<RecordResult> records = {record("a.csv", 1.80, 14.0e-3),
                                             record("b.csv", 1.90, 15.0e-3),
                                             record("c.csv", 2.00, 16.0e-3)};
  Analysis run;
  run.F_star = 2.5;         // the exact plate's spike ...
  run.F_star_plate = 1.95;  // ... and through a 170 Hz plate, which is what a record shows
  run.t_star = 25e-3;
  run.outcome = theory::Outcome::Jump;
  theory::Prediction p;
  p.F_star = {1.0, 3.0};
  p.t_star = {5e-3, 12e-3};
  const auto c = compare(records, run, p, RecordUncertainty{});

  const auto* F = row(c, "F_star");
  ASSERT_NE(F, nullptr);
  EXPECT_EQ(F->values.size(), 3U);
  EXPECT_NEAR(*F->record, 1.90, 1e-12);
  EXPECT_NEAR(*F->spread, 0.10, 1e-12);  // sample standard deviation of 1.8, 1.9, 2.0
  EXPECT_EQ(F->run_key, "F_star_plate");
  EXPECT_NEAR(*F->run, 1.95, 1e-12);
  EXPECT_NEAR(*F->difference, -0.05, 1e-12);
  EXPECT_TRUE(*F->within);  // |-0.05| <= max(12 mN, 0.1 N)
  EXPECT_TRUE(*F->in_bounds);
  EXPECT_EQ(F->source, "t, F");

  const auto* t = row(c, "t_star");
  ASSERT_NE(t, nullptr);
  EXPECT_NEAR(*t->record, 15e-3, 1e-12);
  EXPECT_NEAR(*t->uncertainty, 1.2e-3, 1e-12);  // a sample of the laser and one of F
  EXPECT_NEAR(*t->spread, 1e-3, 1e-12);
  EXPECT_FALSE(*t->within);     // 10 ms apart, against 1.2 ms
  EXPECT_FALSE(*t->in_bounds);  // 15 ms against 5..12 ms widened by 1.2 ms
  EXPECT_EQ(c.record_outcomes.size(), 3U);
  EXPECT_EQ(c.run_outcome, "Jump");
}

TEST(Comparison, OneRecordIsJudgedByItsInstrumentsAloneAndUnstatedOnesAreNotJudged) {
  const std::vector<RecordResult> records = {record("a.csv", 1.80, 14.0e-3)};
  Analysis run;
  run.F_star = 1.81;
  run.r_star = 12e-3;
  theory::Prediction p;
  auto one = records;
  one[0].analysis.r_star = 12.5e-3;
  auto c = compare(one, run, p, RecordUncertainty{});
  const auto* F = row(c, "F_star");
  ASSERT_NE(F, nullptr);
  EXPECT_FALSE(F->spread);
  EXPECT_EQ(F->run_key, "F_star");  // no plate-filtered value in the run: its own F*
  EXPECT_TRUE(*F->within);          // 10 mN within the plate's 12 mN
  const auto* r = row(c, "r_star");
  ASSERT_NE(r, nullptr);
  EXPECT_FALSE(r->within);  // no ring width stated: r* is not judged
  RecordUncertainty u;
  u.ring_width = 1e-3;
  c = compare(one, run, p, u);
  EXPECT_TRUE(*row(c, "r_star")->within);
  std::ostringstream csv, table;
  write_csv(csv, c);
  write_table(table, c);
  EXPECT_NE(csv.str().find("r_star,m,0.0125,"), std::string::npos) << csv.str();
  EXPECT_NE(table.str().find("r_star"), std::string::npos);
  const auto j = to_json(c);
  EXPECT_EQ(j["units"], "SI");
  EXPECT_DOUBLE_EQ(j["quantities"]["F_star"]["record"].get<double>(), 1.80);
}

}  // namespace
}  // namespace snapjump::measure
