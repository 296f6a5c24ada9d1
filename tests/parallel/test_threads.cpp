// The parallel paths of a step give the same bits at any thread count (make test runs one thread
// per test, so these tests set the counts themselves), and the thread tuner keeps the faster count.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numbers>
#include <tuple>
#include <vector>

#include "fem/body.hpp"
#include "fem/explicit.hpp"
#include "hybrid/body_forces.hpp"
#include "mesh/cap_mesher.hpp"
#include "mpm/stepper.hpp"
#include "parallel/threads.hpp"

namespace snapjump {
namespace {

using parallel::ThreadTuner;

// Records `calls` calls of `seconds` each, checking that each was to run at `threads`.
void feed(ThreadTuner& t, int threads, double seconds, int calls) {
  for (int k = 0; k < calls; ++k) {
    ASSERT_EQ(t.next(), threads) << "call " << k;
    t.record(seconds);
  }
}

TEST(Threads, TunerKeepsTheFasterCount) {
  ThreadTuner t(2, 4, 20);
  // A trial: four calls at one thread, then four at two.
  feed(t, 1, 1.0, 4);
  feed(t, 2, 0.6, 4);
  EXPECT_EQ(t.chosen(), 2);
  EXPECT_EQ(t.trials(), 1);
  // Settled for `period` calls, then the next trial; now two threads are the slower.
  feed(t, 2, 0.6, 20);
  feed(t, 1, 1.0, 4);
  feed(t, 2, 1.5, 4);
  EXPECT_EQ(t.chosen(), 1);
  EXPECT_EQ(t.next(), 1);
  EXPECT_EQ(t.trials(), 2);
}

TEST(Threads, AFixedTunerNeverTries) {
  auto t = ThreadTuner::fixed(3);
  feed(t, 3, 1.0, 10);
  EXPECT_EQ(t.chosen(), 3);
  EXPECT_EQ(t.trials(), 0);
}

// A machine whose other core is busy: the first call at two threads takes 70 times as long, and
// the trial ends there rather than spending three more such calls.
TEST(Threads, TunerLeavesAHopelessTrialAtOnce) {
  ThreadTuner t(2, 4, 100);
  for (int k = 0; k < 4; ++k) t.record(1.0);
  ASSERT_EQ(t.next(), 2);
  t.record(70.0);
  EXPECT_EQ(t.next(), 1);
  EXPECT_EQ(t.chosen(), 1);
  EXPECT_EQ(t.close_calls(), 0);  // a hopeless call is no close call: the whole period passes
}

// A first trial (four calls each) in which two threads are the faster: the tuner settles on two.
void settle_on_two(ThreadTuner& t) {
  feed(t, 1, 1.0, 4);
  feed(t, 2, 0.6, 4);
  ASSERT_EQ(t.chosen(), 2);
}

// The other core becomes busy after a trial chose two threads: the tuner's watch of its own
// calls starts a new trial within one trial's length, not after the whole period.
TEST(Threads, TunerRetriesWhenTheChosenCountSlowsDown) {
  ThreadTuner t(2, 4, 1000);
  settle_on_two(t);
  // Slower than one thread was, but never hopeless: four such calls, then a trial.
  feed(t, 2, 1.5, 4);
  EXPECT_EQ(t.early_trials(), 1);
  feed(t, 1, 1.0, 4);
  feed(t, 2, 1.5, 4);
  EXPECT_EQ(t.chosen(), 1);
  // Settled at one thread there is nothing to watch: slow calls wait for the period.
  feed(t, 1, 9.0, 20);
  EXPECT_EQ(t.early_trials(), 1);
  EXPECT_EQ(t.trials(), 2);
}

// One settled call at two threads that takes more than four one-thread calls starts a trial at
// once; calls as fast as the trial's keep the count.
TEST(Threads, TunerRetriesAtOnceAfterAHopelessCall) {
  ThreadTuner t(2, 4, 1000);
  settle_on_two(t);
  feed(t, 2, 0.7, 40);
  EXPECT_EQ(t.early_trials(), 0);
  feed(t, 2, 50.0, 1);
  EXPECT_EQ(t.early_trials(), 1);
  EXPECT_EQ(t.next(), 1);
}

// A trial in which two threads are barely slower than one (the other core briefly taken): one
// thread is chosen, and the next trial comes after a sixteenth of the period (20 calls here)
// instead of the whole period; it finds two threads faster again. A clear verdict (two threads
// 1.5 times slower) waits the whole period.
TEST(Threads, TunerTriesAgainSoonAfterACloseCall) {
  ThreadTuner t(2, 4, 320);
  feed(t, 1, 1.0, 4);
  feed(t, 2, 1.1, 4);
  EXPECT_EQ(t.chosen(), 1);
  EXPECT_EQ(t.close_calls(), 1);
  feed(t, 1, 1.0, 20);  // 320 / 16 calls, then the trial
  feed(t, 1, 1.0, 4);
  feed(t, 2, 0.6, 4);
  EXPECT_EQ(t.chosen(), 2);
  EXPECT_EQ(t.trials(), 2);
  // After a clear verdict the whole period passes before the next trial.
  feed(t, 2, 0.6, 320);
  feed(t, 1, 1.0, 4);
  feed(t, 2, 1.5, 4);
  EXPECT_EQ(t.chosen(), 1);
  EXPECT_EQ(t.close_calls(), 1);
  feed(t, 1, 1.0, 320);
  feed(t, 1, 1.0, 4);  // the next trial's one-thread calls
  EXPECT_EQ(t.next(), 2);
}

// The least wait after a close call is two trials' length (here the period's sixteenth is less).
TEST(Threads, TunerWaitsAtLeastTwoTrialsAfterACloseCall) {
  ThreadTuner t(2, 4, 64);
  feed(t, 1, 1.0, 4);
  feed(t, 2, 1.1, 4);
  ASSERT_EQ(t.close_calls(), 1);
  feed(t, 1, 1.0, 8);
  feed(t, 1, 1.0, 4);
  EXPECT_EQ(t.next(), 2);
}

TEST(Threads, OneThreadAllowedMeansNoTrial) {
  ThreadTuner t(1);
  feed(t, 1, 1.0, 10);
  EXPECT_EQ(t.trials(), 0);
  EXPECT_THROW(ThreadTuner(2, 0, 10), std::invalid_argument);
  EXPECT_THROW(ThreadTuner(2, 8, 10), std::invalid_argument);
}

TEST(Threads, ScopedCountIsRestored) {
  const int before = omp_get_max_threads();
  {
    const parallel::ScopedThreadCount c(3);
    EXPECT_EQ(omp_get_max_threads(), 3);
  }
  EXPECT_EQ(omp_get_max_threads(), before);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

fem::Body small_cap(fem::BulkRule bulk = fem::BulkRule::full) {
  return fem::Body(mesh::make_cap_mesh({.R = 0.030,
                                        .h = 0.002,
                                        .phi = 80.0 * std::numbers::pi / 180,
                                        .element_size = 0.005,
                                        .layers = 2}),
                   fem::Material::from_young(1.2e6, 0.45, 1160.0), bulk);
}

struct StepState {
  mpm::Particles p;
  double container_z = 0.0, plate_force = 0.0;
  std::vector<std::array<std::int64_t, 3>> loaded;  // the plate's loaded nodes after the last step
  bool wide = false;                                // the transfers' AVX2 version ran
};

// A cap under pressure, clamped to a container, moving down onto the frictional plate: every
// stage of the MPM step (forces, transfers, clamp, plate) runs, for 150 steps. With restart_at > 0
// the stepper is made again from its particles after that many steps (as a resumed run is), so
// its grid starts afresh instead of keeping its blocks.
StepState run_steps(const fem::Body& shell, int threads, bool tune, int restart_at = 0,
                    std::vector<long>* blocks_made = nullptr, bool wide = true) {
  const parallel::ScopedThreadCount count(threads);
  hybrid::BodyForces forces(shell, 9.81, [](double) { return 2000.0; });
  auto particles = hybrid::particles_of(shell);
  const double zmin = *std::min_element(particles.x.z.begin(), particles.x.z.end());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.x.z[i] += 0.0003 - zmin;
    particles.v.z[i] = -0.5;
  }
  mpm::StepperOptions o{shell.stable_time_step(0.3), 0.001, 0.5};
  o.tune_threads = tune;
  o.wide_vectors = wide;
  mpm::RigidBody container;
  container.mass = 0.05;
  container.vz = -0.5;
  container.applied_force = -2.0;
  const mpm::PlateRule* plate = nullptr;
  const auto make = [&](mpm::Particles p) {
    auto s = std::make_unique<mpm::Stepper>(std::move(p), forces, o);
    s->add_rule(std::make_unique<mpm::ClampRule>(container));
    plate = &dynamic_cast<mpm::PlateRule&>(s->add_rule(std::make_unique<mpm::PlateRule>(0.5)));
    s->add_rigid_body(container);
    return s;
  };
  auto s = make(std::move(particles));
  double plate_force = 0.0;
  for (int k = 0; k < 150; ++k) {
    if (k > 0 && k == restart_at) {
      const double t = s->time();
      s = make(s->particles());
      s->restore_clock(t, k);
    }
    s->step();
    plate_force += plate->force();
    if (blocks_made != nullptr) blocks_made->push_back(s->grid().full_rebuilds());
  }
  return {s->particles(), container.z, plate_force, plate->loaded_nodes(), s->wide_vectors()};
}

TEST(Threads, MpmStepIsTheSameAtOneTwoFourAndEightThreads) {
  const auto shell = small_cap();
  const auto one = run_steps(shell, 1, false);
  ASSERT_GT(one.plate_force, 0.0) << "the plate never pushed: the test would not cover it";
  // (Eight threads on two cores: the scatter's cubes wait on each other in more orders.)
  for (const int threads : {2, 4, 8}) {
    const auto many = run_steps(shell, threads, false);
    EXPECT_TRUE(same_bits(one.p.x.x, many.p.x.x) && same_bits(one.p.x.y, many.p.x.y) &&
                same_bits(one.p.x.z, many.p.x.z))
        << threads << " threads";
    EXPECT_TRUE(same_bits(one.p.v.z, many.p.v.z) && same_bits(one.p.C, many.p.C))
        << threads << " threads";
    EXPECT_EQ(std::memcmp(&one.container_z, &many.container_z, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&one.plate_force, &many.plate_force, sizeof(double)), 0);
    EXPECT_EQ(one.loaded, many.loaded) << threads << " threads";
  }
  ASSERT_FALSE(one.loaded.empty());
  EXPECT_TRUE(std::is_sorted(one.loaded.begin(), one.loaded.end()));
  // With the tuner switching between one and two threads on its own.
  const auto tuned = run_steps(shell, 2, true);
  EXPECT_TRUE(same_bits(one.p.x.z, tuned.p.x.z) && same_bits(one.p.C, tuned.p.C));
}

// The transfers' two versions (the baseline processor's and AVX2's, stepper.cpp) give the same
// bits, at one and two threads.
TEST(Threads, TheTransfersBaselineAndAvx2VersionsGiveTheSameBits) {
  const auto shell = small_cap();
  for (const int threads : {1, 2}) {
    const auto wide = run_steps(shell, threads, false, 0, nullptr, true);
    if (!wide.wide) GTEST_SKIP() << "this processor (or build) has no AVX2 version to compare";
    const auto base = run_steps(shell, threads, false, 0, nullptr, false);
    ASSERT_FALSE(base.wide);
    EXPECT_TRUE(same_bits(base.p.x.x, wide.p.x.x) && same_bits(base.p.x.y, wide.p.x.y) &&
                same_bits(base.p.x.z, wide.p.x.z) && same_bits(base.p.v.x, wide.p.v.x) &&
                same_bits(base.p.v.y, wide.p.v.y) && same_bits(base.p.v.z, wide.p.v.z) &&
                same_bits(base.p.C, wide.p.C))
        << threads << " threads";
    EXPECT_EQ(std::memcmp(&base.plate_force, &wide.plate_force, sizeof(double)), 0);
  }
}

// The grid keeps its blocks while the particles stay within them, and starts afresh in a new
// stepper (a resumed run): both sum in the same order, so both give the same bits.
TEST(Threads, AStepperMadeAgainFromItsParticlesStepsOnAsTheFirstOne) {
  const auto shell = small_cap();
  std::vector<long> made;  // blocks made so far, after each step
  const auto straight = run_steps(shell, 1, false, 0, &made);
  ASSERT_EQ(made.size(), 150u);
  // At the restart the straight run's grid was kept while the restarted one is new.
  ASSERT_EQ(made[75], made[74]) << "the straight run made its blocks again at the restart: the "
                                   "test would not compare a kept grid with a fresh one";
  ASSERT_LT(made.back(), 50) << "the grid was rarely kept";
  for (const int threads : {1, 2}) {
    const auto restarted = run_steps(shell, threads, false, 75);
    EXPECT_TRUE(same_bits(straight.p.x.z, restarted.p.x.z) &&
                same_bits(straight.p.C, restarted.p.C) &&
                same_bits(straight.p.v.x, restarted.p.v.x))
        << threads << " threads";
    EXPECT_EQ(std::memcmp(&straight.plate_force, &restarted.plate_force, sizeof(double)), 0);
  }
}

// 100 explicit steps of a cap under 3 kPa: the positions, and the internal forces there.
std::pair<mesh::Points, mesh::Points> loaded_explicit_steps(const fem::Body& shell) {
  fem::ExplicitOptions o;
  o.pressure = [](double) { return 3000.0; };
  o.tune_threads = false;
  fem::ExplicitDriver d(shell, o);
  for (int k = 0; k < 100; ++k) d.step();
  mesh::Points f;
  shell.internal_forces(d.positions(), f);
  return {d.positions(), f};
}

// The elements' forces in their two versions (the baseline processor's and AVX2's, body.cpp)
// give the same bits: along 100 explicit steps of a loaded cap, for both bulk rules.
TEST(Threads, TheElementForcesBaselineAndAvx2VersionsGiveTheSameBits) {
  for (const auto bulk : {fem::BulkRule::full, fem::BulkRule::centroid}) {
    SCOPED_TRACE(bulk == fem::BulkRule::full ? "bulk at four points" : "bulk at the centroid");
    auto shell = small_cap(bulk);
    if (!shell.wide_vectors()) GTEST_SKIP() << "this processor (or build) has no AVX2 version";
    const auto run = [&](bool wide) {
      shell.set_wide_vectors(wide);
      EXPECT_EQ(shell.wide_vectors(), wide);
      return loaded_explicit_steps(shell);
    };
    const auto [xw, fw] = run(true);
    const auto [xb, fb] = run(false);
    EXPECT_TRUE(same_bits(xw.x, xb.x) && same_bits(xw.y, xb.y) && same_bits(xw.z, xb.z));
    EXPECT_TRUE(same_bits(fw.x, fb.x) && same_bits(fw.y, fb.y) && same_bits(fw.z, fb.z));
  }
}

TEST(Threads, InternalForcesPressureVolumeAndExplicitStepsAreTheSameAtOneAndFourThreads) {
  for (const auto bulk : {fem::BulkRule::full, fem::BulkRule::centroid}) {
    SCOPED_TRACE(bulk == fem::BulkRule::full ? "bulk at four points" : "bulk at the centroid");
    const auto shell = small_cap(bulk);
    const auto run = [&](int threads) {
      const parallel::ScopedThreadCount count(threads);
      const auto [x, f] = loaded_explicit_steps(shell);
      // The pressure load and the cavity volume at the deformed positions (both in parallel
      // over the faces).
      mesh::Points g;
      shell.cavity_volume_gradient(x, g);
      return std::tuple{x, f, g, std::vector{shell.cavity_volume(x)}};
    };
    const auto [x1, f1, g1, v1] = run(1);
    const auto [x4, f4, g4, v4] = run(4);
    EXPECT_TRUE(same_bits(x1.x, x4.x) && same_bits(x1.y, x4.y) && same_bits(x1.z, x4.z));
    EXPECT_TRUE(same_bits(f1.x, f4.x) && same_bits(f1.y, f4.y) && same_bits(f1.z, f4.z));
    EXPECT_TRUE(same_bits(g1.x, g4.x) && same_bits(g1.y, g4.y) && same_bits(g1.z, g4.z));
    EXPECT_TRUE(same_bits(v1, v4));
  }
}

}  // namespace
}  // namespace snapjump
