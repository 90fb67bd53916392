// The README's "use the checker from your own OMPL code" snippet, compiled and run as is
// (between the SNIPPET markers), so that the documentation cannot rot.
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <boost/test/unit_test.hpp>

#include "dss/planning/planning_problem.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

BOOST_AUTO_TEST_SUITE(readme_snippet)

BOOST_AUTO_TEST_CASE(plans_with_the_dss_checker) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7/";
  // SNIPPET BEGIN
  dss::LoadedRobot robot = dss::loadRobot(dir + "dss_arm7.urdf", dir + "dss_arm7.srdf");
  dss::PlanRequest request = dss::loadPlanRequestYaml(dir + "scenes/shelf_request.yaml");
  dss::Problem problem = dss::makeProblem(robot, dss::loadScene(dir + "scenes/shelf.yaml"),
                                          request.group_name, request.startState());
  dss::CheckerConfig config;  // checker "dss", Mode::kExact, no padding
  auto checker = dss::makeValidityChecker(problem, config);

  og::SimpleSetup ss(problem.si);
  ss.setStateValidityChecker(checker);
  ob::ScopedState<> start(problem.si->getStateSpace()), goal(problem.si->getStateSpace());
  std::map<std::string, double> goal_by_name = request.startState();
  for (const auto& c : request.goals.at(0).joint_constraints)
    goal_by_name[c.joint_name] = c.position;
  problem.map->fromGroupValues(problem.map->groupValues(request.startState()).data(), start.get());
  problem.map->fromGroupValues(problem.map->groupValues(goal_by_name).data(), goal.get());
  ss.setStartAndGoalStates(start, goal);
  ss.setPlanner(std::make_shared<og::RRTConnect>(problem.si));
  const bool solved = ss.solve(5.0) == ob::PlannerStatus::EXACT_SOLUTION;
  // SNIPPET END
  BOOST_TEST(solved);
  // The waypoints are valid; between them the discrete validator only looked at OMPL's
  // resolution (the continuous validator covers the gaps: test_continuous_motion.cpp).
  const og::PathGeometric& path = ss.getSolutionPath();
  BOOST_TEST(path.getStateCount() >= 2u);
  for (std::size_t i = 0; i < path.getStateCount(); ++i)
    BOOST_TEST(checker->isValid(path.getState(i)));
}

BOOST_AUTO_TEST_SUITE_END()
