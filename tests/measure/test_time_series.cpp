// TimeSeries and its CSV format: construction, appending, exact round trips, unit brackets, the
// incremental writer, and one message per class of malformed input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "config/files.hpp"
#include "config/units.hpp"
#include "measure/time_series.hpp"

namespace snapjump::measure {
namespace {

TimeSeries read(const std::string& text, const units::UnitParser& parser) {
  std::istringstream in(text);
  return TimeSeries::read_csv(in, "run.csv", parser);
}

// The message of the SeriesError that reading `text` throws ("" if none).
std::string read_error(const std::string& text) {
  const units::UnitParser parser;
  try {
    read(text, parser);
  } catch (const SeriesError& e) {
    return e.what();
  }
  return "";
}

std::string contents(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(TimeSeries, AddRowAndColumns) {
  TimeSeries s({"t", "F", "z"}, true);
  s.add_row({0.0, 0.5, 0.0}, ContactState::Ring);
  s.add_row({1e-3, 0.7, 2e-4}, ContactState::Disk);
  const std::vector<double> row{2e-3, 0.1, 5e-4};
  s.add_row(row, ContactState::None);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_TRUE(s.has("z"));
  EXPECT_FALSE(s.has("w"));
  EXPECT_EQ(s.column("F")[1], 0.7);
  EXPECT_EQ(s.time()[2], 2e-3);
  EXPECT_EQ(s.contact()[1], ContactState::Disk);
  EXPECT_THROW((void)s.column("w"), SeriesError);
}

TEST(TimeSeries, AddRowChecks) {
  TimeSeries s({"t", "F"});
  s.add_row({1.0, 0.0});
  EXPECT_THROW(s.add_row({1.0, 0.0}), SeriesError);                      // time does not increase
  EXPECT_THROW(s.add_row({0.5, 0.0}), SeriesError);                      // time goes back
  EXPECT_THROW(s.add_row({2.0}), SeriesError);                           // too few values
  EXPECT_THROW(s.add_row({2.0, 0.0}, ContactState::Disk), SeriesError);  // no contact column
  EXPECT_THROW(s.add_row({std::numeric_limits<double>::quiet_NaN(), 0.0}), SeriesError);
  EXPECT_EQ(s.size(), 1u);
  TimeSeries c({"t", "F"}, true);
  EXPECT_THROW(c.add_row({0.0, 0.0}), SeriesError);  // contact state missing
}

TEST(TimeSeries, ColumnNameChecks) {
  EXPECT_THROW(TimeSeries({"F", "z"}), SeriesError);        // no t
  EXPECT_THROW(TimeSeries({"t", "F", "t"}), SeriesError);   // duplicate
  EXPECT_THROW(TimeSeries({"t", "contact"}), SeriesError);  // contact is not numeric
  EXPECT_THROW(TimeSeries({"t", "a,b"}), SeriesError);      // comma
  EXPECT_THROW(TimeSeries({"t", ""}), SeriesError);         // empty
  EXPECT_THROW(TimeSeries({"t", "z [mm]"}), SeriesError);   // known column with unit
  EXPECT_NO_THROW(TimeSeries({"t", "F", "T [degC]"}));      // unknown column, kept as is
}

TEST(ContactState, Text) {
  EXPECT_EQ(to_string(ContactState::None), "none");
  EXPECT_EQ(to_string(ContactState::Ring), "ring");
  EXPECT_EQ(to_string(ContactState::Disk), "disk");
  EXPECT_EQ(parse_contact_state(" Disk "), ContactState::Disk);
  EXPECT_EQ(parse_contact_state("RING"), ContactState::Ring);
  EXPECT_FALSE(parse_contact_state("annulus"));
  EXPECT_FALSE(parse_contact_state(""));
}

TEST(TimeSeriesCsv, RoundTripIsExact) {
  TimeSeries s({"t", "F", "z", "r", "w", "e", "delta_p", "T [degC]"}, true);
  // Values that do not print exactly in few digits.
  s.add_row({0.0, 1.0 / 3.0, -0.0, 1e-300, 0.1, 2.0 / 7.0, -1234.5678, 21.5}, ContactState::None);
  s.add_row({1e-4, 0.48, 1.2345678901234567e-5, 0.012, 0.02, 1e-3, -0.1, 21.6}, ContactState::Ring);
  s.add_row({std::nextafter(2e-4, 1.0), 5e10, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0}, ContactState::Disk);
  std::ostringstream out;
  s.write_csv(out);
  EXPECT_EQ(out.str().substr(0, out.str().find('\n')), "t,F,z,r,w,e,delta_p,T [degC],contact");

  const units::UnitParser parser;
  const auto back = read(out.str(), parser);
  ASSERT_EQ(back.columns(), s.columns());
  ASSERT_EQ(back.size(), s.size());
  ASSERT_TRUE(back.has_contact());
  for (std::size_t i = 0; i < s.columns().size(); ++i) {
    for (std::size_t r = 0; r < s.size(); ++r) {
      EXPECT_EQ(back.column(i)[r], s.column(i)[r]) << s.columns()[i] << " row " << r;
    }
  }
  for (std::size_t r = 0; r < s.size(); ++r) EXPECT_EQ(back.contact()[r], s.contact()[r]);
  // And once more: the text itself is stable.
  std::ostringstream again;
  back.write_csv(again);
  EXPECT_EQ(again.str(), out.str());
}

TEST(TimeSeriesCsv, UnitBrackets) {
  const units::UnitParser parser;
  const auto s = read(
      "# a measured record\n"
      "t [ms], F [mN],z [mm],w[um],delta_p [kPa],r [cm],e [mm],contact,gain [dB]\n"
      "1,480,2.5,900,-1.5,1.2,3,ring,7\n"
      "\n"
      "# comment between rows\n"
      "2.5,+1e3,3,800,-2,1.1,3.5,disk,8\r\n",
      parser);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s.time()[0], 1e-3);  // 1 ms
  EXPECT_DOUBLE_EQ(s.time()[1], 2.5e-3);
  EXPECT_DOUBLE_EQ(s.column("F")[0], 0.48);  // 480 mN
  EXPECT_DOUBLE_EQ(s.column("F")[1], 1.0);
  EXPECT_DOUBLE_EQ(s.column("z")[0], 2.5e-3);
  EXPECT_DOUBLE_EQ(s.column("w")[1], 8e-4);  // 800 um
  EXPECT_DOUBLE_EQ(s.column("delta_p")[0], -1500.0);
  EXPECT_DOUBLE_EQ(s.column("r")[0], 0.012);
  EXPECT_DOUBLE_EQ(s.column("e")[1], 3.5e-3);
  EXPECT_EQ(s.column("gain [dB]")[1], 8.0);  // unknown: kept as written, not converted
  EXPECT_EQ(s.contact()[0], ContactState::Ring);
  EXPECT_EQ(s.contact()[1], ContactState::Disk);
  // Plain names are SI.
  const auto si = read("t,F\n0.001,2\n", parser);
  EXPECT_EQ(si.time()[0], 0.001);
}

TEST(CsvWriter, AppendsAndFlushesEachRow) {
  const auto path = std::filesystem::path(testing::TempDir()) / "snapjump_writer_test.csv";
  {
    CsvWriter w(path, {"t", "F", "z"}, true);
    w.write_comment("case: default\nR = 30 mm");
    w.write_row(std::vector<double>{0.0, 0.5, 0.0}, ContactState::Ring);
    w.write_row(std::vector<double>{1e-4, 0.6, 1e-6}, ContactState::Disk);
    // Still open: what was written is already in the file.
    EXPECT_EQ(contents(path),
              "t,F,z,contact\n# case: default\n# R = 30 mm\n0,0.5,0,ring\n0.0001,0.6,1e-06,disk\n");
    EXPECT_THROW(w.write_row(std::vector<double>{1e-4, 0.0, 0.0}, ContactState::None),
                 SeriesError);  // time must increase
    EXPECT_THROW(w.write_row(std::vector<double>{2e-4, 0.0, 0.0}), SeriesError);  // no state
    EXPECT_EQ(w.rows(), 2u);
  }
  const auto s = TimeSeries::read_csv_file(path);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.column("z")[1], 1e-6);
  std::filesystem::remove(path);
}

TEST(CsvWriter, SameTextAsWriteCsv) {
  TimeSeries s({"t", "F"});
  s.add_row({0.0, 0.25});
  s.add_row({0.5, -1.0 / 3.0});
  std::ostringstream a;
  s.write_csv(a);
  std::ostringstream b;
  CsvWriter w(b, {"t", "F"});
  w.write_row(std::vector<double>{0.0, 0.25});
  w.write_row(std::vector<double>{0.5, -1.0 / 3.0});
  EXPECT_EQ(a.str(), b.str());
}

// A file that cannot be written is a write failure (the command line's status 4), not bad data.
TEST(CsvWriter, CannotCreate) {
  try {
    CsvWriter("/nonexistent-dir/x/run.csv", {"t", "F"});
    ADD_FAILURE() << "no error";
  } catch (const text::WriteFailed& e) {
    EXPECT_EQ(e.path(), "/nonexistent-dir/x/run.csv");
    EXPECT_NE(std::string(e.what()).find("could not write /nonexistent-dir/x/run.csv"),
              std::string::npos)
        << e.what();
  }
}

// --- Malformed input: each class has its message, naming file, line and column. -----------------

TEST(TimeSeriesCsvErrors, WrongDimensionInHeader) {
  const auto m = read_error("t [mm],F [N]\n1,2\n");
  EXPECT_NE(m.find("run.csv:1"), std::string::npos) << m;
  EXPECT_NE(m.find("column 1 't [mm]'"), std::string::npos) << m;
  EXPECT_NE(m.find("a time is needed"), std::string::npos) << m;
}

TEST(TimeSeriesCsvErrors, UnknownUnit) {
  const auto m = read_error("# header follows\nt [s],F [blorfs]\n1,2\n");
  EXPECT_NE(m.find("run.csv:2: column 2 'F [blorfs]'"), std::string::npos) << m;
  EXPECT_NE(m.find("unknown unit 'blorfs'"), std::string::npos) << m;
}

TEST(TimeSeriesCsvErrors, BadBrackets) {
  EXPECT_NE(read_error("t [ms,F\n").find("column 1 't [ms': unbalanced brackets"),
            std::string::npos);
  EXPECT_NE(read_error("t,F [N] x\n").find("column 2 'F [N] x': text after the ']'"),
            std::string::npos);
  EXPECT_NE(read_error("t,[N]\n").find("column 2 '[N]': the column has no name"),
            std::string::npos);
  EXPECT_NE(read_error("t,F,contact [s]\n").find("takes no unit"), std::string::npos);
}

TEST(TimeSeriesCsvErrors, DuplicateColumn) {
  const auto m = read_error("t,F,t [ms]\n");
  EXPECT_NE(m.find("run.csv:1: column 3 't [ms]': the name 't' is also column 1"),
            std::string::npos)
      << m;
}

TEST(TimeSeriesCsvErrors, NonNumericCell) {
  const auto m = read_error("t,F,z [mm]\n0,1,2\n# c\n1e-3,0.5,abc\n");
  EXPECT_NE(m.find("run.csv:4: column 3 'z [mm]': 'abc' is not a finite number"), std::string::npos)
      << m;
  EXPECT_NE(read_error("t,F\n0,1.5x\n").find("'1.5x' is not a finite number"), std::string::npos);
  EXPECT_NE(read_error("t,F\n0,inf\n").find("'inf' is not a finite number"), std::string::npos);
  // An empty or NaN cell is a missing value; a record whose F is all missing has nothing to read.
  EXPECT_NE(read_error("t,F\n0,nan\n").find("no row has a value of F"), std::string::npos);
  EXPECT_NE(read_error("t,F\n0,\n").find("no row has a value of F"), std::string::npos);
  EXPECT_NE(read_error("t,F\n,1\n").find("column 1 't': the time is empty"), std::string::npos);
}

TEST(TimeSeriesCsvErrors, FewerAndMoreCells) {
  const auto m = read_error("t,F,z\n0,1,2\n1,2\n");
  EXPECT_NE(m.find("run.csv:3: 2 cells, but the header has 3 columns (column 3 'z' is missing)"),
            std::string::npos)
      << m;
  const auto more = read_error("t,F\n0,1,2\n");
  EXPECT_NE(more.find("run.csv:2: 3 cells, but the header has only 2 columns"), std::string::npos)
      << more;
}

TEST(TimeSeriesCsvErrors, OneTimeWithTwoValues) {
  // Rows of one time are merged (a merged file of several sensors); two different values of one
  // column at one time are an error naming both lines.
  const auto m = read_error("F,t [ms]\n0,1\n0,2\n1,2\n");
  EXPECT_NE(m.find("run.csv:4: column 'F': time 0.002 s is also on line 3 with another value"),
            std::string::npos)
      << m;
}

TEST(TimeSeriesCsvErrors, MissingTimeOrForce) {
  const auto no_t = read_error("clock,F\n0,1\n");
  EXPECT_NE(no_t.find("run.csv:1: the header has no 't' column (time, required); it has: clock, F"),
            std::string::npos)
      << no_t;
  EXPECT_NE(no_t.find("--column t=\"Time (s)\""), std::string::npos) << no_t;
  const auto no_f = read_error("t,z\n0,1\n");
  EXPECT_NE(no_f.find("run.csv:1: the header has no 'F' column"), std::string::npos) << no_f;
}

TEST(TimeSeriesCsvErrors, BadContactState) {
  const auto m = read_error("t,F,contact\n0,1,ring\n1,1,annulus\n");
  EXPECT_NE(m.find("run.csv:3: column 3 'contact': 'annulus' is not a contact state"),
            std::string::npos)
      << m;
}

TEST(TimeSeriesCsvErrors, EmptyInputAndMissingFile) {
  EXPECT_NE(read_error("# only comments\n\n").find("run.csv: no header line"), std::string::npos);
  try {
    (void)TimeSeries::read_csv_file("/nonexistent-dir/run.csv");
    FAIL() << "no error";
  } catch (const SeriesError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/run.csv: no such file (a time series)"),
              std::string::npos);
  }
}

