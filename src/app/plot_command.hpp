// `snapjump plot`: figures with gnuplot (plot/figures.hpp, docs/figures.md).
//
//   snapjump plot series RUN_DIR                        Fig. 2(a)
//   snapjump plot sections RUN_DIR --times 0,0.2,0.45   Fig. 1(c)
//   snapjump plot sweep TABLE.csv --figure scaling|lift|flight|phase|friction
//   snapjump plot contact CURVES.csv                    Fig. S2(a)
//
// Each takes --format png|svg and --output FILE. The environment variable SNAPJUMP_GNUPLOT names
// the gnuplot program (default: gnuplot on the PATH).
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace snapjump::app {

class PlotCommand {
 public:
  // Adds the `plot` subcommand and its own subcommands to `app`. The options refer to this
  // object, so it must outlive the parse.
  explicit PlotCommand(CLI::App& app);
  PlotCommand(const PlotCommand&) = delete;
  PlotCommand& operator=(const PlotCommand&) = delete;

  // Whether the command line chose `plot`.
  [[nodiscard]] bool parsed() const;
  // Draws the chosen figure; returns the exit status (2 on bad input, 1 when gnuplot fails) and
  // prints errors to err.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* plot_ = nullptr;
  CLI::App* series_ = nullptr;
  CLI::App* sections_ = nullptr;
  CLI::App* sweep_ = nullptr;
  CLI::App* contact_ = nullptr;
  std::string input_;   // RUN_DIR, TABLE.csv or CURVES.csv
  std::string format_;  // png or svg; empty: from --output's extension, else png
  std::string output_;
  std::string times_;
  std::string figure_;
  std::string experiment_;  // plot series: a measured record drawn beside the run
  std::string window_;      // plot series: "450ms:560ms"
  std::string align_ = "onset";
  std::vector<std::string> columns_;  // plot series: NAME=HEADER for the record
  std::vector<std::string> units_;    // plot series: NAME=UNIT for the record
};

}  // namespace snapjump::app
