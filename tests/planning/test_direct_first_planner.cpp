// DirectFirstPlanner on our arm in its shelf scene: a goal the start sees is reached by the
// straight motion alone (the wrapped planner never runs); a goal it does not see goes to the
// wrapped planner, which then plans exactly as it does alone (same seed: the same path, and the
// same checks plus the attempt's); an invalid start and a goal region that lists no states go
// to the wrapped planner untried.
#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "dss/planning/direct_first_planner.h"
#include "dss/planning/discrete_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/planning/validity_checker.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

struct Shelf {
  Shelf() {
    const std::string arm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
    robot = dss::loadRobot(arm + "/dss_arm7.urdf", arm + "/dss_arm7.srdf");
    req = dss::loadPlanRequestYaml(arm + "/scenes/shelf_request.yaml");
    scene = dss::loadScene(arm + "/scenes/shelf.yaml");
  }
  dss::LoadedRobot robot;
  dss::PlanRequest req;
  dss::Scene scene;
};

// One problem on the shelf: its model, checker and validator, and the request's start and goal
// as group values.
struct Setup {
  explicit Setup(const Shelf& shelf)
      : p(dss::makeProblem(shelf.robot, shelf.scene, shelf.req.group_name, shelf.req.startState())),
        checker(dss::makeValidityChecker(p, {"dss"})),
        ss(p.si) {
    ss.setStateValidityChecker(checker);
    p.si->setMotionValidator(dss::makeDiscreteMotionValidator(p, *checker));
    p.si->setup();  // the space's resolution, which the motion checks below need
    start = p.map->groupValues(shelf.req.startState());
    std::map<std::string, double> by_name;
    for (const dss::JointConstraint& c : shelf.req.goals.front().joint_constraints)
      by_name[c.joint_name] = c.position;
    goal = p.map->groupValues(by_name);
  }
  ob::ScopedState<> state(const std::vector<double>& g) const {
    ob::ScopedState<> s(p.si->getStateSpace());
    p.map->fromGroupValues(g.data(), s.get());
    return s;
  }
  std::vector<std::vector<double>> path() const {
    std::vector<std::vector<double>> out;
    for (auto* s : ss.getSolutionPath().getStates()) {
      std::vector<double> g(p.map->dimension());
      p.map->toGroupValues(s, g.data());
      out.push_back(g);
    }
    return out;
  }
  dss::Problem p;
  std::shared_ptr<dss::ValidityChecker> checker;
  og::SimpleSetup ss;
  std::vector<double> start, goal;
};

std::size_t plannerVertices(const ob::Planner& planner) {
  ob::PlannerData data(planner.getSpaceInformation());
  planner.getPlannerData(data);
  return data.numVertices();
}

// A goal region around one state that lists no states (only samples them).
class BallGoal : public ob::GoalSampleableRegion {
 public:
  BallGoal(const ob::SpaceInformationPtr& si, const ob::State* center)
      : ob::GoalSampleableRegion(si), center_(si->cloneState(center)) {
    setThreshold(1e-9);
  }
  ~BallGoal() override { si_->freeState(center_); }
  double distanceGoal(const ob::State* s) const override { return si_->distance(s, center_); }
  void sampleGoal(ob::State* s) const override { si_->copyState(s, center_); }
  unsigned maxSampleCount() const override { return 1; }

 private:
  ob::State* center_;
};

// Goals a little way from the start (normal steps of `sigma` at every joint), kept where the
// goal is valid and the straight motion to it free under the validator: up to `count` of them
// from 40 draws.
std::vector<std::vector<double>> goalsInSight(const Setup& s, std::uint64_t seed, double sigma,
                                              int count) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, sigma);
  std::vector<std::vector<double>> goals;
  for (int k = 0; k < 40 && int(goals.size()) < count; ++k) {
    std::vector<double> g = s.start;
    for (double& v : g) v += n(rng);
    const auto a = s.state(s.start), b = s.state(g);
    if (s.p.si->satisfiesBounds(b.get()) && s.p.si->isValid(b.get()) &&
        s.p.si->checkMotion(a.get(), b.get()))
      goals.push_back(g);
  }
  return goals;
}

// A limit of ten seconds from the call (a termination condition fixes its deadline when made).
ob::PlannerTerminationCondition tenSeconds() { return ob::timedPlannerTerminationCondition(10.0); }

}  // namespace

BOOST_AUTO_TEST_SUITE(direct_first_planner)

BOOST_AUTO_TEST_CASE(a_goal_in_sight_is_reached_by_the_straight_motion_alone) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const Shelf shelf;
  Setup s(shelf);
  // Goals in sight of the start: the planner must answer with exactly the straight motion.
  const auto goals = goalsInSight(s, 5, 0.15, 8);
  BOOST_CHECK_GE(goals.size(), 4u);
  for (const std::vector<double>& g : goals) {
    const auto a = s.state(s.start), b = s.state(g);
    auto inner = std::make_shared<og::RRTConnect>(s.p.si);
    auto direct = std::make_shared<dss::DirectFirstPlanner>(inner);
    s.ss.setPlanner(direct);
    s.ss.setStartAndGoalStates(a, b);
    BOOST_REQUIRE(s.ss.solve(tenSeconds()) == ob::PlannerStatus::EXACT_SOLUTION);
    BOOST_CHECK(direct->lastWasDirect());
    BOOST_CHECK_EQUAL(direct->getName(), "RRTConnect+direct");
    BOOST_CHECK_EQUAL(plannerVertices(*inner), 0u);  // the wrapped planner never ran
    const auto path = s.path();
    BOOST_REQUIRE_EQUAL(path.size(), 2u);
    BOOST_CHECK(path[0] == s.start);
    BOOST_CHECK(path[1] == g);
    BOOST_CHECK(s.ss.getSolutionPath().check());
  }
}

