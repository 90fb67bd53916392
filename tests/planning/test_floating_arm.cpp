// An arm on a floating base: the Panda with its SRDF's floating virtual joint moved by the
// planning group together with the arm (a group as a MoveIt user defines it for a humanoid
// torso or a free-flying manipulator). The group's space is an SE(3) part and the arm's seven
// joints; states answer as the same arm placed by a fixed joint at the base's pose; DSS and
// fcl-hull agree on random states; the continuous validator never accepts a motion on which a
// dense check finds a collision; RRTConnect plans with our discrete validator, and the path
// holds under a dense check.
#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>

#include "dss/checker/dss_checker.h"
#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/discrete_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/placed_robot.h"
#include "support/shared_data.h"
#include "support/space_sampling_checks.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

// The Panda's SRDF with one more group: its floating virtual joint and the arm.
std::string floatingArmSrdf() {
  const std::string srdf = dss_test::readText(dss_test::sharedPath("robots/panda/panda.srdf"));
  const std::regex vj("(<virtual_joint[^>]*name=\"virtual_joint\"[^>]*type=\"floating\"[^>]*/>)");
  BOOST_REQUIRE(std::regex_search(srdf, vj));
  return std::regex_replace(srdf, vj,
                            "$1<group name=\"vbase\"><joint name=\"virtual_joint\"/></group>"
                            "<group name=\"floating_arm\"><group name=\"vbase\"/>"
                            "<group name=\"panda_arm\"/></group>");
}

// The Panda with the floating-arm group, its base bounded to a box about the table's robot
// position, in the first MotionBenchMaker table_pick scene.
struct FloatingPanda {
  dss::LoadedRobot robot;
  dss::Scene scene;
  std::map<std::string, double> start;
  dss::Problem problem;

  FloatingPanda() {
    const std::string dir = dss_test::sharedPath("robots/panda");
    const std::string srdf_file = (std::filesystem::temp_directory_path() /
                                   ("dss_floating_arm_" + std::to_string(::getpid()) + ".srdf"))
                                      .string();
    {
      std::ofstream out(srdf_file);
      out << floatingArmSrdf();
    }
    robot = dss::withWorkspace(dss::loadRobot(dir + "/panda.urdf", srdf_file),
                               Eigen::Vector3d(-0.3, -0.3, -0.2), Eigen::Vector3d(0.3, 0.3, 0.2));
    std::filesystem::remove(srdf_file);
    const std::string mbm = dss_test::sharedPath("scenes/mbm_panda/table_pick");
    scene = dss::loadScene(mbm + "/scene0001.yaml");
    const dss::PlanRequest req = dss::loadPlanRequestYaml(mbm + "/request0001.yaml");
    start = req.startState();
    problem = dss::makeProblem(robot, scene, "floating_arm", start);
  }
};

}  // namespace

BOOST_AUTO_TEST_SUITE(floating_arm)

BOOST_AUTO_TEST_CASE(the_group_is_an_se3_part_and_the_arm, DSS_NEEDS_SHARED) {
  const FloatingPanda f;
  const auto compound = std::dynamic_pointer_cast<ob::CompoundStateSpace>(f.problem.map->space());
  BOOST_REQUIRE(compound);
  int se3 = 0;
  for (unsigned k = 0; k < compound->getSubspaceCount(); ++k)
    se3 += compound->getSubspace(k)->getType() == ob::STATE_SPACE_SE3;
  BOOST_TEST(se3 == 1);
  BOOST_TEST(f.problem.map->dimension() == 7u + 7u);  // position, quaternion, seven joints
  ob::StateSamplerPtr sampler = f.problem.map->space()->allocStateSampler();
  ob::ScopedState<> s(f.problem.map->space()), t(f.problem.map->space());
  for (int k = 0; k < 200; ++k) {
    sampler->sampleUniform(s.get());
    std::vector<double> g(f.problem.map->dimension());
    f.problem.map->toGroupValues(s.get(), g.data());
    f.problem.map->fromGroupValues(g.data(), t.get());
    BOOST_TEST(f.problem.map->space()->distance(s.get(), t.get()) < 1e-12);
  }
}

