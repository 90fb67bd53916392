// Threads sharing one checker: 4 threads check seeded random motions (the continuous motion
// check, with its last valid fraction), their end states and a few clearances on one shared
// ContinuousMotionChecker and DssChecker (our arm in its shelf scene), each in its own order,
// and every answer must equal the single-threaded one; the shared counters must add up to
// exactly four times the single-threaded counts; the same for the vector motion check's
// batches. Run under ThreadSanitizer by tools/sanitize.sh, where any data race in the checkers
// is a report.
#include <array>
#include <atomic>
#include <boost/test/unit_test.hpp>
#include <random>
#include <thread>
#include <vector>

#include "dss/checker/continuous_motion.h"
#include "dss/checker/discrete_motion.h"
#include "dss/checker/dss_checker.h"
#include "support/checker_fixtures.h"

namespace {

struct Motion {
  std::vector<double> q0, q1;
  // Single-threaded answers.
  bool clear = false;
  double last_valid = -1.0;
  dss::StateVerdict v0 = dss::StateVerdict::kFree, v1 = dss::StateVerdict::kFree;
  double clearance = -1.0;  // of q0, for every 8th motion
};

constexpr int kThreads = 4;

// kThreads threads, each through all n motions in its own order (a different start and
// stride), summing mismatches(i, t) for motion i: the total.
template <class Mismatches>
int inFourThreads(std::size_t n, Mismatches&& mismatches) {
  std::atomic<int> total{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      const std::size_t stride = std::array<std::size_t, kThreads>{1, 3, 7, 9}[t];
      for (std::size_t k = 0; k < n; ++k) total += mismatches((t * 40 + k * stride) % n);
    });
  for (auto& th : threads) th.join();
  return total.load();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(concurrent_motion)

BOOST_AUTO_TEST_CASE(four_threads_agree_with_one) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  const auto checker = std::make_shared<const dss::DssChecker>(setup.model);
  const dss::ContinuousMotionChecker cmc(checker);
  const dss::CollisionModel& m = *setup.model;

  // Long and short motions, so that both verdicts and several sub-motion depths occur.
  std::mt19937_64 rng(4242);
  std::vector<Motion> motions(160);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    Motion& mo = motions[i];
    mo.q0 = dss_test::randomGroupState(m, rng);
    const std::vector<double> far = dss_test::randomGroupState(m, rng);
    const double scale = std::array<double, 4>{1.0, 0.3, 0.1, 0.03}[i % 4];
    mo.q1 = mo.q0;
    for (int a : m.groupActive()) mo.q1[a] = mo.q0[a] + scale * (far[a] - mo.q0[a]);
  }
  const auto counters0 = checker->counters();
  const auto sub0 = cmc.subMotions(), units0 = cmc.unitTests();
  int clear = 0, free_starts = 0;
  for (std::size_t i = 0; i < motions.size(); ++i) {
    Motion& mo = motions[i];
    mo.clear = cmc.clear(mo.q0.data(), mo.q1.data(), &mo.last_valid);
    mo.v0 = checker->check(mo.q0.data());
    mo.v1 = checker->check(mo.q1.data());
    if (i % 8 == 0) mo.clearance = checker->clearance(mo.q0.data());
    clear += mo.clear;
    free_starts += mo.v0 == dss::StateVerdict::kFree;
  }
  const auto single = checker->counters() - counters0;
  const auto single_sub = cmc.subMotions() - sub0, single_units = cmc.unitTests() - units0;
  BOOST_TEST(clear > 10);
  BOOST_TEST(clear < int(motions.size()) - 10);
  BOOST_TEST(free_starts > 10);

  const auto counters1 = checker->counters();
  const auto sub1 = cmc.subMotions(), units1 = cmc.unitTests();
  const int mismatches = inFourThreads(motions.size(), [&](std::size_t i) {
    const Motion& mo = motions[i];
    double last = -1.0;
    int bad = cmc.clear(mo.q0.data(), mo.q1.data(), &last) != mo.clear;
    bad += !mo.clear && last != mo.last_valid;
    bad += checker->check(mo.q0.data()) != mo.v0;
    bad += checker->check(mo.q1.data()) != mo.v1;
    if (i % 8 == 0) bad += checker->clearance(mo.q0.data()) != mo.clearance;
    return bad;
  });
  BOOST_TEST(mismatches == 0);

  // Every thread did the single-threaded work once: the counters add up exactly.
  const auto multi = checker->counters() - counters1;
  BOOST_TEST(multi.checks == kThreads * single.checks);
  BOOST_TEST(multi.collisions == kThreads * single.collisions);
  BOOST_TEST(multi.invalid_input == kThreads * single.invalid_input);
  BOOST_TEST(multi.pair_tests == kThreads * single.pair_tests);
  BOOST_TEST(multi.cap_hits == kThreads * single.cap_hits);
  BOOST_TEST(cmc.subMotions() - sub1 == kThreads * single_sub);
  BOOST_TEST(cmc.unitTests() - units1 == kThreads * single_units);
  BOOST_TEST_MESSAGE("4 threads x " << motions.size() << " motions (" << clear << " clear), "
                                    << single_sub << " sub-motions and " << single.checks
                                    << " state checks each");
}

// The vector motion check's batches (StateChecker::freeStates) from four threads at once: the
// same verdicts, last valid fractions and proven lanes as one thread, the counters four times
// its own.
BOOST_AUTO_TEST_CASE(four_threads_share_the_batches, DSS_NEEDS_BATCHES) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  const auto checker = std::make_shared<const dss::DssChecker>(setup.model);
  const dss::DiscreteMotionChecker batched(checker, true);
  BOOST_REQUIRE(batched.batched());
  const dss::CollisionModel& m = *setup.model;
  std::mt19937_64 rng(777);
  std::vector<Motion> motions(160);
  std::vector<unsigned> proven(motions.size());
  const auto counters0 = checker->counters();
  int clear = 0;
  for (std::size_t i = 0; i < motions.size(); ++i) {
    Motion& mo = motions[i];
    mo.q0 = dss_test::randomGroupState(m, rng);
    const std::vector<double> far = dss_test::randomGroupState(m, rng);
    mo.q1 = mo.q0;
    for (int a : m.groupActive()) mo.q1[a] = mo.q0[a] + 0.2 * (far[a] - mo.q0[a]);
    mo.clear = batched.clear(mo.q0.data(), mo.q1.data(), 20, &mo.last_valid);
    const double* two[2] = {mo.q0.data(), mo.q1.data()};
    proven[i] = checker->freeStates(two, 2);
    clear += mo.clear;
  }
  const auto single = checker->counters() - counters0;
  BOOST_TEST(clear > 10);
  BOOST_TEST(clear < int(motions.size()) - 10);
  BOOST_TEST(single.batch_free > 0u);

  const auto counters1 = checker->counters();
  const int mismatches = inFourThreads(motions.size(), [&](std::size_t i) {
    const Motion& mo = motions[i];
    double last = -1.0;
    int bad = batched.clear(mo.q0.data(), mo.q1.data(), 20, &last) != mo.clear;
    bad += !mo.clear && last != mo.last_valid;
    const double* two[2] = {mo.q0.data(), mo.q1.data()};
    bad += checker->freeStates(two, 2) != proven[i];
    return bad;
  });
  BOOST_TEST(mismatches == 0);
  const auto multi = checker->counters() - counters1;
  BOOST_TEST(multi.checks == kThreads * single.checks);
  BOOST_TEST(multi.batch_free == kThreads * single.batch_free);
  BOOST_TEST(multi.collisions == kThreads * single.collisions);
}

BOOST_AUTO_TEST_SUITE_END()
