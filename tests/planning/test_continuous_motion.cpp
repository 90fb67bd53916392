// The conservative continuous motion validator: it rejects a motion that sweeps through a
// thin plate between two valid states which the discrete validator (OMPL's resolution)
// accepts, honours lastValid, and a seeded plan made with it on our shelf scene has every
// motion accepted again and every densely interpolated state valid under DSS and fcl-hull.
// Its motion bound (paddings) holds on finely sampled random motions, and on random motions
// it never accepts what dense sampling finds colliding.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <ompl/base/ScopedState.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/urdf_loader.h"
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

BOOST_AUTO_TEST_CASE(continuous_rejects_a_thin_plate_that_discrete_misses) {
  dss::LoadedRobot r;
  r.model = std::make_shared<const dss::RobotModel>(dss::loadUrdfString(kArmUrdf, "sweeper.urdf", "."));
  // A 1 mm plate on the ray halfway between two of the discrete validator's samples of the
  // motion 0 -> pi/2 (segment count as OMPL computes it: resolution 1% of the 2 pi extent).
  dss::Problem p0 = dss::makeProblem(r, dss::Scene{}, "", {});
  p0.si->setStateValidityChecker(dss::makeChecker(p0, {"dss"}));
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
  plate.X_WO = Eigen::Translation3d(std::cos(angle), std::sin(angle), 0) * Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ());
  plate.X_FO = plate.X_WO;
  scene.obstacles.push_back(plate);
  dss::Problem p = dss::makeProblem(r, scene, "", {});
  auto checker = std::dynamic_pointer_cast<dss::DssValidityChecker>(dss::makeChecker(p, {"dss"}));
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
  dss::ContinuousMotionValidator continuous(p.si, checker);
  BOOST_TEST(!continuous.checkMotion(a.get(), b.get()));
  BOOST_TEST(continuous.checkMotion(a.get(), c.get()));  // short of the plate: accepted
  // lastValid: a valid state before the plate.
  ob::State* last = p.si->allocState();
  std::pair<ob::State*, double> lv{last, -1.0};
  BOOST_TEST(!continuous.checkMotion(a.get(), b.get(), lv));
  BOOST_TEST(lv.second >= 0.0);
  BOOST_TEST(lv.second * M_PI / 2 < angle);
  BOOST_TEST(checker->isValid(last));
  p.si->freeState(last);
}

BOOST_AUTO_TEST_CASE(shelf_plan_with_continuous_motions) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const auto r = dss::loadRobot(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(dir + "/scenes/shelf_request.yaml");
  dss::Problem p = dss::makeProblem(r, dss::loadScene(dir + "/scenes/shelf.yaml"), req.group_name, req.startState());
  auto checker = std::dynamic_pointer_cast<dss::DssValidityChecker>(dss::makeChecker(p, {"dss"}));
  auto fcl = dss::makeChecker(p, {"fcl-hull"});
  auto cmv = std::make_shared<dss::ContinuousMotionValidator>(p.si, checker);
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
  BOOST_TEST_MESSAGE("continuous plan: " << cmv->subMotions() << " sub-motions");
}

namespace {

struct Arm {
  dss::LoadedRobot robot;
  dss::Problem problem;
  std::shared_ptr<dss::DssValidityChecker> checker;
};

Arm loadArm(const std::string& urdf, const std::string& srdf, const std::string& scene_file) {
  Arm a;
  a.robot = dss::loadRobot(urdf, srdf);
  a.problem = dss::makeProblem(a.robot, scene_file.empty() ? dss::Scene{} : dss::loadScene(scene_file), "", {});
  a.checker = std::dynamic_pointer_cast<dss::DssValidityChecker>(dss::makeChecker(a.problem, {"dss"}));
  a.problem.si->setStateValidityChecker(a.checker);
  a.problem.si->setup();
  return a;
}

// Group values -> full active-joint vector (held joints at their held values).
std::vector<double> fullJoints(const dss::Problem& p, const std::vector<double>& g) {
  std::vector<double> q = p.model->held();
  for (std::size_t i = 0; i < g.size(); ++i) q[p.model->groupActive()[i]] = g[i];
  return q;
}

std::vector<double> randomGroupState(const Arm& a, std::mt19937_64& rng) {
  std::vector<double> g;
  for (int act : a.problem.model->groupActive()) {
    const auto& j = a.robot.model->joints[a.robot.model->active_joints[act]];
    g.push_back(std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng));
  }
  return g;
}

double distToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double len2 = d.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

// Every point of every moving slot's bounding sphere stays within paddings() of the segment
// between its end positions, sampled finely over seeded random motions of several lengths;
// and on short motions the padding shrinks quadratically (the bulge term), far below the
// linear bound half the path length.
void checkPaddings(const Arm& a, std::uint64_t seed) {
  dss::ContinuousMotionValidator cmv(a.problem.si, a.checker);
  const dss::CollisionModel& m = *a.problem.model;
  const std::size_t nl = a.robot.model->links.size();
  std::vector<Eigen::Isometry3d> X0(nl), X1(nl), Xt(nl);
  std::vector<double> pad(m.slots().size()), pad_half(m.slots().size());
  std::vector<Eigen::Vector3d> probes;
  for (int s : {-1, 1})
    for (int ax = 0; ax < 3; ++ax) probes.push_back(s * Eigen::Vector3d::Unit(ax));
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) probes.push_back(Eigen::Vector3d(sx, sy, sz).normalized());
  std::mt19937_64 rng(seed);
  double worst = 0.0;  // largest measured deviation / padding
  int violations = 0, checked = 0;
  for (double scale : {1.0, 0.3, 0.05, 0.01}) {
    for (int k = 0; k < 40; ++k) {
      const auto g0 = randomGroupState(a, rng), g1r = randomGroupState(a, rng);
      std::vector<double> g1(g0.size());
      for (std::size_t i = 0; i < g0.size(); ++i) g1[i] = g0[i] + scale * (g1r[i] - g0[i]);
      const auto q0 = fullJoints(a.problem, g0), q1 = fullJoints(a.problem, g1);
      cmv.paddings(q0.data(), q1.data(), pad.data());
      m.kinematics().computeLinkPoses(q0.data(), X0.data());
      m.kinematics().computeLinkPoses(q1.data(), X1.data());
      std::vector<double> qt(q0.size());
      for (int step = 1; step < 64; ++step) {
        const double t = step / 64.0;
        for (std::size_t i = 0; i < qt.size(); ++i) qt[i] = q0[i] + t * (q1[i] - q0[i]);
        m.kinematics().computeLinkPoses(qt.data(), Xt.data());
        for (std::size_t sl = 0; sl < m.slots().size(); ++sl) {
          const auto& s = m.slots()[sl];
          if (!s.moves) continue;
          for (const auto& u : probes) {
            const Eigen::Vector3d pL = s.center_L + s.radius * u;
            const double d = distToSegment(Xt[s.link] * pL, X0[s.link] * pL, X1[s.link] * pL);
            ++checked;
            if (d > pad[sl]) ++violations;
            if (pad[sl] > 0) worst = std::max(worst, d / pad[sl]);
          }
        }
      }
      if (scale == 0.01) {
        // Quadratic regime: the padding is at most the turn (radians) times the linear bound.
        std::vector<double> qh(q0.size());
        double turn = 0.0;
        for (std::size_t i = 0; i < q0.size(); ++i) turn += std::abs(q1[i] - q0[i]);
        for (std::size_t i = 0; i < q0.size(); ++i) qh[i] = 0.5 * (q0[i] + q1[i]);
        cmv.paddings(q0.data(), qh.data(), pad_half.data());
        for (std::size_t sl = 0; sl < m.slots().size(); ++sl)
          if (pad[sl] > 1e-9) BOOST_TEST(pad_half[sl] < 0.3 * pad[sl]);  // 1/4 up to the 1e-12 floor
        BOOST_TEST(turn < 1.0);
      }
    }
  }
  BOOST_TEST(violations == 0);
  BOOST_TEST(checked > 10000);
  BOOST_TEST_MESSAGE("paddings: " << checked << " probe positions, largest deviation / padding " << worst);
}

