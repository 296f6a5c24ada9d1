// The readers' shared rules: CSV records (text::split_csv) and whole files (text::read_file).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "config/csv.hpp"
#include "config/files.hpp"
#include "config/text.hpp"

namespace snapjump::text {
namespace {

using Cells = std::vector<std::string>;

std::vector<CsvRecord> split(std::string_view csv, char sep = ',') {
  return split_csv<std::runtime_error>(csv, sep, "t.csv");
}

std::string problem(std::string_view csv, char sep = ',') {
  try {
    (void)split(csv, sep);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Csv, CellsAreTrimmedUnlessQuoted) {
  const auto r = split(" a , b ,\" c \"\n1,2,3");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].cells, (Cells{"a", "b", " c "}));
  EXPECT_EQ(r[1].cells, (Cells{"1", "2", "3"}));
  EXPECT_EQ(r[0].line, 1u);
  EXPECT_EQ(r[1].line, 2u);
}

TEST(Csv, QuotedCellsHoldSeparatorsLineBreaksAndQuotes) {
  const auto r = split("name,note\n\"a, b\",\"say \"\"x\"\"\nand y\"\nlast,row\n");
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[1].cells, (Cells{"a, b", "say \"x\"\nand y"}));
  EXPECT_EQ(r[1].line, 2u);
  EXPECT_EQ(r[2].cells, (Cells{"last", "row"}));
  EXPECT_EQ(r[2].line, 4u);  // the quoted line break counts
}

TEST(Csv, CommentsBlankRecordsAndByteOrderMark) {
  const auto r = split("\xEF\xBB\xBF# made by a lab\n\n  # indented comment\nt,F\r\n\n0,1\r\n");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].cells, (Cells{"t", "F"}));
  EXPECT_EQ(r[0].line, 4u);
  EXPECT_EQ(r[1].cells, (Cells{"0", "1"}));
  EXPECT_EQ(r[1].line, 6u);
}

TEST(Csv, EmptyCellsAndATrailingSeparator) {
  const auto r = split("a,,c,\n,\n");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].cells, (Cells{"a", "", "c", ""}));
  EXPECT_EQ(r[1].cells, (Cells{"", ""}));
  EXPECT_EQ(split("a,b,").front().cells, (Cells{"a", "b", ""}));
}

TEST(Csv, LinesOfBlanksAndIndentedCommentsAreSkippedWhateverTheSeparator) {
  // Spreadsheets end tab-separated exports with lines of tabs.
  const auto r = split("t\tF\n\t\t\n0\t1\n\t# note\n\t\t\r\n1\t2\n", '\t');
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[1].cells, (Cells{"0", "1"}));
  EXPECT_EQ(r[2].cells, (Cells{"1", "2"}));
  EXPECT_EQ(r[2].line, 6u);
  EXPECT_EQ(detect_separator("\t\t\n\t# c\nt\tF\n"), '\t');
}

TEST(Csv, RecordsOneAtATime) {
  CsvReader reader("a,b\n\"x\ny\",2\n\"open\n", ',');
  CsvRecord rec;
  ASSERT_TRUE(reader.next(rec));
  EXPECT_EQ(rec.cells, (Cells{"a", "b"}));
  ASSERT_TRUE(reader.next(rec));
  EXPECT_EQ(rec.cells, (Cells{"x\ny", "2"}));
  EXPECT_EQ(rec.line, 2u);
  EXPECT_FALSE(reader.next(rec));
  ASSERT_TRUE(reader.problem());
  EXPECT_EQ(reader.problem()->line, 4u);
  EXPECT_FALSE(reader.next(rec));  // and stays stopped
}

TEST(Csv, TabAndSemicolonSeparators) {
  // A tab that separates is not a blank: an empty cell before a quoted one stays a cell.
  const auto r = split("t\tF\tnote\n0\t\t\"x\ty\"\n", '\t');
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[1].cells, (Cells{"0", "", "x\ty"}));
  const auto s = split("t;F\n0,5;1,25\n", ';');
  EXPECT_EQ(s[1].cells, (Cells{"0,5", "1,25"}));
}

