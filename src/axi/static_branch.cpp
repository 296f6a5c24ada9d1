#include "axi/static_branch.hpp"

#include <fmt/format.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

#include "axi/contact.hpp"
#include "axi/surface_stretch.hpp"

namespace snapjump::axi {
namespace {

using Vec = Eigen::VectorXd;
using Sparse = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// The contacts' smoothing length over the element's thickness (axi/contact.hpp): a thousandth,
// a thousand times the central differences' step, so that the differences see the regularised
// law's stiffness, not a jump.
constexpr double kSmoothing = 1e-3;

// The equilibrium problem in the free degrees of freedom u (every node's r and z but the rim
// face's, and the axis nodes' r): the residual dPi/du of the potential
// Pi = W + dp V + the contacts' penalty energy, its stiffness, and the volume's gradient.
class Problem {
 public:
  Problem(const Body& body, bool contacts)
      : body_(body),
        contacts_(contacts),
        self_(body, default_contact_stiffness(body),
              kSmoothing * body.spec().h / body.spec().through),
        cone_(rim_cone(body.spec())),
        eps_(1e-6 * body.spec().h / body.spec().through) {
    const std::size_t n = body.num_nodes();
    dof_r_.assign(n, -1);
    dof_z_.assign(n, -1);
    std::vector<char> rim(n, 0), axis(n, 0);
    for (int a : body.rim()) rim[a] = 1;
    for (int a : body.axis()) axis[a] = 1;
    for (std::size_t a = 0; a < n; ++a) {
      if (rim[a]) continue;
      if (!axis[a]) dof_r_[a] = dofs_++;
      dof_z_[a] = dofs_++;
    }
    contact_rows_.assign(n, {});
    for (int a : body.inner()) {
      if (rim[a]) continue;
      contact_nodes_.push_back(a);
      contact_rows_[a] = body.inner();
    }
    make_colours();
  }

  [[nodiscard]] int dofs() const { return dofs_; }

  void scatter(const Vec& u, Points& x) const {
    for (std::size_t a = 0; a < x.size(); ++a) {
      if (dof_r_[a] >= 0) x.r[a] = u[dof_r_[a]];
      if (dof_z_[a] >= 0) x.z[a] = u[dof_z_[a]];
    }
  }
  [[nodiscard]] Vec gather(const Points& x) const {
    Vec u(dofs_);
    for (std::size_t a = 0; a < x.size(); ++a) {
      if (dof_r_[a] >= 0) u[dof_r_[a]] = x.r[a];
      if (dof_z_[a] >= 0) u[dof_z_[a]] = x.z[a];
    }
    return u;
  }

  [[nodiscard]] Vec residual(const Points& x, double dp) const {
    Points f = zero();
    element_forces(x, dp, f);
    if (contacts_) contact_forces(x, f);
    return -gather(f);
  }
  // dV/du: the pressure load of dp = -1.
  [[nodiscard]] Vec volume_gradient(const Points& x) const {
    Points f = zero();
    body_.add_pressure_forces(x, -1.0, f);
    return gather(f);
  }
  [[nodiscard]] Triplets stiffness(const Points& x, double dp) const;
  // The self-contact's deepest crossing [m] and how many separate regions touch.
  [[nodiscard]] InnerSelfContact::Touch self_contact(const Points& x) const {
    return self_.touch(x);
  }