// The base at a random pose answers as the same arm placed there by a fixed joint.
BOOST_AUTO_TEST_CASE(a_floating_base_answers_as_a_fixed_joint_placing_it, DSS_NEEDS_SHARED) {
  const FloatingPanda f;
  const dss::RobotModel& m = *f.robot.model;
  const std::string dir = dss_test::sharedPath("robots/panda");
  const std::string urdf = dss_test::readText(dir + "/panda.urdf");
  const std::string fixed_srdf = std::regex_replace(
      dss_test::readText(dir + "/panda.srdf"), std::regex("type=\"floating\""), "type=\"fixed\"");
  const dss::DssChecker floating(f.problem.model);
  const char* names[7] = {"virtual_joint/trans_x", "virtual_joint/trans_y", "virtual_joint/trans_z",
                          "virtual_joint/rot_x",   "virtual_joint/rot_y",   "virtual_joint/rot_z",
                          "virtual_joint/rot_w"};
  int idx[7];
  for (int k = 0; k < 7; ++k) {
    idx[k] = m.variableIndex(names[k]);
    BOOST_REQUIRE(idx[k] >= 0);
  }
  // The fixed-joint arm never checks its base link against the scene (a link that never
  // moves): only base poses where the whole arm, at its start, is clear of the scene (the base
  // group alone, by FCL) are compared.
  const dss::Problem base_only = dss::makeProblem(f.robot, f.scene, "vbase", f.start);
  const auto fcl_base = dss::makeStateChecker(base_only.model, {"fcl-hull"});
  ob::StateSamplerPtr sampler = f.problem.map->space()->allocStateSampler();
  ob::ScopedState<> s(f.problem.map->space());
  std::vector<double> q(m.numActiveJoints());
  int colliding = 0, compared = 0, differ = 0;
  for (int pose = 0; pose < 8; ++pose) {
    for (int tries = 0;; ++tries) {
      BOOST_REQUIRE(tries < 10000);
      sampler->sampleUniform(s.get());
      BOOST_REQUIRE(f.problem.map->toJoints(s.get(), q.data()));
      std::vector<double> qb = base_only.model->held();
      for (int v : idx) qb[v] = q[v];
      if (fcl_base->check(qb.data()) == dss::StateVerdict::kFree) break;
    }
    const Eigen::Quaterniond r(q[idx[6]], q[idx[3]], q[idx[4]], q[idx[5]]);
    const Eigen::Vector3d rpy = r.normalized().toRotationMatrix().eulerAngles(2, 1, 0);
    const dss::LoadedRobot fixed_robot = dss_test::placedByFixedJoint(
        urdf, "panda_link0", Eigen::Vector3d(q[idx[0]], q[idx[1]], q[idx[2]]),
        Eigen::Vector3d(rpy[2], rpy[1], rpy[0]), fixed_srdf, dir);
    const dss::Problem pf = dss::makeProblem(fixed_robot, f.scene, "panda_arm",
                                             dss_test::startOf(*fixed_robot.model, f.start));
    const dss::DssChecker at_fixed(pf.model);
    std::mt19937_64 rng(pose);
    for (int k = 0; k < 150; ++k) {
      std::vector<double> qf;
      dss_test::drawGroupJoints(pf, m, rng, qf, q);
      const dss::StateVerdict a = floating.check(q.data()), b = at_fixed.check(qf.data());
      // The two kinematics differ in rounding only (a quaternion against roll, pitch, yaw):
      // where the answers differ, the one that says free must see the state at contact.
      if (a != b) {
        ++differ;
        const double gap = a == dss::StateVerdict::kFree ? floating.clearance(q.data())
                                                         : at_fixed.clearance(qf.data());
        BOOST_TEST(gap < 1e-6, "pose " << pose << " state " << k << " clearance " << gap);
      }
      colliding += a == dss::StateVerdict::kColliding;
      ++compared;
    }
  }
  BOOST_TEST_MESSAGE(compared << " states, " << colliding << " colliding, " << differ
                              << " answered differently (at contact)");
  BOOST_TEST(colliding > 0);
  BOOST_TEST(colliding < compared);
}

