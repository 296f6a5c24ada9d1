#include "theory/design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "theory/prefactors.hpp"

namespace snapjump::theory {
namespace {

// The theory's thin, shallow shell: beyond about h / R = 0.19 its ranges are not defined
// (Prediction::beyond_range); no search goes past this.
constexpr double kMaxThickness = 0.18;

std::vector<double> log_grid(double lo, double hi, int n) {
  std::vector<double> v;
  if (n <= 1 || hi <= lo) return {lo};
  for (int i = 0; i < n; ++i) v.push_back(lo * std::pow(hi / lo, i / static_cast<double>(n - 1)));
  return v;
}

// One requirement's relative slack (>= 0: met) and what it says when it binds.
struct Slack {
  double value;
  std::string what;
};

std::vector<Slack> slacks(const Prediction& p, const DesignTargets& t, const DesignSpace& s) {
  std::vector<Slack> out;
  const auto mm = [](double v) { return fmt::format("{:.4g} mm", 1e3 * v); };
  if (t.H) {
    out.push_back({p.H.lo / t.H->lo - 1.0,
                   fmt::format("H's lower bound {} against at least {}", mm(p.H.lo), mm(t.H->lo))});
    if (t.H->hi) {
      out.push_back({*t.H->hi / p.H.hi - 1.0, fmt::format("H's upper bound {} against at most {}",
                                                          mm(p.H.hi), mm(*t.H->hi))});
    }
  }
  if (t.F_star) {
    out.push_back({p.F_star.lo / t.F_star->lo - 1.0,
                   fmt::format("F*'s lower bound {:.4g} N against at least {:.4g} N", p.F_star.lo,
                               t.F_star->lo)});
    if (t.F_star->hi) {
      out.push_back({*t.F_star->hi / p.F_star.hi - 1.0,
                     fmt::format("F*'s upper bound {:.4g} N against at most {:.4g} N", p.F_star.hi,
                                 *t.F_star->hi)});
    }
  }
  out.push_back({p.jump_margin.lo / t.margin - 1.0,
                 fmt::format("F* / mg's lower bound {:.4g} against at least {:.4g}",
                             p.jump_margin.lo, t.margin)});
  out.push_back({p.snap_margin.lo - 1.0,
                 fmt::format("U / (mg H_l)'s lower bound {:.4g} against at least 1 (below 1 the "
                             "shell may not snap)",
                             p.snap_margin.lo)});
  if (t.energy) {
    out.push_back({p.inverted_energy / *t.energy - 1.0,
                   fmt::format("the stored energy {:.4g} mJ against at least {:.4g} mJ",
                               1e3 * p.inverted_energy, 1e3 * *t.energy)});
  }
  if (t.t_star) {
    out.push_back({*t.t_star / p.t_star.hi - 1.0,
                   fmt::format("t*'s upper bound {:.4g} ms against at most {:.4g} ms",
                               1e3 * p.t_star.hi, 1e3 * *t.t_star)});
  }
  if (s.max_suction) {
    out.push_back({*s.max_suction / p.zoelly_pc - 1.0,
                   fmt::format("the buckling suction (Zoelly's p_c) {:.4g} kPa against the pump's "
                               "{:.4g} kPa",
                               1e-3 * p.zoelly_pc, 1e-3 * *s.max_suction)});
  }
  return out;
}

void check_space(const config::Case& base, const DesignTargets& t, const DesignSpace& s) {
  const auto bad = [](const std::string& what) { throw config::CaseError("design: " + what); };
  if (!(s.net_weight_lo > 0.0) || s.net_weight_hi < s.net_weight_lo) {
    bad("the net weight must be positive (and a range from the smaller to the larger)");
  }
  if (!(s.max_footprint > 0.0)) bad("the largest footprint must be positive");
  if (!(s.min_h > 0.0)) bad("the thinnest wall must be positive");
  const double R_max = s.max_footprint / (2.0 * std::sin(base.shell.phi));
  if (!(s.min_R < R_max)) {
    bad(
        fmt::format("a footprint of {:.4g} mm allows R up to {:.4g} mm only, below the smallest "
                    "searched {:.4g} mm",
                    1e3 * s.max_footprint, 1e3 * R_max, 1e3 * s.min_R));
  }
  if (!(s.max_h_over_R > 0.0) || s.max_h_over_R > kMaxThickness) {
    bad(fmt::format("the thickest shell h / R must lie in (0, {}]", kMaxThickness));
  }
  if (s.min_h >= s.max_h_over_R * R_max) {
    bad(
        fmt::format("the thinnest wall {:.4g} mm is too thick for the theory at the largest R "
                    "the footprint allows ({:.4g} mm, h / R at most {})",
                    1e3 * s.min_h, 1e3 * R_max, s.max_h_over_R));
  }
  if (t.H && (!(t.H->lo > 0.0) || (t.H->hi && *t.H->hi < t.H->lo))) bad("H's target must be > 0");
  if (t.F_star && (!(t.F_star->lo > 0.0) || (t.F_star->hi && *t.F_star->hi < t.F_star->lo))) {
    bad("F*'s target must be > 0");
  }
  if (!(t.margin > 0.0)) bad("the margin F* / mg must be positive");
  if (s.grid < 2 || s.grid > 2000) bad("the search grid must have 2 to 2000 points a side");
}

double score(const Design& d, Rank r) {
  switch (r) {
    case Rank::Smallest:
      return d.footprint;
    case Rank::Lightest:
      return d.prediction.shell_mass;
    case Rank::Margin:
      return -d.prediction.jump_margin.lo;
    case Rank::Highest:
      return -d.prediction.H.lo;
  }
  return 0.0;
}

bool near(const Design& a, const Design& b) {
  constexpr double kApart = 0.05;  // 5 % in R, h and the net weight
  return std::abs(std::log(a.R / b.R)) < kApart && std::abs(std::log(a.h / b.h)) < kApart &&
         std::abs(std::log(a.net_weight / b.net_weight)) < kApart;
}

std::vector<Design> pareto_front(std::vector<Design> feasible) {
  std::sort(feasible.begin(), feasible.end(), [](const Design& a, const Design& b) {
    return a.footprint < b.footprint ||
           (a.footprint == b.footprint && a.prediction.H.lo > b.prediction.H.lo);
  });
  std::vector<Design> front;
  double best = -std::numeric_limits<double>::infinity();
  for (auto& d : feasible) {
    if (d.prediction.H.lo > best * 1.02) {  // 2 % higher than any smaller design: a new step
      best = d.prediction.H.lo;
      front.push_back(std::move(d));
    }
  }
  return front;
}

}  // namespace

std::optional<Rank> parse_rank(const std::string& s) {
  if (s == "smallest") return Rank::Smallest;
  if (s == "lightest") return Rank::Lightest;
  if (s == "margin") return Rank::Margin;
  if (s == "highest") return Rank::Highest;
  return std::nullopt;
}

std::string to_string(Rank r) {
  switch (r) {
    case Rank::Smallest:
      return "smallest footprint";
    case Rank::Lightest:
      return "lightest shell";
    case Rank::Margin:
      return "largest margin F* / mg";
    case Rank::Highest:
      return "highest jump (H's lower bound)";
  }
  return "";
}

config::Case design_case(const config::Case& base, double R, double h, double net_weight) {
  auto c = base;
  c.shell.R = R;
  c.shell.h = h;
  c.popper.net_weight = net_weight;
  const bool mass_defaulted =
      std::any_of(base.defaults_used.begin(), base.defaults_used.end(),
                  [](const std::string& d) { return d.starts_with("popper.mass"); });
  if (mass_defaulted) {
    // The case's rule for a default mass: a popper heavier than it needs no counterweight.
    c.popper.mass = std::max(config::kDefaultPopperMass, net_weight / config::kStandardGravity);
  }
  return c;
}

DesignResult design(const config::Case& base, const DesignTargets& targets,
                    const DesignSpace& space, Rank rank, int count) {
  check_space(base, targets, space);
  const auto& constants = contact_constants();
  const double R_max = space.max_footprint / (2.0 * std::sin(base.shell.phi));
  const auto weights = log_grid(space.net_weight_lo, space.net_weight_hi,
                                space.net_weight_hi > space.net_weight_lo ? space.grid / 4 : 1);
  DesignResult result;
  std::vector<Design> feasible;
  for (const double R : log_grid(space.min_R, R_max, space.grid)) {
    if (space.min_h >= space.max_h_over_R * R) continue;
    for (const double h : log_grid(space.min_h, space.max_h_over_R * R, space.grid)) {
      for (const double mg : weights) {
        Design d;
        d.R = R;
        d.h = h;
        d.net_weight = mg;
        d.prediction = predict(design_case(base, R, h, mg), constants);
        ++result.evaluated;
        if (!d.prediction.beyond_range.empty()) continue;
        d.footprint = 2.0 * d.prediction.rim_radius;
        d.slack = std::numeric_limits<double>::infinity();
        for (auto& s : slacks(d.prediction, targets, space)) {
          if (!(s.value >= d.slack)) {  // NaN binds too
            d.slack = std::isfinite(s.value) ? s.value : -std::numeric_limits<double>::infinity();
            d.binding = std::move(s.what);
          }
        }
        result.points.push_back(
            {h / R, base.material.E * h * h / mg, d.prediction.H.lo, d.slack >= 0.0});
        if (d.slack >= 0.0) {
          feasible.push_back(d);
        } else if (!result.closest || d.slack > result.closest->slack) {
          result.closest = d;
        }
      }
    }
  }
  if (feasible.empty()) {
    if (result.closest) {
      const auto& c = *result.closest;
      result.infeasible = fmt::format(
          "no design meets the targets within the constraints; the closest, R = {:.4g} mm, "
          "h = {:.4g} mm, mg = {:.4g} N (footprint {:.4g} mm), misses by {:.3g} %: {}",
          1e3 * c.R, 1e3 * c.h, c.net_weight, 1e3 * c.footprint, -100.0 * c.slack, c.binding);
    } else {
      result.infeasible = "no design in the search space lies within the theory's range";
    }
    return result;
  }
  result.pareto = pareto_front(feasible);
  std::stable_sort(feasible.begin(), feasible.end(), [&](const Design& a, const Design& b) {
    return score(a, rank) < score(b, rank);
  });
  for (auto& d : feasible) {
    if (static_cast<int>(result.designs.size()) >= count) break;
    if (std::none_of(result.designs.begin(), result.designs.end(),
                     [&](const Design& e) { return near(d, e); })) {
      result.designs.push_back(std::move(d));
    }
  }
  return result;
}

}  // namespace snapjump::theory