 private:
  [[nodiscard]] Points zero() const {
    return {std::vector<double>(body_.num_nodes(), 0.0),
            std::vector<double>(body_.num_nodes(), 0.0)};
  }
  void element_forces(const Points& x, double dp, Points& f) const {
    body_.internal_forces(x, f);
    body_.add_pressure_forces(x, dp, f);
  }
  // The self-contact, and the cone as a penalty of the same law on the inner surface's nodes that
  // have crossed its rigid part by g.
  void contact_forces(const Points& x, Points& f) const {
    self_.add_forces(x, f);
    const auto& in = body_.inner();
    const auto& area = self_.areas();
    for (std::size_t i = 0; i < in.size(); ++i) {
      const int a = in[i];
      if (dof_z_[a] < 0) continue;
      const double g = cone_.gap(x.r[a], x.z[a], 0.0);
      if (!(g > 0.0) || cone_.along(x.r[a], x.z[a], 0.0) < cone_.s_min) continue;
      const double push = self_.stiffness() * area[i] * penalty(g, self_.smoothing()).force;
      f.r[a] -= push * cone_.nr();
      f.z[a] -= push * cone_.nz();
    }
  }
  void make_colours();
  template <typename Forces>
  void differences(const Points& x, const std::vector<int>& moved,
                   const std::vector<std::vector<int>>& rows, Forces forces, Triplets& out) const;

  const Body& body_;
  bool contacts_;
  InnerSelfContact self_;
  RimCone cone_;
  double eps_;  // the central differences' step [m]
  int dofs_ = 0;
  std::vector<int> dof_r_, dof_z_;
  std::vector<int> contact_nodes_;
  // The contacts couple any two inner nodes: each contact node's rows are all the inner nodes.
  std::vector<std::vector<int>> contact_rows_;
  std::vector<std::vector<int>> colours_;     // nodes no element holds two of
  std::vector<std::vector<int>> neighbours_;  // per node: the nodes its elements hold
};

void Problem::make_colours() {
  const std::size_t n = body_.num_nodes();
  neighbours_.assign(n, {});
  for (const auto& el : body_.elements()) {
    for (int a : el) neighbours_[a].insert(neighbours_[a].end(), el.begin(), el.end());
  }
  for (auto& list : neighbours_) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  // Greedy: each node takes the first colour none of its neighbours' neighbours has (two nodes
  // perturbed together must not share an element, or their forces would mix on a common row).
  std::vector<int> colour(n, -1);
  for (std::size_t a = 0; a < n; ++a) {
    std::vector<char> taken;
    for (int b : neighbours_[a]) {
      for (int c : neighbours_[b]) {
        if (colour[c] < 0) continue;
        if (taken.size() <= static_cast<std::size_t>(colour[c])) taken.resize(colour[c] + 1, 0);
        taken[colour[c]] = 1;
      }
    }
    int c = 0;
    while (c < static_cast<int>(taken.size()) && taken[c]) ++c;
    colour[a] = c;
    if (colours_.size() <= static_cast<std::size_t>(c)) colours_.resize(c + 1);
    colours_[c].push_back(static_cast<int>(a));
  }
}

// Central differences of forces(x, f) moving the nodes `moved` together, in r and then in z:
// the stiffness entries -df/du of each moved node's column on the rows of rows[node].
template <typename Forces>
void Problem::differences(const Points& x, const std::vector<int>& moved,
                          const std::vector<std::vector<int>>& rows, Forces forces,
                          Triplets& out) const {
  for (int dir = 0; dir < 2; ++dir) {
    const auto& col = dir == 0 ? dof_r_ : dof_z_;
    Points plus = x, minus = x;
    bool any = false;
    for (int a : moved) {
      if (col[a] < 0) continue;
      auto& p = dir == 0 ? plus.r : plus.z;
      auto& m = dir == 0 ? minus.r : minus.z;
      p[a] += eps_;
      m[a] -= eps_;
      any = true;
    }
    if (!any) continue;
    Points fp = zero(), fm = zero();
    forces(plus, fp);
    forces(minus, fm);
    for (int a : moved) {
      if (col[a] < 0) continue;
      for (int b : rows[a]) {
        const double dr = -(fp.r[b] - fm.r[b]) / (2.0 * eps_);
        const double dz = -(fp.z[b] - fm.z[b]) / (2.0 * eps_);
        if (dof_r_[b] >= 0 && dr != 0.0) out.emplace_back(dof_r_[b], col[a], dr);
        if (dof_z_[b] >= 0 && dz != 0.0) out.emplace_back(dof_z_[b], col[a], dz);
      }
    }
  }
}

Triplets Problem::stiffness(const Points& x, double dp) const {
  Triplets t;
  const auto elements = [&](const Points& y, Points& f) { element_forces(y, dp, f); };
  for (const auto& nodes : colours_) differences(x, nodes, neighbours_, elements, t);
  if (!contacts_) return t;
  // The contacts couple any two inner nodes: one node at a time, every inner node's row.
  const auto contacts = [&](const Points& y, Points& f) { contact_forces(y, f); };
  Points f = zero();
  contact_forces(x, f);
  const bool active = std::any_of(contact_nodes_.begin(), contact_nodes_.end(),
                                  [&](int a) { return f.r[a] != 0.0 || f.z[a] != 0.0; });
  if (!active) return t;
  for (int a : contact_nodes_) differences(x, {a}, contact_rows_, contacts, t);
  return t;
}

// One point of the branch: the state and where it lies in (v, q).
struct State {
  Vec u;
  double q = 0.0, v = 1.0;
};

// (v - v0) tv + (q - q0) tq + (u - u0) . tu / scale = ds: the arclength counts the nodes'
// displacement too (its root mean square over the element's thickness), or a buckle that moves
// the shell at almost the same volume and pressure would be one point of the arc.
struct Arc {
  Vec u0, tu;
  double v0, q0, tv, tq, ds, scale;
};

class Tracer {
 public:
  Tracer(const Body& body, const BranchOptions& o)
      : body_(body),
        o_(o),
        problem_(body, o.contacts),
        x_(body.nodes()),
        V0_(body.cavity_volume(body.nodes())) {
    const double a = body.spec().R * std::sin(body.spec().phi);
    force_scale_ = o.p_ref * std::numbers::pi * a * a;
  }
  StaticBranch run();

