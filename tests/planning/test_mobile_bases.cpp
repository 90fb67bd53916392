// Planar and floating bases end to end: our mobile base (planar virtual joint) in its aisle and
// our free flyer (floating virtual joint) behind its window. Their groups become SE(2) and
// SE(3) parts of the state space (refused without translation bounds); states with the base
// far away answer as the same robot placed there by a fixed joint; DSS and fcl-hull agree on
// random states; the continuous validator never accepts a motion on which a dense check finds a
// collision. (Plans from dss_plan: tests/tools/test_mobile_base_plans.cpp.)
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "dss/checker/dss_checker.h"
#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/multi_dof.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/thrown_message.h"

namespace ob = ompl::base;

namespace {

const std::string kRobots = std::string(DSS_SOURCE_DIR) + "/robots";

struct Case {
  std::string dir, urdf, srdf, scene, request;
};
const Case kMobile{kRobots + "/dss_mobile_base", "dss_mobile_base.urdf", "dss_mobile_base.srdf",
                   "scenes/aisle.yaml", "scenes/aisle_request.yaml"};
const Case kFlyer{kRobots + "/dss_free_flyer", "dss_free_flyer.urdf", "dss_free_flyer.srdf",
                  "scenes/window.yaml", "scenes/window_request.yaml"};

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The robot bounded by its request's workspace, the request's start, and the problem.
struct Loaded {
  dss::LoadedRobot robot;
  dss::PlanRequest request;
  std::map<std::string, double> start;
  dss::Problem problem;
};

Loaded load(const Case& c) {
  Loaded l;
  l.request = dss::loadPlanRequestYaml(c.dir + "/" + c.request);
  BOOST_REQUIRE(l.request.workspace.has_value());
  l.robot = dss::withWorkspace(dss::loadRobot(c.dir + "/" + c.urdf, c.dir + "/" + c.srdf),
                               l.request.workspace->first, l.request.workspace->second);
  l.start = l.request.startState();
  for (const auto& [n, v] : dss::multiDofStateValues(*l.robot.model, l.request.start_multi_dof))
    l.start[n] = v;
  l.problem = dss::makeProblem(l.robot, dss::loadScene(c.dir + "/" + c.scene), l.request.group_name,
                               l.start);
  return l;
}

// A state of the problem's group drawn by OMPL's sampler, as every active joint's value.
std::vector<double> sample(const dss::Problem& p, ob::StateSamplerPtr& sampler, ob::State* s) {
  sampler->sampleUniform(s);
  std::vector<double> q(p.model->robot().numActiveJoints());
  BOOST_REQUIRE(p.map->toJoints(s, q.data()));
  return q;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mobile_bases)

BOOST_AUTO_TEST_CASE(planar_and_floating_groups_become_se2_and_se3_parts) {
  for (const Case* c : {&kMobile, &kFlyer}) {
    const Loaded l = load(*c);
    const auto compound = std::dynamic_pointer_cast<ob::CompoundStateSpace>(l.problem.map->space());
    BOOST_REQUIRE(compound);
    int se2 = 0, se3 = 0;
    for (unsigned k = 0; k < compound->getSubspaceCount(); ++k) {
      se2 += compound->getSubspace(k)->getType() == ob::STATE_SPACE_SE2;
      se3 += compound->getSubspace(k)->getType() == ob::STATE_SPACE_SE3;
    }
    BOOST_TEST(se2 == (c == &kMobile ? 1 : 0));
    BOOST_TEST(se3 == (c == &kFlyer ? 1 : 0));
    // Group values round trip through OMPL states (angles and quaternions as OMPL keeps them).
    ob::StateSamplerPtr sampler = l.problem.map->space()->allocStateSampler();
    ob::ScopedState<> s(l.problem.map->space()), t(l.problem.map->space());
    for (int k = 0; k < 100; ++k) {
      sampler->sampleUniform(s.get());
      std::vector<double> g(l.problem.map->dimension());
      l.problem.map->toGroupValues(s.get(), g.data());
      l.problem.map->fromGroupValues(g.data(), t.get());
      BOOST_TEST(l.problem.map->space()->distance(s.get(), t.get()) < 1e-12);
    }
    // Without the workspace the translation has no bounds: refused, naming the way out.
    const auto bare = dss::loadRobot(c->dir + "/" + c->urdf, c->dir + "/" + c->srdf);
    const std::string e = dss_test::thrownMessage(
        [&] { dss::makeProblem(bare, dss::Scene{}, l.request.group_name, l.start); });
    BOOST_TEST(e.find("has no finite bounds") != std::string::npos, e);
    BOOST_TEST(e.find("workspace_parameters") != std::string::npos, e);
  }
}

BOOST_AUTO_TEST_CASE(a_base_far_away_answers_as_a_fixed_joint_placing_it_there) {
  // The same robot with its base placed by a fixed joint from a new root: the SRDF's planar
  // virtual joint becomes a fixed one (its groups then hold the arm only).
  const Loaded l = load(kMobile);
  const std::string urdf = readText(kMobile.dir + "/" + kMobile.urdf);
  const std::string srdf = std::regex_replace(readText(kMobile.dir + "/" + kMobile.srdf),
                                              std::regex("type=\"planar\""), "type=\"fixed\"");
  const dss::Scene scene = dss::loadScene(kMobile.dir + "/" + kMobile.scene);
  const dss::RobotModel& m = *l.robot.model;
  const int x = m.variableIndex("base/x"), y = m.variableIndex("base/y"),
            th = m.variableIndex("base/theta");
  BOOST_REQUIRE(x >= 0 && y >= 0 && th >= 0);
  const dss::DssChecker planar(l.problem.model);
  // The fixed-joint robot does not check its base against the scene (a link that never moves):
  // only poses where the base (with the arm held) is clear of the scene, by FCL, are compared.
  const dss::Problem base_only = dss::makeProblem(l.robot, scene, "base", l.start);
  const auto fcl_base = dss::makeStateChecker(base_only.model, {"fcl-hull"});
  ob::StateSamplerPtr sampler = l.problem.map->space()->allocStateSampler();
  ob::ScopedState<> s(l.problem.map->space());
  int colliding = 0, compared = 0;
  for (int pose = 0; pose < 12; ++pose) {
    std::vector<double> q;
    for (;;) {
      q = sample(l.problem, sampler, s.get());
      std::vector<double> qb = base_only.model->held();
      for (int v : {x, y, th}) qb[v] = q[v];
      if (fcl_base->check(qb.data()) == dss::StateVerdict::kFree) break;
    }
    std::ostringstream fixed;
    fixed.precision(17);
    fixed << "<link name=\"world\"/><joint name=\"place\" type=\"fixed\"><parent link=\"world\"/>"
          << "<child link=\"base_link\"/><origin xyz=\"" << q[x] << " " << q[y] << " 0\" rpy=\"0 0 "
          << q[th] << "\"/></joint>";
    const std::string placed =
        std::regex_replace(urdf, std::regex("(<robot name=\"[^\"]*\">)"), "$1" + fixed.str());
    // Mesh paths resolve against the original folder.
    dss::LoadedRobot fixed_robot;
    fixed_robot.model = std::make_shared<const dss::RobotModel>(
        dss::loadUrdfString(placed, "placed.urdf", kMobile.dir));
    fixed_robot.srdf = dss::parseSrdf(srdf, "placed.srdf");
    std::map<std::string, double> arm_start;
    for (const auto& [n, v] : l.start)
      if (fixed_robot.model->variableIndex(n) >= 0) arm_start[n] = v;
    const dss::Problem pf = dss::makeProblem(fixed_robot, scene, "mast_arm", arm_start);
    const dss::DssChecker at_fixed(pf.model);
    const dss::RobotModel& fm = *fixed_robot.model;
    std::mt19937_64 rng(pose);
    for (int k = 0; k < 300; ++k) {
      std::vector<double> qf = pf.model->held();
      for (int a : pf.model->groupActive()) {
        const auto& j = fm.joints[fm.active_joints[a]];
        const double v =
            std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng);
        qf[a] = v;
        q[m.variableIndex(fm.activeJointNames()[a])] = v;
      }
      const dss::StateVerdict a = planar.check(q.data()), b = at_fixed.check(qf.data());
      BOOST_TEST((a == b), "pose " << pose << " state " << k);
      colliding += a == dss::StateVerdict::kColliding;
      ++compared;
    }
  }
  // Both answers occur (the test can fail both ways).
  BOOST_TEST(colliding > 0);
  BOOST_TEST(colliding < compared);
}

