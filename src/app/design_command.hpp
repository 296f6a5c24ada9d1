// `snapjump design`: from targets for a jump to the spherical caps that meet them by the theory's
// lower bounds (theory::design), ranked, with the footprint-height trade-off, and with --verify
// the best of them simulated beside their predictions (docs/design.md).
#pragma once

#include <ostream>
#include <string>

#include "app/case_options.hpp"

namespace CLI {
class App;
}

namespace snapjump::app {

class DesignCommand {
 public:
  explicit DesignCommand(CLI::App& app);  // registers the subcommand and its options
  [[nodiscard]] bool parsed() const;
  // Returns the exit status; bad input throws config::CaseError (the caller prints it).
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* cmd_ = nullptr;
  CaseOptions base_;
  std::string height_, force_, energy_, t_star_, net_weight_max_, footprint_ = "100 mm",
                                                                  min_h_ = "0.5 mm", suction_;
  double margin_ = 1.0;
  double max_h_over_R_ = 0.1;
  std::string rank_ = "smallest";
  int count_ = 5;
  int grid_ = 120;
  std::string format_ = "table";
  bool no_branch_ = false;
  std::string figure_;
  int verify_ = 0;
  std::string model_ = "axisymmetric", resolution_ = "default", output_ = "runs/design";
  int jobs_ = 0;
};

}  // namespace snapjump::app