BOOST_AUTO_TEST_CASE(a_goal_out_of_sight_is_planned_as_the_wrapped_planner_plans_it) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const Shelf shelf;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    Setup plain(shelf), wrapped(shelf);
    // A valid goal drawn within the joint limits whose straight motion from the start collides.
    std::mt19937_64 rng(seed);
    const auto& bounds = plain.p.si->getStateSpace()->as<ob::RealVectorStateSpace>()->getBounds();
    bool found = false;
    for (int k = 0; k < 1000 && !found; ++k) {
      for (std::size_t j = 0; j < plain.goal.size(); ++j)
        plain.goal[j] = std::uniform_real_distribution<double>(bounds.low[j], bounds.high[j])(rng);
      const auto a = plain.state(plain.start), b = plain.state(plain.goal);
      found = plain.p.si->isValid(b.get()) && !plain.p.si->checkMotion(a.get(), b.get());
    }
    BOOST_REQUIRE(found);
    wrapped.goal = plain.goal;
    const auto a = plain.state(plain.start), b = plain.state(plain.goal);
    ompl::RNG::setSeed(seed);
    plain.ss.setPlanner(std::make_shared<og::RRTConnect>(plain.p.si));
    plain.ss.setStartAndGoalStates(a, b);
    const std::uint64_t plain0 = plain.checker->counters().checks;
    BOOST_REQUIRE(plain.ss.solve(tenSeconds()) == ob::PlannerStatus::EXACT_SOLUTION);
    const std::uint64_t plain_checks = plain.checker->counters().checks - plain0;

    ompl::RNG::setSeed(seed);
    auto direct =
        std::make_shared<dss::DirectFirstPlanner>(std::make_shared<og::RRTConnect>(wrapped.p.si));
    wrapped.ss.setPlanner(direct);
    // Several goal states, none of them in sight: each is tried, then the planner runs.
    auto goals = std::make_shared<ob::GoalStates>(wrapped.p.si);
    goals->addState(wrapped.state(wrapped.goal));
    wrapped.ss.setStartState(wrapped.state(wrapped.start));
    wrapped.ss.setGoal(goals);
    const std::uint64_t wrapped0 = wrapped.checker->counters().checks;
    BOOST_REQUIRE(wrapped.ss.solve(tenSeconds()) == ob::PlannerStatus::EXACT_SOLUTION);
    const std::uint64_t wrapped_checks = wrapped.checker->counters().checks - wrapped0;
    BOOST_CHECK(!direct->lastWasDirect());
    BOOST_CHECK_MESSAGE(wrapped.path() == plain.path(), "seed " << seed << ": paths differ");
    // The attempt: the two ends, then the motion's states up to its first collision.
    BOOST_CHECK_GT(wrapped_checks, plain_checks + 2);
    BOOST_CHECK_LT(wrapped_checks, plain_checks + 2 + 200);
  }
}

BOOST_AUTO_TEST_CASE(an_invalid_start_or_a_goal_without_states_goes_to_the_wrapped_planner) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const Shelf shelf;
  Setup s(shelf);
  // A start with a NaN value: never tried; RRTConnect finds no valid start.
  {
    std::vector<double> bad = s.start;
    bad[1] = std::numeric_limits<double>::quiet_NaN();
    auto direct =
        std::make_shared<dss::DirectFirstPlanner>(std::make_shared<og::RRTConnect>(s.p.si));
    s.ss.setPlanner(direct);
    s.ss.setStartAndGoalStates(s.state(bad), s.state(s.start));
    BOOST_CHECK(s.ss.solve(ob::timedPlannerTerminationCondition(0.2)) ==
                ob::PlannerStatus::INVALID_START);
    BOOST_CHECK(!direct->lastWasDirect());
  }
  // A goal region around a state in sight of the start: not tried (it lists no states), so the
  // wrapped planner grows its trees to it.
  const auto goals = goalsInSight(s, 11, 0.1, 1);
  BOOST_REQUIRE_EQUAL(goals.size(), 1u);
  const auto a = s.state(s.start), b = s.state(goals.front());
  auto inner = std::make_shared<og::RRTConnect>(s.p.si);
  auto direct = std::make_shared<dss::DirectFirstPlanner>(inner);
  s.ss.setPlanner(direct);
  s.ss.setStartState(a);
  s.ss.setGoal(std::make_shared<BallGoal>(s.p.si, b.get()));
  BOOST_REQUIRE(s.ss.solve(tenSeconds()) == ob::PlannerStatus::EXACT_SOLUTION);
  BOOST_CHECK(!direct->lastWasDirect());
  BOOST_CHECK_GT(plannerVertices(*inner), 0u);
}

BOOST_AUTO_TEST_CASE(needs_a_planner_to_wrap) {
  BOOST_CHECK_THROW(dss::DirectFirstPlanner(nullptr), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
