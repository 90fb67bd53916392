// Planar and floating bases end to end: our mobile base (planar virtual joint) in its aisle, our
// free flyer (floating virtual joint) behind its window and our quadrotor (floating) among
// trees. Their groups become SE(2) and
// SE(3) parts of the state space (refused without translation bounds); states with the base
// far away answer as the same robot placed there by a fixed joint; DSS and fcl-hull agree on
// random states; the continuous validator never accepts a motion on which a dense check finds a
// collision. (Plans from dss_plan: tests/tools/test_mobile_base_plans.cpp.)
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>
#include <regex>

#include "dss/checker/dss_checker.h"
#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/multi_dof.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/placed_robot.h"
#include "support/space_sampling_checks.h"
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
const Case kQuadrotor{kRobots + "/dss_quadrotor", "dss_quadrotor.urdf", "dss_quadrotor.srdf",
                      "scenes/forest.yaml", "scenes/forest_request.yaml"};

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
  for (const Case* c : {&kMobile, &kFlyer, &kQuadrotor}) {
    const Loaded l = load(*c);
    const auto compound = std::dynamic_pointer_cast<ob::CompoundStateSpace>(l.problem.map->space());
    BOOST_REQUIRE(compound);
    int se2 = 0, se3 = 0;
    for (unsigned k = 0; k < compound->getSubspaceCount(); ++k) {
      se2 += compound->getSubspace(k)->getType() == ob::STATE_SPACE_SE2;
      se3 += compound->getSubspace(k)->getType() == ob::STATE_SPACE_SE3;
    }
    BOOST_TEST(se2 == (c == &kMobile ? 1 : 0));
    BOOST_TEST(se3 == (c == &kMobile ? 0 : 1));
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
  const std::string urdf = dss_test::readText(kMobile.dir + "/" + kMobile.urdf);
  const std::string srdf = std::regex_replace(dss_test::readText(kMobile.dir + "/" + kMobile.srdf),
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
    // Mesh paths resolve against the original folder.
    const dss::LoadedRobot fixed_robot =
        dss_test::placedByFixedJoint(urdf, "base_link", Eigen::Vector3d(q[x], q[y], 0.0),
                                     Eigen::Vector3d(0.0, 0.0, q[th]), srdf, kMobile.dir);
    const dss::Problem pf = dss::makeProblem(fixed_robot, scene, "mast_arm",
                                             dss_test::startOf(*fixed_robot.model, l.start));
    const dss::DssChecker at_fixed(pf.model);
    std::mt19937_64 rng(pose);
    for (int k = 0; k < 300; ++k) {
      std::vector<double> qf;
      dss_test::drawGroupJoints(pf, m, rng, qf, q);
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

// The free flyer on its floating joint answers as the same body carried by six joints from a
// fixed root (dss_free_flyer_serial.urdf: x, y, z, then yaw, pitch, roll), pose for pose: the
// quaternion of Rz(yaw) Ry(pitch) Rx(roll) on one side, the six joint values on the other.
BOOST_AUTO_TEST_CASE(the_floating_flyer_answers_as_its_body_on_six_fixed_base_joints) {
  const Loaded l = load(kFlyer);
  const dss::LoadedRobot serial_robot =
      dss::loadRobot(kFlyer.dir + "/dss_free_flyer_serial.urdf", "");
  const dss::Problem serial =
      dss::makeProblem(serial_robot, dss::loadScene(kFlyer.dir + "/" + kFlyer.scene), "", {});
  const dss::RobotModel& mf = *l.robot.model;
  const dss::RobotModel& ms = *serial_robot.model;
  BOOST_REQUIRE(ms.numActiveJoints() == 6u);
  const auto index = [](const dss::RobotModel& m, const std::string& name) {
    const int i = m.variableIndex(name);
    BOOST_REQUIRE_MESSAGE(i >= 0, name);
    return i;
  };
  const int ft[3] = {index(mf, "base/trans_x"), index(mf, "base/trans_y"),
                     index(mf, "base/trans_z")};
  const int fr[4] = {index(mf, "base/rot_x"), index(mf, "base/rot_y"), index(mf, "base/rot_z"),
                     index(mf, "base/rot_w")};
  const int st[3] = {index(ms, "x"), index(ms, "y"), index(ms, "z")};
  const int yaw = index(ms, "yaw"), pitch = index(ms, "pitch"), roll = index(ms, "roll");
  const std::vector<std::shared_ptr<const dss::StateChecker>> floating = {
      dss::makeStateChecker(l.problem.model, {"dss"}),
      dss::makeStateChecker(l.problem.model, {"fcl-hull"})};
  const std::vector<std::shared_ptr<const dss::StateChecker>> fixed = {
      dss::makeStateChecker(serial.model, {"dss"}),
      dss::makeStateChecker(serial.model, {"fcl-hull"})};
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 3000;
  int colliding = 0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d p(-3.0 + 6.0 * u(rng), -2.0 + 4.0 * u(rng), 3.0 * u(rng));
    const double a = M_PI * (2.0 * u(rng) - 1.0), b = 0.5 * M_PI * (2.0 * u(rng) - 1.0),
                 c = M_PI * (2.0 * u(rng) - 1.0);
    std::vector<double> qs(ms.numActiveJoints()), qf = l.problem.model->held();
    for (int i = 0; i < 3; ++i) qs[st[i]] = qf[ft[i]] = p[i];
    qs[yaw] = a, qs[pitch] = b, qs[roll] = c;
    const Eigen::Quaterniond q = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(c, Eigen::Vector3d::UnitX());
    qf[fr[0]] = q.x(), qf[fr[1]] = q.y(), qf[fr[2]] = q.z(), qf[fr[3]] = q.w();
    const dss::StateVerdict v = floating[0]->check(qf.data());
    BOOST_TEST((v != dss::StateVerdict::kInvalidInput), "state " << k);
    BOOST_TEST((floating[1]->check(qf.data()) == v), floating[1]->name() << " state " << k);
    for (const auto& checker : fixed)
      BOOST_TEST((checker->check(qs.data()) == v), checker->name() << " state " << k);
    colliding += v == dss::StateVerdict::kColliding;
  }
  // Both answers occur (the test can fail both ways).
  BOOST_TEST(colliding > 0);
  BOOST_TEST(colliding < n);
}

BOOST_AUTO_TEST_CASE(dss_and_fcl_hull_agree_on_random_states) {
  for (const Case* c : {&kMobile, &kFlyer, &kQuadrotor}) {
    const Loaded l = load(*c);
    const int n = 3000;
    const dss_test::Agreement t = dss_test::dssAgainstFclHull(l.problem, n);
    BOOST_TEST(t.differ == 0, c->urdf);
    BOOST_TEST(t.colliding > 0, c->urdf);
    BOOST_TEST(t.colliding < n, c->urdf);
  }
}

// An obstacle the scene allows one link to touch stays allowed to it however deep the link goes
// into it, while the other links still collide with it (the clearance grid's proofs of
// collision count only obstacles no link may touch): the mobile base with a low block in its
// aisle that its base link may drive through answers as fcl-hull on the same model, and some
// of its states are free only because of that entry.
BOOST_AUTO_TEST_CASE(an_obstacle_allowed_to_one_link_stays_allowed_deep_inside_it) {
  const Loaded l = load(kMobile);
  dss::Scene scene = dss::loadScene(kMobile.dir + "/" + kMobile.scene);
  dss::Obstacle block;
  block.name = block.object_id = "block";
  block.shape = dss::Box{Eigen::Vector3d(1.0, 0.7, 0.125)};  // z -0.05 .. 0.2, the deck's height
  block.X_WO.translation() = Eigen::Vector3d(4.5, 0.0, 0.075);
  block.X_FO = block.X_WO;
  block.frame_resolved = true;
  scene.obstacles.push_back(block);
  dss::Scene allowing = scene;
  allowing.allowed_collisions.allow("base_link", "block");
  dss::CollisionModelOptions every_chain;  // whether or not they pay here
  every_chain.chain_min_settled = 0.0;
  const dss::Problem with_block =
      dss::makeProblem(l.robot, std::move(scene), l.request.group_name, l.start, every_chain);
  const dss::Problem allowed =
      dss::makeProblem(l.robot, std::move(allowing), l.request.group_name, l.start, every_chain);
  // The base link's chain runs (its inner balls could prove collisions with the block).
  int base_chain = -1;
  for (const auto& slot : allowed.model->slots())
    if (allowed.model->robot().links[slot.link].name == "base_link") base_chain = slot.num_chain;
  BOOST_TEST(base_chain > 0);
  const int n = 4000;
  const dss_test::Agreement t = dss_test::dssAgainstFclHull(allowed, n);
  BOOST_TEST(t.differ == 0);
  BOOST_TEST(t.colliding > 0);
  auto with = dss::makeStateChecker(allowed.model, {"dss"});
  auto without = dss::makeStateChecker(with_block.model, {"dss"});
  ob::StateSamplerPtr sampler = allowed.map->space()->allocStateSampler();
  ob::ScopedState<> s(allowed.map->space());
  int freed = 0;
  for (int k = 0; k < n; ++k) {
    const std::vector<double> q = sample(allowed, sampler, s.get());
    freed += with->check(q.data()) == dss::StateVerdict::kFree &&
             without->check(q.data()) == dss::StateVerdict::kColliding;
  }
  BOOST_TEST(freed > 10);
}

BOOST_AUTO_TEST_CASE(continuous_validator_misses_nothing_a_dense_check_finds) {
  for (const Case* c : {&kMobile, &kFlyer, &kQuadrotor}) {
    const Loaded l = load(*c);
    // Motions of up to a quarter of the space's extent.
    const dss_test::MotionTally t = dss_test::continuousAgainstDense(l.problem, 300, 0.25);
    BOOST_TEST(t.missed == 0, c->urdf);
    BOOST_TEST(t.accepted > 0, c->urdf);
    BOOST_TEST(t.rejected > 0, c->urdf);
  }
}

BOOST_AUTO_TEST_SUITE_END()
