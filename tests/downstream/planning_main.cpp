// Uses the installed planning component: our 7-DOF arm in its shelf scene, checked and planned
// with OMPL's RRTConnect, with the DSS checker and the continuous motion validator.
#include <dss/planning/planning_problem.h>
#include <dss/scene/plan_request.h>
#include <dss/scene/scene_loader.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <map>

int main() {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(1);
  const std::string dir = DSS_ROBOT_DIR;
  const dss::LoadedRobot robot = dss::loadRobot(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf");
  const dss::PlanRequest req = dss::loadPlanRequestYaml(dir + "/scenes/shelf_request.yaml");
  const std::map<std::string, double> start = req.startState();
  dss::Problem p =
      dss::makeProblem(robot, dss::loadScene(dir + "/scenes/shelf.yaml"), req.group_name, start);
  auto checker = dss::makeValidityChecker(p, dss::CheckerConfig{});
  ompl::geometric::SimpleSetup ss(p.si);
  ss.setStateValidityChecker(checker);
  p.si->setMotionValidator(dss::makeContinuousMotionValidator(p, *checker));
  ss.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(p.si));
  ompl::base::ScopedState<> s0(p.si->getStateSpace()), g0(p.si->getStateSpace());
  const std::vector<double> gs = p.map->groupValues(start);
  p.map->fromGroupValues(gs.data(), s0.get());
  std::map<std::string, double> goal = start;
  for (const auto& c : req.goals.front().joint_constraints) goal[c.joint_name] = c.position;
  const std::vector<double> gg = p.map->groupValues(goal);
  p.map->fromGroupValues(gg.data(), g0.get());
  ss.setStartAndGoalStates(s0, g0);
  const bool solved = ss.solve(10.0) == ompl::base::PlannerStatus::EXACT_SOLUTION;
  std::printf("downstream planning: %s (%llu state checks)\n", solved ? "solved" : "NOT SOLVED",
              static_cast<unsigned long long>(checker->counters().checks));
  return solved ? 0 : 1;
}