 private:
  // Newton from the predictor s on the arc, damped; the iterations it took, or nothing.
  std::optional<int> correct(State& s, const Arc& arc);
  double damped(const State& s, const Vec& d, double residual);
  BranchPoint point(const State& s, int iterations);
  bool at_end_dp(State& s, const State& before);
  // Reports the points up to (not including) `end` not yet reported (BranchOptions::progress).
  void report(const StaticBranch& b, std::size_t end) {
    for (; o_.progress && reported_ < end; ++reported_) o_.progress(b.points[reported_]);
  }

  const Body& body_;
  const BranchOptions& o_;
  Problem problem_;
  Points x_;
  double V0_;
  double force_scale_ = 0.0;
  // The stiffness at fixed dp of the corrector's last iteration, one Newton correction (below
  // the tolerance) from the point it converged to: what the stability check factorises.
  Triplets last_stiffness_;
  std::size_t reported_ = 1;  // the natural state, point 0, is not reported
};

std::optional<int> Tracer::correct(State& s, const Arc& arc) {
  const int n = problem_.dofs();
  Eigen::SparseLU<Sparse, Eigen::COLAMDOrdering<int>> lu;
  for (int it = 0; it < 30; ++it) {
    problem_.scatter(s.u, x_);
    Vec r;
    try {
      r = problem_.residual(x_, s.q * o_.p_ref);
    } catch (const fem::InvertedElement&) {
      return std::nullopt;
    }
    s.v = body_.cavity_volume(x_) / V0_;
    const double c = (s.v - arc.v0) * arc.tv + (s.q - arc.q0) * arc.tq +
                     (s.u - arc.u0).dot(arc.tu) / arc.scale - arc.ds;
    if (!r.allFinite()) return std::nullopt;
    if (it > 0 && r.norm() <= o_.tolerance * force_scale_ && std::abs(c) <= 1e-12) return it;
    auto t = problem_.stiffness(x_, s.q * o_.p_ref);
    last_stiffness_ = t;
    const Vec g = problem_.volume_gradient(x_);
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, n, o_.p_ref * g[i]);                              // d r / d q
      t.emplace_back(n, i, arc.tv * g[i] / V0_ + arc.tu[i] / arc.scale);  // d c / d u
    }
    t.emplace_back(n, n, arc.tq);
    Sparse A(n + 1, n + 1);
    A.setFromTriplets(t.begin(), t.end());
    lu.compute(A);
    if (lu.info() != Eigen::Success) return std::nullopt;
    Vec rhs(n + 1);
    rhs.head(n) = -r;
    rhs[n] = -c;
    const Vec d = lu.solve(rhs);
    if (!d.allFinite()) return std::nullopt;
    const double step = damped(s, d, r.norm());
    s.u += step * d.head(n);
    s.q += step * d[n];
  }
  return std::nullopt;
}

