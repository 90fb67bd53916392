// The OMPL motion validator on the continuous motion check (continuous_motion_validator.h): it
// rejects a motion that sweeps through a thin plate between two valid states which OMPL's
// discrete validator (at its resolution) accepts, honours lastValid (a valid state before the
// plate), and a seeded plan made with it on our shelf scene has every motion accepted again and
// every densely interpolated state valid under DSS and fcl-hull. Its motion counts are its own
// (motionChecks), and it is built only on a DSS validity checker.
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <stdexcept>

#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace ob = ompl::base;

namespace {
// One revolute joint about z; a 1 cm thick box 1 m out along x.
const char* kArmUrdf = R"(<robot name="sweeper">
  <link name="base"/>
  <link name="arm"><collision><origin xyz="1.0 0 0"/><geometry><box size="0.1 0.01 0.01"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/></joint>
</robot>)";
}  // namespace

BOOST_AUTO_TEST_SUITE(continuous_motion_validator)

BOOST_AUTO_TEST_CASE(continuous_rejects_a_thin_plate_that_discrete_misses) {
  dss::LoadedRobot r;
  r.model =
      std::make_shared<const dss::RobotModel>(dss::loadUrdfString(kArmUrdf, "sweeper.urdf", "."));
  // A 1 mm plate on the ray halfway between two of the discrete validator's samples of the
  // motion 0 -> pi/2 (segment count as OMPL computes it: resolution 1% of the 2 pi extent).
  dss::Problem p0 = dss::makeProblem(r, dss::Scene{}, "", {});
  p0.si->setStateValidityChecker(dss::makeValidityChecker(p0, {"dss"}));
  p0.si->setup();
  ob::ScopedState<> a0(p0.si->getStateSpace()), b0(p0.si->getStateSpace());
  a0[0] = 0.0;
  b0[0] = M_PI / 2;
  const unsigned n = p0.si->getStateSpace()->validSegmentCount(a0.get(), b0.get());
  BOOST_TEST_MESSAGE("discrete segments: " << n);
  BOOST_REQUIRE(n > 12);
  const double angle = 10.5 * (M_PI / 2) / n;
  dss::Scene scene;
  dss::Obstacle plate;
  plate.name = plate.object_id = "plate";
  plate.shape = dss::Box::fromSize(Eigen::Vector3d(0.3, 0.001, 0.3));
  plate.X_WO = Eigen::Translation3d(std::cos(angle), std::sin(angle), 0) *
               Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ());
  plate.X_FO = plate.X_WO;
  scene.obstacles.push_back(plate);
  dss::Problem p = dss::makeProblem(r, scene, "", {});
  auto checker = dss::makeValidityChecker(p, {"dss"});
  p.si->setStateValidityChecker(checker);
  p.si->setup();
  ob::ScopedState<> a(p.si->getStateSpace()), b(p.si->getStateSpace()), c(p.si->getStateSpace());
  a[0] = 0.0;
  b[0] = M_PI / 2;
  c[0] = 0.3;
  BOOST_REQUIRE(checker->isValid(a.get()));
  BOOST_REQUIRE(checker->isValid(b.get()));
  ob::DiscreteMotionValidator discrete(p.si);
  BOOST_TEST(discrete.checkMotion(a.get(), b.get()));  // the discrete check steps over the plate
  BOOST_TEST(dss::motionChecks(discrete) == 1u);
  auto continuous = dss::makeContinuousMotionValidator(p, *checker);
  BOOST_TEST(!continuous->checkMotion(a.get(), b.get()));
  BOOST_TEST(continuous->checkMotion(a.get(), c.get()));  // short of the plate: accepted
  // lastValid: a valid state before the plate.
  ob::State* last = p.si->allocState();
  std::pair<ob::State*, double> lv{last, -1.0};
  BOOST_TEST(!continuous->checkMotion(a.get(), b.get(), lv));
  BOOST_TEST(lv.second >= 0.0);
  BOOST_TEST(lv.second * M_PI / 2 < angle);
  BOOST_TEST(checker->isValid(last));
  p.si->freeState(last);
  // Its own counts (atomic), not OMPL's.
  BOOST_TEST(continuous->validMotions() == 1u);
  BOOST_TEST(continuous->invalidMotions() == 2u);
  BOOST_TEST(dss::motionChecks(*continuous) == 3u);
}

// The motion validator needs the DSS checker (its bounds and narrow phase): an FCL validity
// checker is refused.
BOOST_AUTO_TEST_CASE(needs_a_dss_validity_checker) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const auto r = dss::loadRobot(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf");
  const dss::Problem p = dss::makeProblem(r, dss::loadScene(dir + "/scenes/shelf.yaml"), "", {});
  for (const char* name : {"fcl-hull", "fcl-mesh"}) {
    auto fcl = dss::makeValidityChecker(p, {name});
    BOOST_CHECK_THROW(dss::makeContinuousMotionValidator(p, *fcl), std::invalid_argument);
  }
  auto dss_checker = dss::makeValidityChecker(p, {"dss"});
  auto cmv = dss::makeContinuousMotionValidator(p, *dss_checker);
  BOOST_TEST(&cmv->motionChecker().checker() == &dss_checker->checker());
  BOOST_CHECK_THROW(dss::makeContinuousMotionValidator(p, *dss_checker, 0.0),
                    std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(shelf_plan_with_continuous_motions) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const auto r = dss::loadRobot(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(dir + "/scenes/shelf_request.yaml");
  dss::Problem p = dss::makeProblem(r, dss::loadScene(dir + "/scenes/shelf.yaml"), req.group_name,
                                    req.startState());
  auto checker = dss::makeValidityChecker(p, {"dss"});
  auto fcl = dss::makeValidityChecker(p, {"fcl-hull"});
  auto cmv = dss::makeContinuousMotionValidator(p, *checker);
  ompl::geometric::SimpleSetup ss(p.si);
  ss.setStateValidityChecker(checker);
  p.si->setMotionValidator(cmv);
  ss.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(p.si));
  ob::ScopedState<> start(p.si->getStateSpace()), goal(p.si->getStateSpace());
  std::map<std::string, double> goal_map;
  for (const auto& jc : req.goals.at(0).joint_constraints) goal_map[jc.joint_name] = jc.position;
  const auto g0 = p.map->groupValues(req.startState()), g1 = p.map->groupValues(goal_map);
  p.map->fromGroupValues(g0.data(), start.get());
  p.map->fromGroupValues(g1.data(), goal.get());
  ss.setStartAndGoalStates(start, goal);
  BOOST_REQUIRE(ss.solve(20.0) == ob::PlannerStatus::EXACT_SOLUTION);
  auto path = ss.getSolutionPath();
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
    BOOST_TEST(cmv->checkMotion(path.getState(i), path.getState(i + 1)));
  path.interpolate(2000);  // far finer than OMPL's resolution: continuous motions stay valid
  int bad_dss = 0, bad_fcl = 0;
  for (auto* s : path.getStates()) {
    bad_dss += !checker->isValid(s);
    bad_fcl += !fcl->isValid(s);
  }
  BOOST_TEST(bad_dss == 0);
  BOOST_TEST(bad_fcl == 0);
  BOOST_TEST_MESSAGE("continuous plan: " << cmv->motionChecker().subMotions() << " sub-motions");
}

BOOST_AUTO_TEST_SUITE_END()
