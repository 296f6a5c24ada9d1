// `snapjump plot`: every figure from small synthetic inputs, through the command line in-process,
// and the error paths (exit 2 naming the file or column, exit 1 when gnuplot cannot run).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "config/case.hpp"
#include "config/text.hpp"
#include "plot/figures.hpp"
#include "plot/snapshots.hpp"
#include "plot/table.hpp"
#include "support/cli_runner.hpp"
#include "support/hostile_text.hpp"
#include "theory/scaling.hpp"

namespace snapjump::plot {
namespace {

namespace fs = std::filesystem;

using Result = test_support::CliResult;

Result run(std::vector<std::string> args) { return test_support::run_cli(std::move(args)); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool is_png(const fs::path& p) {
  const auto s = slurp(p);
  return s.size() > 8 && s.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

// A fresh folder per test, removed afterwards.
class Plot : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / fmt_name(std::string("snapjump_plot_") + info->name() + "_" +
                                                std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  // SNAPJUMP_KEEP_PLOTS=1 keeps the folders, to look at the figures.
  void TearDown() override {
    if (std::getenv("SNAPJUMP_KEEP_PLOTS") != nullptr) return;
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static std::string fmt_name(std::string s) {
    for (auto& c : s) {
      if (c == '/') c = '_';
    }
    return s;
  }
  fs::path dir_;
};

// --- synthetic inputs ---

// A run folder: series.csv (300 rows, a comment line), summary.json, and optionally run.pvd with
// two tiny snapshots.
fs::path make_run(const fs::path& dir, bool with_delta_p = true) {
  const auto run = dir / "run";
  fs::create_directories(run / "snapshots");
  {
    std::ofstream csv(run / "series.csv");
    csv << "# snapjump run (synthetic); SI units; t = 0 at the release\n";
    csv << "t,z,r,w,e,F" << (with_delta_p ? ",delta_p" : "") << ",contact\n";
    for (int i = 0; i < 300; ++i) {
      const double t = 1e-4 * i;
      const double z = t < 0.01 ? 0.0 : 0.5 * (t - 0.01) * (0.04 - t) * 40.0;
      const double r = t < 0.012 ? 0.02 * (1.0 - t / 0.012) : 0.0;
      const double w = 0.01 * (1.0 - t / 0.03);
      const double F = t < 0.012 ? 2.0 * std::sin(M_PI * t / 0.012) + 0.5 : 0.0;
      const double dp = 8000.0 * std::exp(-t / 0.005);
      const char* contact = t < 0.008 ? "ring" : (t < 0.012 ? "disk" : "none");
      csv << t << ',' << z << ',' << r << ',' << w << ',' << 0.004 << ',' << F;
      if (with_delta_p) csv << ',' << dp;
      csv << ',' << contact << '\n';
    }
  }
  nlohmann::json summary = {
      {"case", {{"title", "synthetic popper, (R, h) = (25, 2.5) mm"}}},
      {"measured",
       {{"quantities",
         {{"t_onset", {{"value", 0.008}, {"unit", "s"}}},
          {"t_launch", {{"value", 0.012}, {"unit", "s"}}},
          {"F_star", {{"value", 2.5}, {"unit", "N"}}},
          {"t_F_star", {{"value", 0.006}, {"unit", "s"}}},
          {"H", {{"value", 0.009}, {"unit", "m"}}}}}}},
      {"theory",
       {{"quantities",
         {{"F_star", {{"lower", 3.8}, {"upper", 6.0}, {"unit", "N"}}},
          {"H", {{"lower", 0.004}, {"upper", 0.012}, {"unit", "m"}}}}}}},
  };
  std::ofstream(run / "summary.json") << summary.dump(2);

  // Two snapshots of a small spherical cap (inner and outer surface), the second lifted by 5 mm.
  const auto write_vtu = [&](const fs::path& path, double lift) {
    std::vector<std::array<double, 3>> pts;
    const double R = 0.025;
    for (const double rad : {R - 0.00125, R + 0.00125}) {
      for (int i = 0; i <= 12; ++i) {
        const double theta = 1.4 * i / 12.0;
        for (int j = 0; j < 24; ++j) {
          const double az = 2.0 * M_PI * j / 24.0;
          pts.push_back({rad * std::sin(theta) * std::cos(az), rad * std::sin(theta) * std::sin(az),
                         rad * std::cos(theta) - R * std::cos(1.4) + lift});
        }
      }
    }
    std::ofstream out(path);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\""
        << pts.size()
        << "\" NumberOfCells=\"0\">\n      <Points>\n        <DataArray type=\"Float64\" "
           "Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const auto& p : pts) out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    out << "        </DataArray>\n      </Points>\n    </Piece>\n  </UnstructuredGrid>\n"
           "</VTKFile>\n";
  };
  write_vtu(run / "snapshots" / "frame_00000.vtu", 0.0);
  write_vtu(run / "snapshots" / "frame_00001.vtu", 0.005);
  std::ofstream(run / "run.pvd")
      << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
         "  <Collection>\n"
         "    <DataSet timestep=\"0\" part=\"0\" file=\"snapshots/frame_00000.vtu\"/>\n"
         "    <DataSet timestep=\"0.00500071504\" part=\"0\" file=\"snapshots/frame_00001.vtu\"/>\n"
         "  </Collection>\n</VTKFile>\n";
  return run;
}

std::string fmt_run(int i) {
  std::string s = std::to_string(i);
  return std::string(4 - s.size(), '0') + s;
}

// The sweep table's header, with a varied key in front.
const char* const kSweepHeader =
    "popper.net_weight [N],run,status,outcome,predicted_outcome,R [m],h [m],phi [rad],E [Pa],"
    "nu [1],rho [kg/m^3],mu [1],net_weight [N],moving_mass [kg],delta_p_j [Pa],p_c [Pa],r_c [m],"
    "e_c [m],F_c [N],t_c [s],h_over_R [1],Eh2_over_mg [1],Eh4_over_mgR2 [1],"
    "delta_p_j_over_p_c [1],r_star [m],e_star [m],F_star [N],t_star [s],H_l [m],H_s [m],H [m],"
    "alpha_r [1],alpha_e [1],alpha_F [1],alpha_t [1],r_star_lo [m],r_star_hi [m],e_star_lo [m],"
    "e_star_hi [m],F_star_lo [N],F_star_hi [N],t_star_lo [s],t_star_hi [s],H_l_lo [m],"
    "H_l_hi [m],H_s_lo [m],H_s_hi [m],H_lo [m],H_hi [m],alpha_r_lo [1],alpha_r_hi [1],"
    "alpha_e_lo [1],alpha_e_hi [1],alpha_F_lo [1],alpha_F_hi [1],alpha_t_lo [1],alpha_t_hi [1],"
    "wall_time [s],error";

// A six-run sweep over the net weight, thickness and friction, with the theory's numbers and
// made-up "measured" ones; run 0005 failed. Case files under runs/<run>/ when with_cases.
fs::path make_sweep(const fs::path& dir, bool with_cases = true, const std::string& drop = "") {
  const auto& k = theory::contact_constants();
  std::string header = kSweepHeader;
  if (!drop.empty()) {
    const auto pos = header.find("," + drop + " [");
    header.erase(pos, header.find(',', pos + 1) - pos);
  }
  std::ostringstream csv;
  csv << header << '\n';
  const double mgs[] = {0.2, 0.48, 1.0, 2.0, 4.0, 0.48};
  const double hs[] = {2.5e-3, 2.0e-3, 1.5e-3, 1.0e-3, 2.5e-3, 2.0e-3};
  const double mus[] = {0.0, 0.1, 0.2, 0.3, 0.5, 0.3};
  const char* outcomes[] = {"Jump", "Jump", "Snap", "No snap", "Thrown", "undetermined"};
  for (int i = 0; i < 6; ++i) {
    auto c = config::default_case();
    c.popper.net_weight = mgs[i];
    c.shell.h = hs[i];
    c.friction.mu = mus[i];
    const auto p = theory::predict(c, k);
    const std::string run = fmt_run(i);
    if (with_cases) {
      fs::create_directories(dir / "runs" / run);
      std::ofstream(dir / "runs" / run / "case.toml") << config::to_toml(c);
    }
    const bool failed = i == 5;
    const double R = c.shell.R, h = c.shell.h, E = c.material.E, mg = mgs[i];
    const auto meas = [&](double v) { return failed ? std::string() : std::to_string(v); };
    std::vector<std::string> cells = {
        std::to_string(mg),
        run,
        failed ? "failed" : "ok",
        outcomes[i],
        p.outcome.text(),
        std::to_string(R),
        std::to_string(h),
        std::to_string(c.shell.phi),
        std::to_string(E),
        std::to_string(c.material.nu),
        std::to_string(c.material.rho),
        std::to_string(mus[i]),
        std::to_string(mg),
        std::to_string(c.popper.moving_mass()),
        std::to_string(p.delta_p_j),
        std::to_string(p.zoelly_pc),
        std::to_string(p.r_c),
        std::to_string(p.e_c),
        std::to_string(p.F_c),
        std::to_string(p.t_c),
        std::to_string(h / R),
        std::to_string(E * h * h / mg),
        std::to_string(E * std::pow(h, 4) / (mg * R * R)),
        std::to_string(p.delta_p_j / p.zoelly_pc + 0.05 * i),
        meas(1.4 * p.r_c),
        meas(1.9 * p.e_c),
        meas(3.0 * p.F_c),
        meas(0.7 * p.t_c),
        meas(0.9 * p.H_l.lo),
        meas(0.3 * p.H_s.lo),
        meas(0.9 * p.H_l.lo + 0.3 * p.H_s.lo),
        meas(1.4),
        meas(1.9),
        meas(3.0),
        meas(0.7 + 0.1 * mus[i]),
        std::to_string(p.r_star.lo),
        std::to_string(p.r_star.hi),
        std::to_string(p.e_star.lo),
        std::to_string(p.e_star.hi),
        std::to_string(p.F_star.lo),
        std::to_string(p.F_star.hi),
        std::to_string(p.t_star.lo),
        std::to_string(p.t_star.hi),
        std::to_string(p.H_l.lo),
        std::to_string(p.H_l.hi),
        std::to_string(p.H_s.lo),
        std::to_string(p.H_s.hi),
        std::to_string(p.H.lo),
        std::to_string(p.H.hi),
        std::to_string(p.alpha.alpha_r.lo),
        std::to_string(p.alpha.alpha_r.hi),
        std::to_string(p.alpha.alpha_e.lo),
        std::to_string(p.alpha.alpha_e.hi),
        std::to_string(p.alpha.alpha_F.lo),
        std::to_string(p.alpha.alpha_F.hi),
        std::to_string(p.alpha.alpha_t.lo),
        std::to_string(p.alpha.alpha_t.hi),
        "12.5",
        failed ? "\"step 1200: inverted element 17, at t = 0.01 s, \"\"det F <= 0\"\"\"" : ""};
    if (!drop.empty()) {
      // The same column as in the header.
      std::istringstream names(kSweepHeader);
      std::string name;
      for (std::size_t j = 0; std::getline(names, name, ','); ++j) {
        if (name.rfind(drop + " [", 0) == 0) {
          cells.erase(cells.begin() + static_cast<std::ptrdiff_t>(j));
          break;
        }
      }
    }
    for (std::size_t j = 0; j < cells.size(); ++j) csv << (j > 0 ? "," : "") << cells[j];
    csv << '\n';
  }
  const auto path = dir / "table.csv";
  std::ofstream(path) << csv.str();
  return path;
}

// --- tests ---

TEST(PlotTable, ReadsQuotedFieldsCommentsAndUnits) {
  std::istringstream in(
      "# a comment\n"
      "mu [1],run,R [m],error,mu [1]\n"
      "0.5,0001,0.025,,0.3\n"
      "# another\n"
      "\n"
      "0.5,0002,,\"a, b \"\"c\"\"\"\n");
  const auto t = Table::read_csv(in, "t.csv");
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.unit("R"), "m");
  EXPECT_EQ(t.text(0, "run"), "0001");
  EXPECT_DOUBLE_EQ(*t.number(0, "R"), 0.025);
  EXPECT_FALSE(t.number(1, "R").has_value());
  EXPECT_EQ(t.text(1, "error"), "a, b \"c\"");
  EXPECT_DOUBLE_EQ(*t.number(0, "mu"), 0.3);    // a repeated name means its last column
  EXPECT_FALSE(t.number(1, "mu").has_value());  // a short row is padded
  try {
    (void)t.number(0, "H_l");
    FAIL() << "expected a missing column";
  } catch (const PlotInputError& e) {
    EXPECT_TRUE(contains(e.what(), "'H_l'")) << e.what();
    EXPECT_TRUE(contains(e.what(), "t.csv")) << e.what();
  }
}

TEST_F(Plot, SeriesPngHasLabelsAndMarks) {
  const auto run_dir = make_run(dir_);
  const auto r = run({"plot", "series", run_dir.string()});
  ASSERT_EQ(r.code, app::kExitOk) << r.err << r.out;
  const auto png = run_dir / "figures" / "series.png";
  const auto gp = run_dir / "figures" / "series.gp";
  ASSERT_TRUE(fs::exists(png));
  EXPECT_TRUE(is_png(png));
  const auto script = slurp(gp);
  for (const char* label : {"t after release [ms]", "container height z [mm]", "r, w [mm]",
                            "plate force F [N]", "δp [kPa]", "onset (8.0 ms)", "launch (12.0 ms)",
                            "theory F* bounds", "ring contact", "disk contact"}) {
    EXPECT_TRUE(contains(script, label)) << label;
  }
  EXPECT_TRUE(contains(r.out, png.string())) << r.out;
}

TEST_F(Plot, SeriesSvgToChosenFile) {
  const auto run_dir = make_run(dir_);
  const auto out = dir_ / "elsewhere" / "jump.svg";
  const auto r = run({"plot", "series", run_dir.string(), "--output", out.string()});
  ASSERT_EQ(r.code, app::kExitOk) << r.err;
  EXPECT_TRUE(contains(slurp(out), "<svg"));
  EXPECT_TRUE(fs::exists(dir_ / "elsewhere" / "jump.gp"));
  const auto clash =
      run({"plot", "series", run_dir.string(), "--output", out.string(), "--format", "png"});
  EXPECT_EQ(clash.code, app::kExitBadInput);
}

TEST_F(Plot, SeriesMissingColumnNamesIt) {
  const auto run_dir = make_run(dir_, false);
  const auto r = run({"plot", "series", run_dir.string()});
  EXPECT_EQ(r.code, app::kExitBadInput);
  EXPECT_TRUE(contains(r.err, "'delta_p'")) << r.err;
  EXPECT_TRUE(contains(r.err, "series.csv")) << r.err;
}

TEST_F(Plot, MissingRunFolder) {
  const auto missing = (dir_ / "no_such_run").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"plot", "series", missing}, {"plot", "sections", missing, "--times", "0"}}) {
    const auto r = run(args);
    EXPECT_EQ(r.code, app::kExitBadInput) << args[1];
    EXPECT_TRUE(contains(r.err, missing)) << r.err;
  }
}

TEST_F(Plot, SectionsAtTwoTimes) {
  const auto run_dir = make_run(dir_);
  const auto r =
      run({"plot", "sections", run_dir.string(), "--times", "0,4.9ms", "--format", "svg"});
  ASSERT_EQ(r.code, app::kExitOk) << r.err;
  EXPECT_TRUE(contains(slurp(run_dir / "figures" / "sections.svg"), "<svg"));
  const auto script = slurp(run_dir / "figures" / "sections.gp");
  for (const char* label :
       {"x [mm]", "height above the plate z [mm]", "plate z = 0", "t = 0.0 ms", "t = 5.0 ms"}) {
    EXPECT_TRUE(contains(script, label)) << label;
  }
  EXPECT_TRUE(contains(r.out, "nearest snapshot")) << r.out;  // 4.9 ms -> the 5.0 ms frame
  const auto bad = run({"plot", "sections", run_dir.string(), "--times", "0,5kg"});
  EXPECT_EQ(bad.code, app::kExitBadInput);
  EXPECT_TRUE(contains(bad.err, "--times")) << bad.err;
}

TEST_F(Plot, SweepFigures) {
  const auto table = make_sweep(dir_);
  const std::vector<std::pair<std::string, std::vector<std::string>>> figures = {
      {"scaling",
       {"r_c = √(hR) [mm]", "F_c = E h^3 / R [N]", "t_c = √(m R / (E h^2)) [ms]",
        "theory bounds (contact solver)", "simulation: Jump", "simulation: Snap"}},
      {"lift", {"δp_j / p_c [-]", "lift H_l [mm]"}},
      {"flight", {"E h^4 / (m g R^2) [-]", "H_s / R [-]"}},
      {"phase",
       {"aspect ratio h / R [-]", "E h^2 / (m g) [-]", "Snap / No snap", "$snap",
        "simulation: Thrown", "failed / no outcome"}},
      {"friction", {"friction coefficient μ [-]", "α_F = F* / (E h^3 / R) [-]"}},
  };
  for (const auto& [figure, labels] : figures) {
    const auto r = run({"plot", "sweep", table.string(), "--figure", figure});
    ASSERT_EQ(r.code, app::kExitOk) << figure << ": " << r.err;
    const auto png = dir_ / "figures" / (figure + ".png");
    EXPECT_TRUE(is_png(png)) << figure;
    const auto script = slurp(dir_ / "figures" / (figure + ".gp"));
    for (const auto& label : labels)
      EXPECT_TRUE(contains(script, label)) << figure << ": " << label;
  }
}

TEST_F(Plot, PhaseWithoutCaseFilesDrawsTheJumpLineOnly) {
  const auto table = make_sweep(dir_, false);
  const auto r = run({"plot", "sweep", table.string(), "--figure", "phase"});
  ASSERT_EQ(r.code, app::kExitOk) << r.err;
  EXPECT_TRUE(contains(r.out, "note: no usable case file")) << r.out;
  const auto script = slurp(dir_ / "figures" / "phase.gp");
  EXPECT_FALSE(contains(script, "$snap"));
  EXPECT_TRUE(contains(script, "F*/mg = 1"));
}

TEST_F(Plot, SweepMissingColumnNamesIt) {
  const auto table = make_sweep(dir_, false, "H_l");
  const auto r = run({"plot", "sweep", table.string(), "--figure", "lift"});
  EXPECT_EQ(r.code, app::kExitBadInput);
  EXPECT_TRUE(contains(r.err, "'H_l'")) << r.err;
  EXPECT_TRUE(contains(r.err, "table.csv")) << r.err;
}

TEST_F(Plot, SweepEmptyTableAndMissingFile) {
  std::ofstream(dir_ / "empty.csv") << kSweepHeader << '\n';
  const auto r = run({"plot", "sweep", (dir_ / "empty.csv").string(), "--figure", "scaling"});
  EXPECT_EQ(r.code, app::kExitBadInput);
  EXPECT_TRUE(contains(r.err, "empty table")) << r.err;
  const auto m = run({"plot", "sweep", (dir_ / "nope.csv").string(), "--figure", "scaling"});
  EXPECT_EQ(m.code, app::kExitBadInput);
  EXPECT_TRUE(contains(m.err, "nope.csv")) << m.err;
}

TEST_F(Plot, ContactBranches) {
  const auto csv = dir_ / "branches.csv";
  std::ofstream(csv) << "branch,a,N,e_hat,c1,residual,min_gap\n"
                        "disk,1e-8,0.01,0.00125,0.1,1e-14,0\n"
                        "disk,1.0,20.0,2.6,0.5,1e-13,0\n"
                        "disk,2.74796,76.943,7.4635,-2.1,1e-13,0\n"
                        "ring,6.0,95.0,18.5,,1e-12,0\n"
                        "ring,3.0223,72.0968,7.618,,1e-12,0\n"
                        "ring,2.74844,76.904,7.4609,,1e-12,0\n";
  const auto r = run({"plot", "contact", csv.string()});
  ASSERT_EQ(r.code, app::kExitOk) << r.err;
  EXPECT_TRUE(is_png(dir_ / "branches.png"));
  const auto script = slurp(dir_ / "branches.gp");
  for (const char* label : {"plane displacement ê = √κ e / h [-]", "force N = κ F R / (E h^3) [-]",
                            "disk branch", "ring branch"}) {
    EXPECT_TRUE(contains(script, label)) << label;
  }
  std::ofstream(dir_ / "bad.csv") << "branch,a,e_hat\ndisk,1,2\n";
  const auto bad = run({"plot", "contact", (dir_ / "bad.csv").string()});
  EXPECT_EQ(bad.code, app::kExitBadInput);
  EXPECT_TRUE(contains(bad.err, "'N'")) << bad.err;
}

TEST_F(Plot, ContactFiguresOfTwoPoissonRatiosDoNotOverwriteEachOther) {
  const std::string table =
      "branch,a,N,e_hat,c1,residual,min_gap\ndisk,1e-8,0.01,0.00125,0.1,1e-14,0\n"
      "disk,1.0,20.0,2.6,0.5,1e-13,0\nring,6.0,95.0,18.5,,1e-12,0\n";
  std::ofstream(dir_ / "a-nu0.3.csv") << table;
  std::ofstream(dir_ / "b-nu0.45.csv") << table;
  ASSERT_EQ(run({"plot", "contact", (dir_ / "a-nu0.3.csv").string()}).code, app::kExitOk);
  ASSERT_EQ(run({"plot", "contact", (dir_ / "b-nu0.45.csv").string()}).code, app::kExitOk);
  EXPECT_TRUE(is_png(dir_ / "a-nu0.3.png"));
  EXPECT_TRUE(is_png(dir_ / "b-nu0.45.png"));
  EXPECT_TRUE(fs::exists(dir_ / "b-nu0.45.gp"));
  // An image name whose extension snapjump cannot write is refused, not filled with PNG data.
  const auto pdf = run(
      {"plot", "contact", (dir_ / "a-nu0.3.csv").string(), "--output", (dir_ / "x.pdf").string()});
  EXPECT_EQ(pdf.code, app::kExitBadInput);
  EXPECT_TRUE(contains(pdf.err, "png or svg")) << pdf.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.pdf"));
}

TEST_F(Plot, SeriesWithAnExperimentBesideItInAWindow) {
  const auto run_dir = make_run(dir_);
  // A record with F, w and a contact column only: its onset (disk) at 18 ms falls on the run's
  // 8 ms; the panels of z and delta_p are left out.
  const auto record = dir_ / "record.csv";
  {
    std::ofstream out(record);
    out << "Time (s);Fz (N);w (mm);contact\n";
    for (int i = 0; i < 300; ++i) {
      const double t = 1e-4 * i;
      out << t << ';' << (t < 0.022 ? 1.0 : 0.0) << ';' << 10.0 * (1.0 - t / 0.04) << ';'
          << (t < 0.018 ? "ring" : "disk") << '\n';
    }
  }
  const auto r = run({"plot", "series", run_dir.string(), "--experiment", record.string(),
                      "--window", "5ms:15ms"});
  ASSERT_EQ(r.code, app::kExitOk) << r.err << r.out;
  const auto png = run_dir / "figures" / "series-experiment.png";
  EXPECT_TRUE(is_png(png));
  const auto script = slurp(run_dir / "figures" / "series-experiment.gp");
  EXPECT_TRUE(contains(script, "set xrange [5:15]")) << script.substr(0, 400);
  EXPECT_TRUE(contains(script, "'experiment F'"));
  EXPECT_TRUE(contains(script, "dt 2 lc rgb")) << "the run is dashed beside a record";
  EXPECT_TRUE(contains(script, "'experiment apex gap w'"));
  EXPECT_FALSE(contains(script, "container height z [mm]"));
  EXPECT_FALSE(contains(script, "δp ["));
  EXPECT_TRUE(contains(r.out, "the record's 0.018 s drawn at the run's 0.008 s")) << r.out;
  EXPECT_TRUE(contains(r.out, "the record has no z: that panel is left out")) << r.out;
  // From the release instead: no shift.
  const auto rel = run({"plot", "series", run_dir.string(), "--experiment", record.string(),
                        "--align", "release", "--output", (dir_ / "rel.svg").string()});
  ASSERT_EQ(rel.code, app::kExitOk) << rel.err;
  EXPECT_FALSE(contains(rel.out, "drawn at the run's")) << rel.out;
  // A record in another spelling, named by --column and --unit as for analyze.
  const auto other = dir_ / "zeit.csv";
  std::ofstream(other) << "Zeit;Kraft\n0;500\n10;2500\n20;0\n30;0\n";
  const auto mapped = run({"plot", "series", run_dir.string(), "--experiment", other.string(),
                           "--column", "t=Zeit", "--column", "F=Kraft", "--unit", "t=ms", "--unit",
                           "F=mN", "--output", (dir_ / "zeit.png").string()});
  ASSERT_EQ(mapped.code, app::kExitOk) << mapped.err;
  EXPECT_TRUE(contains(slurp(dir_ / "zeit.gp"), "'experiment F'"));
  // A window that ends before it starts.
  const auto bad = run({"plot", "series", run_dir.string(), "--window", "15ms:5ms"});
  EXPECT_EQ(bad.code, app::kExitBadInput);
}

TEST_F(Plot, MissingGnuplotIsAFailureNamingTheScript) {
  const auto run_dir = make_run(dir_);
  ::setenv("SNAPJUMP_GNUPLOT", "/nonexistent/gnuplot", 1);
  const auto r = run({"plot", "series", run_dir.string()});
  ::unsetenv("SNAPJUMP_GNUPLOT");
  EXPECT_EQ(r.code, app::kExitFailure);
  EXPECT_TRUE(contains(r.err, "series.gp")) << r.err;
  EXPECT_TRUE(contains(r.err, "gnuplot")) << r.err;
  EXPECT_TRUE(fs::exists(run_dir / "figures" / "series.gp"));  // kept for the user
}

TEST_F(Plot, GnuplotErrorIsReported) {
  FigureResult paths;
  paths.script = dir_ / "broken.gp";
  paths.figure = dir_ / "broken.png";
  try {
    render(paths, "set output 'broken.png'\nplot $nothing using 1:2\n", "gnuplot");
    FAIL() << "expected gnuplot to fail";
  } catch (const PlotError& e) {
    EXPECT_TRUE(contains(e.what(), "broken.gp")) << e.what();
  }
}

// --- Nothing a user writes becomes a gnuplot command ---

// A line that makes gnuplot create `marker` if it is ever read as a command, wrapped in newlines
// (and a carriage return) so that it stands on a line of its own unless the newlines are taken
// out; the quote tries to close a single-quoted string first.
std::string hostile(const fs::path& marker) {
  return "x'\nsystem('touch " + marker.string() + "')\r\n# ";
}

TEST(PlotSnapshots, DamagedSnapshotsAreRefusedNotReadPastTheirEnd) {
  // Inputs that crashed or could exhaust memory before: a <Piece without '>', a point count
  // far beyond the file, a count that is not a whole number.
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_plot_bad_vtu";
  std::filesystem::create_directories(dir);
  const auto refuse = [&](const std::string& text) {
    std::ofstream(dir / "f.vtu") << text;
    try {
      (void)read_vtu_points(dir / "f.vtu");
    } catch (const PlotInputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refuse("<VTKFile><Piece NumberOfPoints=\"3\""), "");
  const std::string grid =
      "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
      "0 0 0\n</DataArray>";
  EXPECT_NE(refuse("<Piece NumberOfPoints=\"1e18\">" + grid).find("NumberOfPoints"),
            std::string::npos);
  EXPECT_NE(refuse("<Piece NumberOfPoints=\"2.5\">" + grid), "");
  EXPECT_NE(refuse("<Piece NumberOfPoints=\"50\">" + grid).find("fewer coordinates"),
            std::string::npos);
  EXPECT_EQ(refuse("<Piece NumberOfPoints=\"1\">" + grid), "");  // the good one
}

TEST(PlotInputs, AnErrorQuotesAShortEscapedExcerptOfTheFile) {
  using test_support::quotes_only_an_excerpt;
  const auto bad = test_support::hostile_text();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("snapjump_plot_hostile_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto error = [&](const std::string& name, const std::string& text, auto read) {
    std::ofstream(dir / name, std::ios::binary) << text;
    try {
      read(dir / name);
    } catch (const PlotInputError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << name << " was read";
    return std::string();
  };
  // A table's cell where a number is read (a quoted cell may hold a line break).
  EXPECT_TRUE(
      quotes_only_an_excerpt(error("t.csv", "t,F\n0,\"" + bad + "\"\n", [](const fs::path& p) {
        (void)Table::read_csv_file(p).numbers("F");
      })));
  // A collection's timestep and file, a snapshot's format.
  const auto pvd = [](const fs::path& p) { (void)read_pvd(p); };
  EXPECT_TRUE(quotes_only_an_excerpt(
      error("a.pvd", "<DataSet timestep=\"" + bad + "\" file=\"f.vtu\"/>", pvd)));
  EXPECT_TRUE(quotes_only_an_excerpt(
      error("b.pvd", "<DataSet timestep=\"0\" file=\"" + bad + "\"/>", pvd)));
  EXPECT_TRUE(
      quotes_only_an_excerpt(error("f.vtu",
                                   "<Piece NumberOfPoints=\"1\">\n<Points>\n<DataArray format=\"" +
                                       bad + "\">\n0 0 0\n</DataArray>",
                                   [](const fs::path& p) { (void)read_vtu_points(p); })));
  std::filesystem::remove_all(dir);
}

TEST(PlotScript, QuotedTextHasNoControlCharacters) {
  std::string every;
  for (int c = 1; c < 128; ++c) every += static_cast<char>(c);
  for (const auto& s : {quote(every), quote(hostile("/tmp/m")), printable(every)}) {
    for (const char c : s) {
      const auto u = static_cast<unsigned char>(c);
      EXPECT_FALSE(u < 0x20 || u == 0x7f) << "control character " << int(u) << " in " << s;
    }
  }
  EXPECT_EQ(quote("it's"), "'it''s'");
  EXPECT_EQ(quote("a\nb"), "'a b'");
  const auto block = datablock("d", "x\nEOD\nsystem('true')", {{1.0, 2.0}});
  EXPECT_EQ(block, "$d << EOD\n# x EOD system('true')\n1 2\nEOD\n");
}

TEST_F(Plot, HostileTitleIsNotRunByGnuplot) {
  const auto run_dir = make_run(dir_);
  const auto marker = dir_ / "title-ran";
  nlohmann::json summary = nlohmann::json::parse(slurp(run_dir / "summary.json"));
  summary["case"]["title"] = hostile(marker);
  std::ofstream(run_dir / "summary.json") << summary.dump(2);
  const auto r = run({"plot", "series", run_dir.string()});
  ASSERT_EQ(r.code, app::kExitOk) << r.err << r.out;
  EXPECT_FALSE(fs::exists(marker)) << "gnuplot ran a command from the case title";
  const auto script = slurp(run_dir / "figures" / "series.gp");
  EXPECT_FALSE(contains(script, "\nsystem(")) << script;
  EXPECT_TRUE(contains(script, "system(''touch")) << "the title is kept, as text";
}

TEST_F(Plot, AHugeTitleIsCutBeforeItReachesGnuplot) {
  const auto run_dir = make_run(dir_);
  nlohmann::json summary = nlohmann::json::parse(slurp(run_dir / "summary.json"));
  summary["case"]["title"] = "start of the title " + std::string(20'000'000, 'x') + " its end";
  std::ofstream(run_dir / "summary.json") << summary.dump(2);
  const auto r = run({"plot", "series", run_dir.string()});
  ASSERT_EQ(r.code, app::kExitOk) << r.err << r.out;
  const auto script = slurp(run_dir / "figures" / "series.gp");
  EXPECT_LT(script.size(), 100'000u);
  const std::string kept = "'start of the title " + std::string(text::kMaxTitleBytes - 22, 'x');
  EXPECT_TRUE(contains(script, kept + "...'")) << script.substr(0, 2000);
  EXPECT_FALSE(contains(script, "its end"));
}

TEST_F(Plot, HostileRunFolderNameIsNotRunByGnuplot) {
  // A folder's name cannot hold '/': the command names a file in the folder gnuplot runs in.
  const auto run_dir = dir_ / hostile("folder-ran");
  const auto marker = run_dir / "figures" / "folder-ran";
  fs::rename(make_run(dir_), run_dir);
  nlohmann::json summary = nlohmann::json::parse(slurp(run_dir / "summary.json"));
  summary["case"].erase("title");  // the figure's title falls back to the folder's name
  std::ofstream(run_dir / "summary.json") << summary.dump(2);
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"plot", "series", run_dir.string()},
           {"plot", "sections", run_dir.string(), "--times", "0"}}) {
    const auto r = run(args);
    ASSERT_EQ(r.code, app::kExitOk) << args[1] << ": " << r.err << r.out;
    EXPECT_FALSE(fs::exists(marker)) << "gnuplot ran a command from the folder's name: " << args[1];
  }
}

TEST_F(Plot, OutputNameWithAControlCharacterIsRefused) {
  const auto run_dir = make_run(dir_);
  const auto marker = dir_ / "output-ran";
  const auto out = dir_ / (hostile(marker) + ".png");
  const auto r = run({"plot", "series", run_dir.string(), "--output", out.string()});
  EXPECT_EQ(r.code, app::kExitBadInput) << r.err << r.out;
  EXPECT_TRUE(contains(r.err, "control character")) << r.err;
  EXPECT_FALSE(fs::exists(marker));
}

}  // namespace
}  // namespace snapjump::plot

namespace snapjump::plot {
namespace {

// The design figure: every searched design, the listed ones numbered, the Jump / Snap line at
// both ends of alpha_F; its datablocks hold the designs the command listed.
TEST_F(Plot, DesignFigureMarksTheListedDesigns) {
  const auto image = dir_ / "design.svg";
  const auto r = run({"design", "--jump-height", "50mm", "--net-weight", "1N", "--count", "2",
                      "--no-branch", "--grid", "40", "--figure", image.string()});
  ASSERT_EQ(r.code, app::kExitOk) << r.err;
  EXPECT_TRUE(fs::exists(image));
  EXPECT_TRUE(contains(r.out, "figure " + image.string())) << r.out;
  const auto script = slurp(dir_ / "design.gp");
  for (const char* block : {"$searched", "$feasible", "$chosen", "$jump_lo", "$jump_hi"}) {
    EXPECT_TRUE(contains(script, block)) << block;
  }
  const auto bad = run({"design", "--figure", (dir_ / "design.pdf").string(), "--no-branch"});
  EXPECT_EQ(bad.code, app::kExitBadInput);
  EXPECT_TRUE(contains(bad.err, ".png or .svg")) << bad.err;
}

}  // namespace
}  // namespace snapjump::plot