// The share of Newton's correction d to take from s: the first of 1, 1/2, ..., 1/1024 at which the
// residual is smaller than `residual`, or all of it where none is (the corrector then goes on
// as undamped Newton would). Where a node first touches, the contacts' stiffness is not in the
// Jacobian of a state that touches nothing, and the full correction crosses far past the touch.
double Tracer::damped(const State& s, const Vec& d, double residual) {
  const int n = problem_.dofs();
  double step = 1.0;
  for (int k = 0; k <= 10; ++k, step *= 0.5) {
    problem_.scatter(s.u + step * d.head(n), x_);
    try {
      const Vec r = problem_.residual(x_, (s.q + step * d[n]) * o_.p_ref);
      if (r.allFinite() && r.norm() < residual) return step;
    } catch (const fem::InvertedElement&) {
    }
  }
  return 1.0;
}

BranchPoint Tracer::point(const State& s, int iterations) {
  problem_.scatter(s.u, x_);
  const int apex = body_.apex();
  const auto crease = largest_compressed_ratio(inner_surface_stretches(body_, x_));
  const auto [depth, regions] = o_.contacts ? problem_.self_contact(x_) : InnerSelfContact::Touch{};
  return {s.v * V0_,    s.q * o_.p_ref, x_.z[apex] - body_.nodes().z[apex],
          iterations,   depth,          regions,
          crease.ratio, crease.from_rim};
}

// The extremum of dp among points[i - 1 .. i + 1] by a parabola in the arclength of (v, q).
void refine(const std::vector<BranchPoint>& p, std::size_t i, double V0, double p_ref, double& dp,
            double& v) {
  dp = p[i].dp;
  v = p[i].volume / V0;
  if (i == 0 || i + 1 >= p.size()) return;
  const auto dist = [&](std::size_t a, std::size_t b) {
    return std::hypot((p[b].volume - p[a].volume) / V0, (p[b].dp - p[a].dp) / p_ref);
  };
  const double s0 = -dist(i - 1, i), s2 = dist(i, i + 1);
  const double f0 = p[i - 1].dp, f1 = p[i].dp, f2 = p[i + 1].dp;
  // Divided differences of the parabola through (s0, f0), (0, f1), (s2, f2).
  const double a = ((f2 - f1) / s2 - (f1 - f0) / -s0) / (s2 - s0);
  const double b = (f2 - f1) / s2 - a * s2;
  if (!(a != 0.0)) return;
  const double s = std::clamp(-b / (2.0 * a), s0, s2);
  dp = f1 + b * s + a * s * s;
  const double t = s < 0 ? s / s0 : s / s2;  // linear in v on the side it falls
  const std::size_t j = s < 0 ? i - 1 : i + 1;
  v = (p[i].volume + t * (p[j].volume - p[i].volume)) / V0;
}

// Local extrema of dp along the points: p_c the first maximum; after it p_- the lowest minimum
// and p_hold the last one (when the branch reached its end).
void find_extrema(StaticBranch& b, double p_ref) {
  const auto& p = b.points;
  std::size_t i = 1;
  while (i + 1 < p.size() && !(p[i].dp > p[i - 1].dp && p[i].dp >= p[i + 1].dp)) ++i;
  if (i + 1 >= p.size()) return;
  refine(p, i, b.V0, p_ref, b.p_c, b.v_c);
  std::size_t lowest = 0, last = 0;
  for (++i; i + 1 < p.size(); ++i) {
    if (!(p[i].dp < p[i - 1].dp && p[i].dp <= p[i + 1].dp)) continue;
    if (lowest == 0 || p[i].dp < p[lowest].dp) lowest = i;
    last = i;
  }
  if (lowest == 0) return;
  refine(p, lowest, b.V0, p_ref, b.p_minus, b.v_minus);
  if (b.reached_end) refine(p, last, b.V0, p_ref, b.p_hold, b.v_hold);
}

