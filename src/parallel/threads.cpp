#include "parallel/threads.hpp"

#include <omp.h>

#include <stdexcept>

namespace snapjump::parallel {

namespace {
// A call at the most threads that takes this many times the one-thread median ends the trial at
// once: under load one such call costs as much as dozens of ordinary ones.
constexpr double kHopeless = 4.0;
// A trial that finds one thread faster by less than this factor is a close call: on a shared
// virtual machine such a verdict often comes from a moment when the other core was taken (its
// steps are then briefly no faster than one thread's), so the next trial comes after a sixteenth
// of the period. A clear verdict (a loaded core) waits the whole period.
constexpr double kClose = 1.25;
}  // namespace

ScopedThreadCount::ScopedThreadCount(int threads) : previous_(omp_get_max_threads()) {
  omp_set_num_threads(std::max(1, threads));
}

ScopedThreadCount::~ScopedThreadCount() { omp_set_num_threads(previous_); }

int max_threads() { return omp_get_max_threads(); }

ThreadTuner::ThreadTuner(int max_threads, int trial, int period)
    : max_(std::max(1, max_threads)),
      trial_(trial),
      period_(period),
      settled_for_(period),
      current_(max_),
      chosen_(max_) {
  if (trial < 1 || period < 2 * trial) {
    throw std::invalid_argument("thread tuner: needs trial >= 1 and period >= 2 trial");
  }
  if (max_ > 1) start_trial();
}

ThreadTuner ThreadTuner::fixed(int threads) {
  ThreadTuner t(threads);
  t.tune_ = false;
  t.phase_ = Phase::Settled;
  t.current_ = t.max_;
  return t;
}

ThreadTuner ThreadTuner::for_process(bool tune) {
  const int threads = parallel::max_threads();
  return tune ? ThreadTuner(threads) : fixed(threads);
}

void ThreadTuner::start_trial() {
  one_.clear();
  many_.clear();
  watched_.clear();
  phase_ = Phase::TrialOne;
  current_ = 1;
  since_trial_ = 0;
}

double ThreadTuner::median(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

void ThreadTuner::record(double seconds) {
  if (!tune_ || max_ <= 1) return;
  switch (phase_) {
    case Phase::TrialOne:
      one_.push_back(seconds);
      if (static_cast<int>(one_.size()) == trial_) {
        phase_ = Phase::TrialMax;
        current_ = max_;
      }
      return;
    case Phase::TrialMax: {
      many_.push_back(seconds);
      one_median_ = median(one_);
      const bool hopeless = seconds > kHopeless * one_median_;
      if (hopeless || static_cast<int>(many_.size()) == trial_) {
        const double many_median = median(many_);
        chosen_ = !hopeless && many_median < one_median_ ? max_ : 1;
        current_ = chosen_;
        phase_ = Phase::Settled;
        ++trials_;
        since_trial_ = 0;
        const bool close = chosen_ == 1 && !hopeless && many_median < kClose * one_median_;
        settled_for_ = close ? std::max(2 * trial_, period_ / 16) : period_;
        if (close) ++close_calls_;
      }
      return;
    }
    case Phase::Settled:
      if (++since_trial_ >= settled_for_) {
        start_trial();
      } else if (chosen_ > 1 && !watch(seconds)) {
        ++early_trials_;
        start_trial();
      }
      return;
  }
}

bool ThreadTuner::watch(double seconds) {
  if (seconds > kHopeless * one_median_) return false;
  watched_.push_back(seconds);
  if (static_cast<int>(watched_.size()) < trial_) return true;
  const bool slower = median(watched_) > one_median_;
  watched_.clear();
  return !slower;
}

}  // namespace snapjump::parallel
