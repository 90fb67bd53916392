// The OMPL validity checker (validity_checker.h), a thin adapter on a state checker: a seeded
// plan on our shelf scene checked state by state under DSS and fcl-hull; its answers are the
// state checker's on the mapped joint values; NaN, Inf and out-of-bounds states are invalid and
// refused before the checker is asked, yet counted by the adapter's counters(); clearance()
// is the DSS checker's (a bounded approximation), and none for FCL.
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "dss/checker/contacts.h"
#include "dss/checker/dss_checker.h"
#include "dss/planning/planning_problem.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace ob = ompl::base;

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";

dss::Problem shelfProblem(const dss::LoadedRobot& r) {
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  return dss::makeProblem(r, dss::loadScene(kArm + "/scenes/shelf.yaml"), req.group_name,
                          req.startState());
}

// OMPL's seed can be set once per process, before any sampling: a global fixture does it.
struct SeedOmpl {
  SeedOmpl() {
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    ompl::RNG::setSeed(7);
  }
};

// Group values uniform within the space's bounds, from our own seeded generator.
std::vector<double> randomGroupValues(const dss::Problem& p, std::mt19937_64& rng) {
  std::vector<double> g(p.map->dimension());
  for (std::size_t i = 0; i < g.size(); ++i)
    g[i] = std::uniform_real_distribution<double>(p.map->lower(i), p.map->upper(i))(rng);
  return g;
}

}  // namespace

BOOST_TEST_GLOBAL_FIXTURE(SeedOmpl);

BOOST_AUTO_TEST_SUITE(validity_checker)

BOOST_AUTO_TEST_CASE(shelf_plan_is_valid_under_dss_and_fcl_hull) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  dss::Problem p = shelfProblem(r);
  BOOST_TEST_MESSAGE(p.model->summary());
  auto dss_checker = dss::makeValidityChecker(p, {"dss"});
  auto fcl_checker = dss::makeValidityChecker(p, {"fcl-hull"});
  ompl::geometric::SimpleSetup ss(p.si);
  ss.setStateValidityChecker(dss_checker);
  ss.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(p.si));
  ob::ScopedState<> start(p.si->getStateSpace()), goal(p.si->getStateSpace());
  const auto g0 = p.map->groupValues(req.startState());
  std::map<std::string, double> goal_map;
  for (const auto& jc : req.goals.at(0).joint_constraints) goal_map[jc.joint_name] = jc.position;
  const auto g1 = p.map->groupValues(goal_map);
  p.map->fromGroupValues(g0.data(), start.get());
  p.map->fromGroupValues(g1.data(), goal.get());
  BOOST_TEST(dss_checker->isValid(start.get()));
  BOOST_TEST(dss_checker->isValid(goal.get()));
  ss.setStartAndGoalStates(start, goal);
  BOOST_REQUIRE(ss.solve(10.0) == ob::PlannerStatus::EXACT_SOLUTION);
  auto path = ss.getSolutionPath();
  path.interpolate();  // at the validity-checking resolution the motion validator used
  int invalid_dss = 0, invalid_fcl = 0;
  for (auto* s : path.getStates()) {
    invalid_dss += !dss_checker->isValid(s);
    invalid_fcl += !fcl_checker->isValid(s);
  }
  BOOST_TEST(path.getStateCount() >= 20u);
  BOOST_TEST(invalid_dss == 0);
  BOOST_TEST(invalid_fcl == 0);
  // The straight line start -> goal passes through the shelf: the problem is not trivial.
  BOOST_TEST(!p.si->checkMotion(start.get(), goal.get()));
}