// Seeded random motions: when the continuous validator accepts a motion, every state sampled
// 2000 times along it is valid; when a sampled state collides, it rejects the motion, and its
// lastValid fraction lies before the first colliding sample with every sample up to it valid.
void checkAgainstDenseSampling(const Arm& a, std::uint64_t seed, double scale, int motions) {
  dss::ContinuousMotionValidator cmv(a.problem.si, a.checker);
  auto space = a.problem.si->getStateSpace();
  ob::ScopedState<> s0(space), s1(space), lastState(space);
  std::mt19937_64 rng(seed);
  int accepted = 0, colliding = 0, conservative = 0, made = 0;
  while (made < motions) {
    const auto g0 = randomGroupState(a, rng), g1r = randomGroupState(a, rng);
    std::vector<double> g1(g0.size());
    for (std::size_t i = 0; i < g0.size(); ++i) g1[i] = g0[i] + scale * (g1r[i] - g0[i]);
    const auto q0 = fullJoints(a.problem, g0), q1 = fullJoints(a.problem, g1);
    if (!a.checker->isValidJoints(q0.data())) continue;  // motions start at a valid state
    ++made;
    a.problem.map->fromGroupValues(g0.data(), s0.get());
    a.problem.map->fromGroupValues(g1.data(), s1.get());
    std::pair<ob::State*, double> lv{lastState.get(), -1.0};
    const bool ok = cmv.checkMotion(s0.get(), s1.get(), lv);
    int first_bad = -1;
    std::vector<double> qt(q0.size());
    const int kSamples = 2000;
    for (int step = 0; step <= kSamples && first_bad < 0; ++step) {
      for (std::size_t i = 0; i < qt.size(); ++i) qt[i] = q0[i] + (double(step) / kSamples) * (q1[i] - q0[i]);
      if (!a.checker->isValidJoints(qt.data())) first_bad = step;
    }
    if (ok) {
      ++accepted;
      BOOST_TEST(first_bad < 0, "accepted motion " << made << " collides at sample " << first_bad);
      continue;
    }
    if (first_bad >= 0) {
      ++colliding;
      BOOST_TEST(lv.second * kSamples < first_bad);
    } else {
      ++conservative;
    }
    BOOST_TEST(lv.second >= 0.0);
    BOOST_TEST(a.checker->isValid(lastState.get()));
  }
  BOOST_TEST(accepted > 0);
  BOOST_TEST(colliding > 0);
  BOOST_TEST_MESSAGE("dense sampling, scale " << scale << ": " << motions << " motions, " << accepted
                                              << " accepted, " << colliding << " colliding rejected, "
                                              << conservative << " rejected though every sample is valid; "
                                              << cmv.subMotions() << " sub-motions, " << cmv.unitTests()
                                              << " swept tests");
}

}  // namespace

BOOST_AUTO_TEST_CASE(paddings_bound_every_point_of_a_moving_link) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  checkPaddings(loadArm(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf", ""), 5);
  const std::string panda = std::string(DSS_SHARED_DIR) + "/robots/panda";
  if (!std::filesystem::exists(panda + "/panda.urdf")) {
    BOOST_TEST_MESSAGE("skipping the Panda: " << panda << " absent");
    return;
  }
  checkPaddings(loadArm(panda + "/panda.urdf", panda + "/panda.srdf", ""), 6);
}

BOOST_AUTO_TEST_CASE(continuous_agrees_with_dense_sampling) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const Arm arm = loadArm(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf", dir + "/scenes/shelf.yaml");
  checkAgainstDenseSampling(arm, 7, 0.15, 150);
  checkAgainstDenseSampling(arm, 8, 1.0, 60);
  const std::string panda = std::string(DSS_SHARED_DIR) + "/robots/panda";
  const std::string scene = std::string(DSS_SHARED_DIR) + "/scenes/mbm_panda/bookshelf_small/scene0001.yaml";
  if (!std::filesystem::exists(scene)) {
    BOOST_TEST_MESSAGE("skipping the Panda: " << scene << " absent");
    return;
  }
  const Arm p = loadArm(panda + "/panda.urdf", panda + "/panda.srdf", scene);
  checkAgainstDenseSampling(p, 9, 0.15, 150);
}