BOOST_AUTO_TEST_CASE(dss_and_fcl_hull_agree_on_random_states, DSS_NEEDS_SHARED) {
  const FloatingPanda f;
  const int n = 3000;
  const dss_test::Agreement t = dss_test::dssAgainstFclHull(f.problem, n);
  BOOST_TEST(t.differ == 0);
  BOOST_TEST(t.colliding > 0);
  BOOST_TEST(t.colliding < n);
}

BOOST_AUTO_TEST_CASE(continuous_validator_misses_nothing_a_dense_check_finds, DSS_NEEDS_SHARED) {
  const FloatingPanda f;
  const dss_test::MotionTally t = dss_test::continuousAgainstDense(f.problem, 200, 0.1);
  BOOST_TEST(t.missed == 0);
  BOOST_TEST(t.accepted > 0);
  BOOST_TEST(t.rejected > 0);
}

// RRTConnect from the request's start (base at the origin) to its goal joints with the base
// moved, through our discrete validator; the path holds under OMPL's own check of its states and
// motions.
BOOST_AUTO_TEST_CASE(rrt_connect_plans_and_the_path_is_free, DSS_NEEDS_SHARED) {
  const FloatingPanda f;
  const std::string mbm = dss_test::sharedPath("scenes/mbm_panda/table_pick");
  const dss::PlanRequest req = dss::loadPlanRequestYaml(mbm + "/request0001.yaml");
  const auto& si = f.problem.si;
  auto checker = dss::makeValidityChecker(f.problem, {"dss"});
  si->setStateValidityChecker(checker);
  si->setMotionValidator(dss::makeDiscreteMotionValidator(f.problem, *checker));
  si->setup();
  std::map<std::string, double> goal = f.start;
  BOOST_REQUIRE(!req.goals.empty());
  for (const dss::JointConstraint& c : req.goals.front().joint_constraints)
    goal[c.joint_name] = c.position;
  ob::ScopedState<> s0(si->getStateSpace()), s1(si->getStateSpace());
  f.problem.map->fromGroupValues(f.problem.map->groupValues(f.start).data(), s0.get());
  BOOST_REQUIRE(checker->isValid(s0.get()));
  // The goal joints with the base lifted and shifted: the first such pose that is free.
  bool goal_found = false;
  for (double z : {0.05, 0.1, 0.15, 0.2})
    for (double x : {-0.1, 0.0, 0.1})
      for (double y : {-0.1, 0.0, 0.1}) {
        if (goal_found) continue;
        goal["virtual_joint/trans_x"] = x;
        goal["virtual_joint/trans_y"] = y;
        goal["virtual_joint/trans_z"] = z;
        f.problem.map->fromGroupValues(f.problem.map->groupValues(goal).data(), s1.get());
        goal_found = checker->isValid(s1.get());
      }
  BOOST_REQUIRE(goal_found);
  og::SimpleSetup ss(si);
  ss.setStartAndGoalStates(s0, s1);
  ss.setPlanner(std::make_shared<og::RRTConnect>(si));
  BOOST_REQUIRE(ss.solve(30.0) == ob::PlannerStatus::EXACT_SOLUTION);
  og::PathGeometric path = ss.getSolutionPath();
  BOOST_TEST(path.check());
  // The base moved on the way.
  bool base_moved = false;
  std::vector<double> g(f.problem.map->dimension());
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    f.problem.map->toGroupValues(path.getState(i), g.data());
    base_moved |= g[0] != 0.0 || g[1] != 0.0 || g[2] != 0.0;
  }
  BOOST_TEST(base_moved);
}

BOOST_AUTO_TEST_SUITE_END()