// Whether the stiffness at fixed dp is positive definite (the state stable under pressure
// control): a Cholesky-type factorisation of its symmetric part succeeds with positive pivots.
bool positive_definite(const Triplets& t, int n) {
  Sparse H(n, n);
  H.setFromTriplets(t.begin(), t.end());
  const Sparse S = 0.5 * (H + Sparse(H.transpose()));
  Eigen::SimplicialLDLT<Sparse> ldlt(S);
  return ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 0.0;
}

constexpr double kMinTurnCosine = 0.9;
// How many times a trace may take a point again with a shorter step (Tracer::run).
constexpr int kMaxStepsBack = 20;

// The cosine between the arc's tangent and the step from s to next.
double turn(const State& s, const State& next, const Arc& arc, double scale) {
  const double dv = next.v - s.v, dq = next.q - s.q;
  const Vec du = (next.u - s.u) / scale;
  const double len = std::sqrt(dv * dv + dq * dq + du.squaredNorm());
  if (!(len > 0.0)) return 1.0;
  return (dv * arc.tv + dq * arc.tq + du.dot(arc.tu)) / len;
}

StaticBranch Tracer::run() {
  StaticBranch b;
  b.V0 = V0_;
  // The walk's state: the last point s and the one before it, the step that led to s, and where
  // the branch is (rise: -1 rising to p_c, 0 falling after a maximum, 1 rising after a minimum;
  // inverted_minimum: the last minimum lay on the inverted side, V < 0).
  struct Walk {
    State s;
    std::optional<State> previous;
    double taken;
    int rise;
    bool inverted_minimum;
  };
  Walk walk{State{problem_.gather(body_.nodes()), 0.0, 1.0}, std::nullopt, o_.step, -1, false};
  auto& [s, previous, taken, rise, inverted_minimum] = walk;
  b.points.push_back(point(s, 0));
  double ds = o_.step;
  const double scale = body_.spec().h * std::sqrt(static_cast<double>(s.u.size()));
  // The walk as it was before the last point was taken, to take that point again with a
  // shorter step (below).
  std::optional<Walk> before_last;
  int steps_back = 0;
  // With through_snaps: the highest maximum of the inverted segment below end_dp passed so far.
  std::optional<State> highest;
  std::vector<std::size_t> passed_at;  // the points of b.passed_maxima
  // Where the last step closed a crease (its point has more separate regions of the inner surface
  // in self-contact than the one before), the secant cuts the corner between the branch with the
  // crease open and the one with it closed, and points back along the second towards the touch
  // and onto the first: the walk goes on from the point under volume control, the volume falling
  // towards inversion, and keeps the step only if the crease stays closed. Where no step that way
  // keeps it closed, however short (the closed branch leaves the touch with the volume rising
  // before it turns), the volume rises instead.
  bool from_touch = false;
  double touch_direction = -1.0;
  const auto touched = [&b] {
    return b.points.size() > 1 &&
           b.points.back().contact_regions > b.points.end()[-2].contact_regions;
  };
  while (static_cast<int>(b.points.size()) < o_.max_points) {
    State trial = s;
    // The first step, and the first from a touch: volume control, the volume decreasing (from a
    // touch, rising where falling found no closed state).
    const double tv = from_touch ? touch_direction : -1.0;
    Arc arc{s.u, Vec::Zero(s.u.size()), s.v, s.q, tv, 0.0, ds, scale};
    if (previous && !from_touch) {
      const double dv = s.v - previous->v, dq = s.q - previous->q;
      const Vec du = (s.u - previous->u) / scale;
      const double len = std::sqrt(dv * dv + dq * dq + du.squaredNorm());
      arc.tv = dv / len;
      arc.tq = dq / len;
      arc.tu = du / len;
      const double k = ds / taken;
      trial.u += k * (s.u - previous->u);
      trial.q += k * (s.q - previous->q);
    }
    auto iterations = correct(trial, arc);
    // A step is kept only if it goes on in the direction it was predicted in: within about 25
    // degrees of the secant, in (v, q, u / scale). A sharper turn is a corrector that has
    // jumped onto another part of the branch (or back along it).
    if (iterations && previous && !from_touch && turn(s, trial, arc, scale) < kMinTurnCosine) {
      iterations.reset();
    }
    if (iterations && from_touch) {
      problem_.scatter(trial.u, x_);
      if (problem_.self_contact(x_).regions < b.points.back().contact_regions) iterations.reset();
    }
    if (!iterations) {
      ds *= 0.5;
      if (ds < o_.min_step && from_touch && touch_direction < 0.0) {
        touch_direction = 1.0;
        ds = taken;
        continue;
      }
      // Past a sharp turn (a maximum whose curvature one step spans) the secant of the last
      // step can lie more than the turn limit off the branch's tangent at its end, so that no
      // step from there, however short, is kept: the last point is taken again, with a quarter
      // of its step, and the walk goes on from the shorter secant.
      if (ds < o_.min_step && before_last && steps_back < kMaxStepsBack) {
        ds = 0.25 * taken;
        walk = *before_last;
        before_last.reset();
        b.points.pop_back();
        from_touch = touched();
        touch_direction = -1.0;
        ++steps_back;
        continue;
      }
      if (ds < o_.min_step) {
        b.stop_reason = fmt::format(
            "the continuation found no equilibrium within an arclength step of {:.2g} after "
            "V / V0 = {:.4g}, dp = {:.6g} Pa",
            o_.min_step, s.v, s.q * o_.p_ref);
        break;
      }
      continue;
    }
    before_last = walk;
    previous = s;
    s = trial;
    taken = ds;
    b.points.push_back(point(s, *iterations));
    from_touch = touched();
    touch_direction = -1.0;
    report(b, b.points.size() - 1);
    if (o_.check_folds) {
      try {
        body_.check_folds(x_);
      } catch (const fem::FoldedElement& e) {
        b.stop_reason =
            fmt::format("at V / V0 = {:.4g}, dp = {:.6g} Pa: {}", s.v, s.q * o_.p_ref, e.what());
        b.fold = e;
        break;
      }
    }
    if (s.v < o_.end_volume) {
      b.reached_end = true;
      break;
    }
    const double dq = s.q - previous->q;
    if (o_.stop_inverted_without_buckling && rise < 0 && dq > 0 && s.v < -1.0) {
      b.stop_reason = fmt::format(
          "the cap turned inside out (V / V0 = {:.4g}) under a suction that only rose, to {:.6g} "
          "Pa, without a buckling maximum",
          s.v, s.q * o_.p_ref);
      break;
    }
    const bool turned_up = rise == 0 && dq > 0;    // previous was a minimum
    const bool turned_down = rise == 1 && dq < 0;  // previous was a maximum after one
    if (rise < 0 && dq < 0) rise = 0;              // past a maximum
    if (turned_up) {                               // and then a minimum
      rise = 1;
      inverted_minimum = previous->v < 0.0;
    }
    if (turned_down) rise = 0;
    const bool rising_to_end = rise == 1 && inverted_minimum && std::isfinite(o_.end_dp) &&
                               s.q * o_.p_ref < o_.end_dp && s.v < 0.0;
    if (turned_down && inverted_minimum && previous->v < 0.0 && std::isfinite(o_.end_dp) &&
        previous->q * o_.p_ref < o_.end_dp) {
      if (o_.through_snaps) {
        // (A maximum passed again after the walk took points again replaces the first passage.)
        const std::size_t at = b.points.size() - 2;
        while (!passed_at.empty() && passed_at.back() >= at) {
          passed_at.pop_back();
          b.passed_maxima.pop_back();
        }
        passed_at.push_back(at);
        b.passed_maxima.push_back(previous->q * o_.p_ref);
        if (!highest || previous->q > highest->q) highest = *previous;
      } else {
        b.snaps_below_end = true;
        s = *previous;
        b.points.pop_back();
        break;
      }
    }
    if (rising_to_end && !turned_up && !o_.through_snaps &&
        !positive_definite(last_stiffness_, problem_.dofs())) {
      b.loses_stability_below_end = true;
      s = *previous;
      b.points.pop_back();
      break;
    }
    // end_dp is met on the inverted side only (V < 0: the shell through its rim's plane).
    if (rise == 1 && s.v < 0.0 && std::isfinite(o_.end_dp) && s.q * o_.p_ref >= o_.end_dp) {
      if (previous->q * o_.p_ref < o_.end_dp) {
        const State past = s;
        b.reached_end = at_end_dp(s, *previous);
        if (b.reached_end && o_.through_snaps &&
            !positive_definite(last_stiffness_, problem_.dofs())) {
          s = past;  // an unstable crossing: the shell does not stop there
          b.reached_end = false;
        } else {
          if (b.reached_end) b.points.back() = point(s, 0);
          if (!b.reached_end) b.stop_reason = "no equilibrium at exactly end_dp next to the branch";
          break;
        }
      }
      // A minimum on the inverted side above end_dp: the foot of a segment that never gets
      // down to end_dp. (A segment that rose from a minimum at V > 0 and crosses into V < 0
      // above end_dp is followed on: it may turn and come down to the inverted side's own.)
      if (turned_up && previous->v < 0.0) {
        b.reached_end = b.end_above = true;
        break;
      }
    }
    if (*iterations <= 3) ds = std::min(o_.step, 1.5 * ds);
    if (*iterations >= 8) ds *= 0.7;
  }
  if (!b.reached_end && b.stop_reason.empty()) {
    b.stop_reason = fmt::format("stopped after {} points", b.points.size());
  }
  // A shell under pressure control snaps from the highest maximum passed over every state of
  // the branch below it: a fold at one of those is never reached, and the shell snaps from that
  // maximum in time.
  if (!b.reached_end && highest && (!b.fold || b.points.back().dp <= highest->q * o_.p_ref)) {
    s = *highest;
    b.snaps_below_end = true;
  }
  report(b, b.points.size());
  find_extrema(b, o_.p_ref);
  problem_.scatter(s.u, x_);
  b.state = x_;
  b.state_dp = s.q * o_.p_ref;
  try {
    b.stable = positive_definite(problem_.stiffness(x_, s.q * o_.p_ref), problem_.dofs());
  } catch (const fem::InvertedElement&) {
    b.stable = false;
  }
  return b;
}

