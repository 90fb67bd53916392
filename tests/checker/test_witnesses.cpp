// Witness planes (DssCheckerSettings::witnesses): a checker that tries each pair's last
// separating plane before its narrow phase answers exactly as one that does not, on the
// states of seeded random motions taken in order (where the planes decide most pairs) and on
// independent random states, for our arm in its shelf and for the Panda in a MotionBenchMaker
// scene; the narrow-phase counts agree too (a deciding plane counts as a test).
#include <boost/test/unit_test.hpp>
#include <random>

#include "dss/checker/dss_checker.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"

namespace {

void compareWithAndWithout(const std::shared_ptr<const dss::CollisionModel>& model,
                           std::uint64_t seed) {
  dss::DssCheckerSettings on, off;
  off.witnesses = false;
  const dss::DssChecker with(model, on), without(model, off);
  const dss::CollisionModel& m = *model;
  std::mt19937_64 rng(seed);
  std::size_t states = 0, colliding = 0, differ = 0;
  std::vector<double> q(m.held().size());
  for (int k = 0; k < 400; ++k) {
    const std::vector<double> q0 = dss_test::randomGroupState(m, rng);
    const std::vector<double> far = dss_test::randomGroupState(m, rng);
    // Short motions in order (consecutive states close), and every 4th an independent jump.
    const double scale = k % 4 == 3 ? 1.0 : 0.1;
    for (int i = 0; i <= 40; ++i) {
      const double t = scale * i / 40.0;
      for (std::size_t a = 0; a < q.size(); ++a) q[a] = q0[a] + t * (far[a] - q0[a]);
      const dss::StateVerdict v1 = with.check(q.data()), v2 = without.check(q.data());
      ++states;
      differ += v1 != v2;
      colliding += v2 != dss::StateVerdict::kFree;
    }
  }
  BOOST_TEST(differ == 0u);
  BOOST_TEST(colliding > states / 20);
  BOOST_TEST(colliding < states - states / 20);
  BOOST_TEST(with.counters().pair_tests == without.counters().pair_tests);
  BOOST_TEST(with.counters().collisions == without.counters().collisions);
  BOOST_TEST_MESSAGE("witnesses: " << states << " states (" << colliding << " colliding), "
                                   << differ << " answers differ; " << with.counters().pair_tests
                                   << " narrow-phase tests");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(witnesses)

BOOST_AUTO_TEST_CASE(same_answers_on_our_arm) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  compareWithAndWithout(dss_test::shelfSetup(robot).model, 5);
}

BOOST_AUTO_TEST_CASE(same_answers_on_the_panda, DSS_NEEDS_SHARED) {
  const auto robot =
      dss::loadRobot(dss_test::kPandaDir + "/panda.urdf", dss_test::kPandaDir + "/panda.srdf");
  const auto req =
      dss::loadPlanRequestYaml(dss_test::kMbmPanda + "/bookshelf_tall/request0001.yaml");
  const dss::ModelSetup p =
      dss::setupModel(robot, dss::loadScene(dss_test::kMbmPanda + "/bookshelf_tall/scene0001.yaml"),
                      req.group_name, req.startState());
  compareWithAndWithout(p.model, 6);
}

BOOST_AUTO_TEST_SUITE_END()
