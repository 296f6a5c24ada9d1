// How many OpenMP threads a repeated piece of work (an MPM step) should use, chosen by timing it.
//
// On a shared machine a second thread can make a step a hundred times slower: every parallel
// region ends in a barrier, and when another process holds the second core the barrier waits for
// a descheduled thread (docs/performance.md, "Threads under load"). The tuner therefore measures:
// every `period` calls it runs `trial` calls at one thread and `trial` at the most threads
// allowed, and keeps the count whose median call was faster until the next trial. While it runs
// more than one thread it watches its own calls: one call over four times the trial's
// one-thread median, or `trial` calls whose median is slower than that median, start a new trial
// at once (a load that arrives after a trial, or a trial that caught a lucky moment, costs one
// trial's calls, not a period's). A trial that finds one thread faster by a narrow margin is
// repeated after a sixteenth of the period (at least two trials' length): on a shared virtual
// machine the other core is now and then taken for a few seconds, and a verdict taken then should
// not hold for the whole period (docs/performance.md, "The thread tuner"). The results do not
// depend on the choice: every parallel path of the step sums in an order fixed by the mesh and the
// grid, not by the threads (tests Threads.*).
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace snapjump::parallel {

// Sets the OpenMP thread count for the regions that follow and restores the previous count when
// it goes out of scope.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(int threads);
  ~ScopedThreadCount();
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  int previous_;
};

// The process's current OpenMP thread count (what the next parallel region would use).
int max_threads();

class ThreadTuner {
 public:
  // max_threads <= 1: always one thread, never a trial.
  explicit ThreadTuner(int max_threads, int trial = 16, int period = 4000);
  // A tuner that never tries: every call runs at `threads`.
  static ThreadTuner fixed(int threads);
  // A step's tuner in this process: over the current OpenMP thread count, or fixed at it when
  // `tune` is false.
  static ThreadTuner for_process(bool tune);

  // Runs work() at next() threads, times it and records the time.
  template <typename Work>
  void run(Work&& work) {
    const auto start = std::chrono::steady_clock::now();
    {
      const ScopedThreadCount threads(current_);
      work();
    }
    record(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }

  // The thread count for the next call.
  [[nodiscard]] int next() const { return current_; }
  // The duration of the call just made with next() threads.
  void record(double seconds);

  [[nodiscard]] int max_threads() const { return max_; }
  // The count chosen by the last finished trial (max_threads() before the first).
  [[nodiscard]] int chosen() const { return chosen_; }
  [[nodiscard]] long trials() const { return trials_; }
  // How many trials the watch on a settled count above one started early.
  [[nodiscard]] long early_trials() const { return early_trials_; }
  // How many trials chose one thread by a close call (two threads less than 1.25 times slower,
  // no hopeless call): after such a verdict the next trial comes after a sixteenth of the period
  // (at least two trials' length), not the whole period.
  [[nodiscard]] long close_calls() const { return close_calls_; }

 private:
  enum class Phase { TrialOne, TrialMax, Settled };
  static double median(std::vector<double>& v);
  void start_trial();
  // A settled call at more than one thread: false when it calls for a new trial now.
  bool watch(double seconds);

  bool tune_ = true;
  int max_;
  int trial_;
  int period_;
  int settled_for_;  // calls from the last trial to the next
  Phase phase_ = Phase::Settled;
  int current_;
  int chosen_;
  long since_trial_ = 0;
  long trials_ = 0;
  long early_trials_ = 0;
  long close_calls_ = 0;
  double one_median_ = 0.0;
  std::vector<double> one_, many_, watched_;
};

}  // namespace snapjump::parallel