// --- Records as laboratories log them ------------------------------------------------------------

TimeSeries read_with(const std::string& text, const ReadOptions& options) {
  const units::UnitParser parser;
  std::istringstream in(text);
  return TimeSeries::read_csv(in, "lab.csv", parser, options);
}

bool has_note(const TimeSeries& s, std::string_view text) {
  for (const auto& n : s.notes()) {
    if (n.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(LabRecords, SeparatorsQuotesAndHeaderSpellings) {
  // Semicolons with decimal commas, quoted headers with units in parentheses, a pandas index.
  const auto a =
      read_with(";\"Time (s)\";\"Fz (N)\";\"z (mm)\"\n0;0,000;0,48;0,0\n1;0,001;0,50;0,5\n", {});
  EXPECT_EQ(a.columns(), (std::vector<std::string>{"t", "F", "z"}));
  ASSERT_EQ(a.size(), 2U);
  EXPECT_DOUBLE_EQ(a.column("t")[1], 1e-3);
  EXPECT_DOUBLE_EQ(a.column("F")[1], 0.50);
  EXPECT_DOUBLE_EQ(a.column("z")[1], 0.5e-3);
  EXPECT_TRUE(has_note(a, "column 1 has no name"));
  // Tabs; names with a unit suffix; "Unnamed: 0" from pandas.
  const auto b = read_with("Unnamed: 0\tt_ms\tF_N\te_m\n0\t0\t1\t0.001\n1\t0.2\t2\t0.002\n", {});
  EXPECT_EQ(b.columns(), (std::vector<std::string>{"t", "F", "e"}));
  EXPECT_DOUBLE_EQ(b.column("t")[1], 0.2e-3);
  EXPECT_DOUBLE_EQ(b.column("e")[1], 0.002);
  // A quoted cell may hold the separator.
  const auto c = read_with("t,F,\"note, free text\"\n0,1,2\n", {});
  EXPECT_EQ(c.columns().size(), 3U);
}

TEST(LabRecords, ColumnMappingAndUnitsByOption) {
  ReadOptions o;
  o.columns = {{"t", "Zeit"}, {"F", "Kraft"}};
  o.units = {{"t", "ms"}, {"F", "mN"}};
  const auto s = read_with("Zeit,Kraft\n0,480\n0.2,500\n", o);
  EXPECT_DOUBLE_EQ(s.column("t")[1], 0.2e-3);
  EXPECT_DOUBLE_EQ(s.column("F")[1], 0.5);
  // A mapping that names no column, a unit given twice, a unit for a column not there.
  ReadOptions bad;
  bad.columns = {{"t", "Time (s)"}};
  try {
    (void)read_with("Zeit,F\n0,1\n", bad);
    ADD_FAILURE() << "no error";
  } catch (const SeriesError& e) {
    EXPECT_NE(std::string(e.what()).find("t=\"Time (s)\" names no column; it has: Zeit, F"),
              std::string::npos)
        << e.what();
  }
  ReadOptions twice;
  twice.units = {{"t", "ms"}};
  EXPECT_THROW((void)read_with("t [s],F\n0,1\n", twice), SeriesError);
  ReadOptions absent;
  absent.units = {{"z", "mm"}};
  EXPECT_THROW((void)read_with("t,F\n0,1\n", absent), SeriesError);
}

TEST(LabRecords, ColumnsTheAnalysisDoesNotReadNeverStopTheRecord) {
  // A trial label (text), a sparse marker (half the time) and a header with text after its unit.
  const auto s = read_with(
      "t,F,trial,marker,Temp (C) sensor 2\n0,1,A,,20\n1,1,A,5,20\n2,1,B,,21\n3,1,B,,21\n"
      "4,1,B,,22\n",
      {});
  EXPECT_EQ(s.size(), 5U);  // the marker does not cut the record to its span
  EXPECT_FALSE(s.has("trial"));
  EXPECT_TRUE(has_note(s, "column 'trial' holds text: left out"));
  EXPECT_TRUE(s.has("Temp (C) sensor 2"));
  // A mapping onto a name the analysis does not know is an error naming it.
  ReadOptions o;
  o.columns = {{"tempo", "Kraft"}};
  try {
    (void)read_with("t,Kraft\n0,1\n", o);
    ADD_FAILURE() << "no error";
  } catch (const SeriesError& e) {
    EXPECT_NE(std::string(e.what()).find("names 'tempo', which is not a column"), std::string::npos)
        << e.what();
  }
}

TEST(LabRecords, UnsortedRowsAreSortedWithANote) {
  const auto s = read_with("t,F\n0.002,3\n0,1\n0.001,2\n", {});
  EXPECT_EQ(std::vector<double>(s.column("F").begin(), s.column("F").end()),
            (std::vector<double>{1, 2, 3}));
  EXPECT_TRUE(has_note(s, "the time goes back at 1 places")) << s.notes().size();
}

TEST(LabRecords, SensorsOnTheirOwnClocksAreResampledOntoTheForce) {
  // F at 0, 1, 2, 3, 4 ms; z (a laser) at 0.5, 2.5, 4.5 ms with z = 10 t (mm, t in ms) exactly,
  // so the interpolated z at 1 ms is 10 mm; the record is cut to 1 .. 4 ms, where z covers it.
  const auto s = read_with(
      "t [ms],F [N],z [mm]\n0,1,\n0.5,,5\n1,2,\n2,3,\n2.5,NaN,25\n3,4,\n4,5,\n4.5,,45\n", {});
  EXPECT_EQ(std::vector<double>(s.column("t").begin(), s.column("t").end()),
            (std::vector<double>{1e-3, 2e-3, 3e-3, 4e-3}));
  const auto z = s.column("z");
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(z[i], 10.0 * s.column("t")[i], 1e-15) << i;  // z [m] = 10 t [s]
  }
  EXPECT_TRUE(has_note(s, "interpolated linearly onto the force's"));
  EXPECT_TRUE(has_note(s, "the record is cut to 0.001 .. 0.004 s"))
      << fmt::format("{}", fmt::join(s.notes(), " | "));
}

TEST(LabRecords, ADropoutIsAGapWithANote) {
  // w sampled every ms from 0 to 20 ms, missing from 6 to 13 ms.
  std::string text = "t [ms],F,w [mm]\n";
  for (int i = 0; i <= 20; ++i) {
    const bool lost = i > 5 && i < 14;
    text += fmt::format("{},{},{}\n", i, 1.0, lost ? std::string("") : fmt::format("{}", 20 - i));
  }
  const auto s = read_with(text, {});
  ASSERT_EQ(s.gaps().size(), 1U);
  EXPECT_EQ(s.gaps()[0].column, "w");
  EXPECT_DOUBLE_EQ(s.gaps()[0].from, 5e-3);
  EXPECT_DOUBLE_EQ(s.gaps()[0].to, 14e-3);
  EXPECT_NEAR(s.column("w")[10], 10e-3, 1e-15);  // linear across the gap
  EXPECT_TRUE(has_note(s, "column 'w' has no values from 0.005 to 0.014 s"));
}

TEST(LabRecords, AColumnCoveringLittleOfTheRecordIsLeftOut) {
  const auto s = read_with("t,F,r\n0,1,\n1,1,0.01\n2,1,\n3,1,\n4,1,\n", {});
  EXPECT_FALSE(s.has("r"));
  EXPECT_TRUE(has_note(s, "column 'r' has 1 values"));
}

}  // namespace
}  // namespace snapjump::measure