// From the point s just past end_dp and the one before it: the equilibrium at end_dp (pressure
// control, from the linear interpolation of the two). s becomes it.
bool Tracer::at_end_dp(State& s, const State& before) {
  const double target = o_.end_dp / o_.p_ref;
  const double f = (target - before.q) / (s.q - before.q);
  State trial = before;
  trial.u += f * (s.u - before.u);
  trial.q = target;
  const Arc arc{trial.u, Vec::Zero(trial.u.size()), 0.0, target, 0.0, 1.0, 0.0, 1.0};
  if (!correct(trial, arc)) return false;
  s = trial;
  return true;
}

}  // namespace

StaticBranch trace_static_branch(const Body& body, const BranchOptions& options) {
  if (!(options.p_ref > 0.0) || !(options.step > 0.0) || !(options.min_step > 0.0) ||
      !(options.min_step <= options.step) || !(options.tolerance > 0.0) || options.max_points < 2 ||
      !std::isfinite(options.end_volume)) {
    throw std::invalid_argument(fmt::format(
        "unusable branch options: p_ref {} Pa, step {} (min {}), tolerance {}, {} points",
        options.p_ref, options.step, options.min_step, options.tolerance, options.max_points));
  }
  return Tracer(body, options).run();
}

}  // namespace snapjump::axi