BOOST_AUTO_TEST_CASE(dss_and_fcl_hull_agree_on_random_states) {
  for (const Case* c : {&kMobile, &kFlyer}) {
    const Loaded l = load(*c);
    auto dss = dss::makeStateChecker(l.problem.model, {"dss"});
    auto fcl = dss::makeStateChecker(l.problem.model, {"fcl-hull"});
    ob::StateSamplerPtr sampler = l.problem.map->space()->allocStateSampler();
    ob::ScopedState<> s(l.problem.map->space());
    int differ = 0, colliding = 0;
    const int n = 3000;
    for (int k = 0; k < n; ++k) {
      const std::vector<double> q = sample(l.problem, sampler, s.get());
      const dss::StateVerdict a = dss->check(q.data()), b = fcl->check(q.data());
      differ += a != b;
      colliding += a == dss::StateVerdict::kColliding;
    }
    BOOST_TEST(differ == 0, c->urdf);
    BOOST_TEST(colliding > 0, c->urdf);
    BOOST_TEST(colliding < n, c->urdf);
  }
}

BOOST_AUTO_TEST_CASE(continuous_validator_misses_nothing_a_dense_check_finds) {
  for (const Case* c : {&kMobile, &kFlyer}) {
    const Loaded l = load(*c);
    auto checker = dss::makeValidityChecker(l.problem, {"dss"});
    auto motion = dss::makeContinuousMotionValidator(l.problem, *checker);
    const auto& si = l.problem.si;
    ob::StateSamplerPtr sampler = si->allocStateSampler();
    ob::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace()), mid(si->getStateSpace());
    int accepted = 0, rejected = 0, missed = 0;
    for (int k = 0; k < 300; ++k) {
      do sampler->sampleUniform(a.get());
      while (!checker->isValid(a.get()));
      // Motions of up to a quarter of the space's extent.
      sampler->sampleUniformNear(b.get(), a.get(), 0.25 * si->getMaximumExtent());
      si->enforceBounds(b.get());
      if (!checker->isValid(b.get())) continue;
      const bool clear = motion->checkMotion(a.get(), b.get());
      (clear ? accepted : rejected) += 1;
      if (!clear) continue;
      for (int i = 1; i < 400; ++i) {
        si->getStateSpace()->interpolate(a.get(), b.get(), i / 400.0, mid.get());
        if (!checker->isValid(mid.get())) {
          ++missed;
          break;
        }
      }
    }
    BOOST_TEST(missed == 0, c->urdf);
    BOOST_TEST(accepted > 0, c->urdf);
    BOOST_TEST(rejected > 0, c->urdf);
  }
}

BOOST_AUTO_TEST_SUITE_END()