// isValid(state) is the state checker's verdict on the state's joint values (held joints at
// their held values), and the adapter's counters are the checker's when every state is in
// bounds.
BOOST_AUTO_TEST_CASE(answers_are_the_state_checkers) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const dss::Problem p = shelfProblem(r);
  for (const char* name : {"dss", "fcl-hull"}) {
    auto c = dss::makeValidityChecker(p, {name});
    BOOST_TEST(c->checker().name() == name);
    std::mt19937_64 rng(3);
    ob::ScopedState<> s(p.si->getStateSpace());
    std::vector<double> q(r.model->numActiveJoints());
    int valid = 0;
    const int n = 500;
    for (int k = 0; k < n; ++k) {
      const auto g = randomGroupValues(p, rng);
      p.map->fromGroupValues(g.data(), s.get());
      std::vector<double> expected = p.model->held();
      for (std::size_t i = 0; i < g.size(); ++i) expected[p.map->groupActive()[i]] = g[i];
      BOOST_REQUIRE(p.map->toJoints(s.get(), q.data()));
      BOOST_TEST_REQUIRE((q == expected));
      const bool v = c->isValid(s.get());
      BOOST_TEST(v == (c->checker().check(q.data()) == dss::StateVerdict::kFree),
                 name << " state " << k);
      valid += v;
    }
    BOOST_TEST(valid > 0);
    BOOST_TEST(valid < n);
    const dss::CheckerCounters a = c->counters(), b = c->checker().counters();
    BOOST_TEST(a.checks == 2u * n);
    BOOST_TEST(a.checks == b.checks);
    BOOST_TEST(a.invalid_input == 0u);
    BOOST_TEST(a.collisions == b.collisions);
    BOOST_TEST(a.collisions == 2u * (n - valid));
  }
}

BOOST_AUTO_TEST_CASE(nan_inf_and_out_of_bounds_states_are_invalid) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  dss::Problem p = shelfProblem(r);
  for (const char* name : {"dss", "fcl-hull"}) {
    auto c = dss::makeValidityChecker(p, {name});
    ob::ScopedState<> s(p.si->getStateSpace());
    auto g = p.map->groupValues({});
    for (std::size_t i = 0; i < g.size(); ++i) g[i] = 0.5 * (p.map->lower(i) + p.map->upper(i));
    p.map->fromGroupValues(g.data(), s.get());
    const bool base = c->isValid(s.get());
    (void)base;
    for (double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity(), 1e6}) {
      auto h = g;
      h[3] = bad;
      p.map->fromGroupValues(h.data(), s.get());
      BOOST_TEST(!c->isValid(s.get()), name << " value " << bad);
    }
    BOOST_TEST(c->counters().invalid_input == 4u);
  }
}

// States outside the space's bounds are refused by the adapter before the state checker is
// asked: the adapter's counters() count them (as checks and as invalid input), the checker's
// own counters do not see them.
BOOST_AUTO_TEST_CASE(counters_count_states_refused_by_the_bounds) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const dss::Problem p = shelfProblem(r);
  for (const char* name : {"dss", "fcl-hull"}) {
    auto c = dss::makeValidityChecker(p, {name});
    ob::ScopedState<> s(p.si->getStateSpace());
    std::mt19937_64 rng(5);
    // In bounds first: both see the same.
    for (int k = 0; k < 20; ++k) {
      const auto g = randomGroupValues(p, rng);
      p.map->fromGroupValues(g.data(), s.get());
      (void)c->isValid(s.get());
    }
    const dss::CheckerCounters adapter0 = c->counters(), checker0 = c->checker().counters();
    BOOST_TEST(adapter0.checks == 20u);
    BOOST_TEST(checker0.checks == 20u);
    BOOST_TEST(adapter0.invalid_input == 0u);
    // Out of bounds: each group joint beyond each limit (one ulp, and far), NaN, +-Inf.
    const auto mid = randomGroupValues(p, rng);
    std::size_t refused = 0;
    for (std::size_t i = 0; i < mid.size(); ++i)
      for (double bad :
           {std::nextafter(p.map->upper(i), 1e300), std::nextafter(p.map->lower(i), -1e300),
            p.map->upper(i) + 1.0, p.map->lower(i) - 1.0, std::numeric_limits<double>::quiet_NaN(),
            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
        auto g = mid;
        g[i] = bad;
        p.map->fromGroupValues(g.data(), s.get());
        BOOST_TEST(!c->isValid(s.get()), name << ": joint " << i << " at " << bad);
        ++refused;
      }
    const dss::CheckerCounters adapter = c->counters() - adapter0,
                               checker = c->checker().counters() - checker0;
    BOOST_TEST(adapter.checks == refused);
    BOOST_TEST(adapter.invalid_input == refused);
    BOOST_TEST(adapter.collisions == 0u);
    BOOST_TEST(adapter.pair_tests == 0u);
    BOOST_TEST(checker.checks == 0u);  // never asked
    BOOST_TEST(checker.invalid_input == 0u);
  }
}