TEST(Csv, BrokenQuotesNameTheLine) {
  EXPECT_EQ(problem("a,b\n1,\"open\nstill\n"), "t.csv:2: a quoted cell is never closed");
  EXPECT_EQ(problem("a,b\n\"x\"y,2\n"), "t.csv:2: text after the closing quote of a cell");
  EXPECT_EQ(problem("a,b\n\"x\"  ,2\n"), "no error");  // blanks after the quote are fine
}

TEST(Csv, ALineOfMoreThanAThousandCellsIsRefusedBeforeItsCellsAreMade) {
  EXPECT_EQ(split(std::string(kMaxCells - 1, ',') + "\n1\n").front().cells.size(), kMaxCells);
  EXPECT_EQ(problem("t,F\n1,2\n" + std::string(kMaxCells, ',') + "\n"),
            "t.csv:3: more than 1000 cells on one line");
  // 2e7 separators (20 MB): refused at once, without 2e7 strings.
  const std::string wide = "t,F" + std::string(20'000'000, ',') + "\n0,1\n";
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(problem(wide), "t.csv:1: more than 1000 cells on one line");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

TEST(Text, ATitleIsCutAtACharactersBoundary) {
  EXPECT_EQ(capped_title("a popper"), "a popper");
  const std::string exact(kMaxTitleBytes, 'x');
  EXPECT_EQ(capped_title(exact), exact);
  const auto cut = capped_title(std::string(100'000'000, 'y'));
  EXPECT_EQ(cut, std::string(kMaxTitleBytes - 3, 'y') + "...");
  // "é" is two bytes: the cut never splits it.
  std::string accents;
  while (accents.size() < 2 * kMaxTitleBytes) accents += "\xc3\xa9";
  const auto cut_accents = capped_title("z" + accents);
  EXPECT_LE(cut_accents.size(), kMaxTitleBytes);
  EXPECT_EQ(cut_accents.substr(cut_accents.size() - 5), "\xc3\xa9...");
}

TEST(Csv, SeparatorOfTheHeaderLine) {
  EXPECT_EQ(detect_separator("# comment; with; semicolons\nt [s],F [N]\n"), ',');
  EXPECT_EQ(detect_separator("\n# c\nt [s];F [N]\n0,1;2\n"), ';');
  EXPECT_EQ(detect_separator("t\tF\n"), '\t');
  EXPECT_EQ(detect_separator("\"a;b\",c\n"), ',');
  EXPECT_EQ(detect_separator("\"t, s\";F\n"), ';');  // the comma is inside quotes
  EXPECT_EQ(detect_separator(""), ',');
}

class ReadFile : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest runs the tests side by side.
    dir_ = std::filesystem::temp_directory_path() /
           ("snapjump_read_file_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

std::string read_error(const std::filesystem::path& p, std::uintmax_t max = kAnySize) {
  try {
    (void)read_file<std::runtime_error>(p, "a test file", max);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST_F(ReadFile, BytesAsWritten) {
  const auto p = dir_ / "bytes.bin";
  const std::string bytes("a\0b\r\n\xff", 6);
  std::ofstream(p, std::ios::binary) << bytes;
  EXPECT_EQ(read_file<std::runtime_error>(p), bytes);
}

TEST_F(ReadFile, SaysWhatWentWrong) {
  EXPECT_EQ(read_error(dir_ / "none.csv"),
            (dir_ / "none.csv").string() + ": no such file (a test file)");
  EXPECT_EQ(read_error(dir_), dir_.string() + ": is a folder, not a file (a test file)");
  const auto p = dir_ / "big.txt";
  std::ofstream(p) << "0123456789";
  EXPECT_EQ(read_error(p, 4),
            p.string() + ": more than the 4 bytes such a file can have (a test file)");
  EXPECT_EQ(read_error(p, 10), "no error");
  // A pipe could be endless: it is refused, not read.
  const auto fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(read_error(fifo), fifo.string() + ": is not a regular file (a test file)");
}

}  // namespace
}  // namespace snapjump::text