// clearance(state): with the DSS checker, its clearance() of the state's joint values (a bounded
// approximation, 0 for an invalid state); with FCL, none.
BOOST_AUTO_TEST_CASE(clearance_is_the_dss_checkers) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const dss::Problem p = shelfProblem(r);
  auto c = dss::makeValidityChecker(p, {"dss"});
  BOOST_TEST(c->getSpecs().clearanceComputationType ==
             ob::StateValidityCheckerSpecs::BOUNDED_APPROXIMATE);
  const auto* dss_checker = dynamic_cast<const dss::DssChecker*>(&c->checker());
  BOOST_REQUIRE(dss_checker);
  auto fcl = dss::makeValidityChecker(p, {"fcl-hull"});
  BOOST_TEST(fcl->getSpecs().clearanceComputationType == ob::StateValidityCheckerSpecs::NONE);
  std::mt19937_64 rng(9);
  ob::ScopedState<> s(p.si->getStateSpace());
  std::vector<double> q(r.model->numActiveJoints());
  int positive = 0;
  for (int k = 0; k < 100; ++k) {
    const auto g = randomGroupValues(p, rng);
    p.map->fromGroupValues(g.data(), s.get());
    BOOST_REQUIRE(p.map->toJoints(s.get(), q.data()));
    const double expected = dss_checker->clearance(q.data());
    BOOST_TEST(c->clearance(s.get()) == expected);
    if (!c->isValid(s.get())) BOOST_TEST(c->clearance(s.get()) == 0.0);
    positive += expected > 0.0;
  }
  BOOST_TEST(positive > 0);
  auto g = randomGroupValues(p, rng);
  g[0] = std::numeric_limits<double>::quiet_NaN();
  p.map->fromGroupValues(g.data(), s.get());
  BOOST_TEST(c->clearance(s.get()) == 0.0);
}

// contacts(): the DSS checker's colliding pairs at the mapped joint values, empty exactly for
// the states isValid() accepts; none with FCL or for a state outside the bounds.
BOOST_AUTO_TEST_CASE(contacts_are_the_dss_checkers) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const dss::Problem p = shelfProblem(r);
  auto c = dss::makeValidityChecker(p, {"dss"});
  auto fcl = dss::makeValidityChecker(p, {"fcl-hull"});
  const auto* dss_checker = dynamic_cast<const dss::DssChecker*>(&c->checker());
  BOOST_REQUIRE(dss_checker);
  std::mt19937_64 rng(21);
  ob::ScopedState<> s(p.si->getStateSpace());
  std::vector<double> q(r.model->numActiveJoints());
  int colliding = 0;
  for (int k = 0; k < 300; ++k) {
    const auto g = randomGroupValues(p, rng);
    p.map->fromGroupValues(g.data(), s.get());
    BOOST_REQUIRE(p.map->toJoints(s.get(), q.data()));
    const auto got = c->contacts(s.get());
    BOOST_REQUIRE(got.has_value());
    BOOST_TEST(got->empty() == c->isValid(s.get()));
    const auto expected = dss::contactsAt(*dss_checker, q.data());
    BOOST_REQUIRE(expected.has_value());
    BOOST_TEST(got->size() == expected->size());
    colliding += !got->empty();
    BOOST_TEST(!fcl->contacts(s.get()).has_value());
  }
  BOOST_TEST(colliding > 0);
  auto g = randomGroupValues(p, rng);
  g[0] = std::numeric_limits<double>::quiet_NaN();
  p.map->fromGroupValues(g.data(), s.get());
  BOOST_TEST(!c->contacts(s.get()).has_value());
}

BOOST_AUTO_TEST_SUITE_END()
