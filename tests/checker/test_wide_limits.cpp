// Robots whose joint limits are far wider than a turn (1e300, as some URDFs write "no limit"):
// the stages of the model -- self-pair tables, the clearance grid, pair blocks, pose links,
// obstacle pruning, oriented boxes and inner balls -- must never change an answer against the
// plain sweep of every pair with exact DSS, at any angle; and an arm whose links can never meet
// is never called colliding (every state of such a robot was once rejected: the tables took
// answers on non-finite poses for certified collisions).
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>

#include "dss/checker/dss_checker.h"
#include "dss/core/any_shape_query.h"
#include "dss/robot/urdf_loader.h"
#include "support/checker_fixtures.h"
#include "support/temp_files.h"

namespace {

// The model's joints with every revolute limit widened to +-limit.
dss::LoadedRobot widened(const dss::LoadedRobot& robot, double limit) {
  auto m = std::make_shared<dss::RobotModel>(*robot.model);
  for (auto& j : m->joints)
    if (j.type == dss::JointType::kRevolute && j.limits.has_position_limits) {
      j.limits.lower = -limit;
      j.limits.upper = limit;
    }
  dss::LoadedRobot out = robot;
  out.model = m;
  return out;
}

// Every pair of the model with exact DSS and no stage at all: the reference answer.
bool plainSweepCollides(const dss::CollisionModel& m, const double* q) {
  std::vector<Eigen::Isometry3d> X(m.robot().links.size(), Eigen::Isometry3d::Identity());
  m.kinematics().computeLinkPoses(q, X.data());
  const auto& el = m.elements();
  for (const auto& s : m.slots())
    for (int o : s.obstacles)
      for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
        const auto& ob = m.scene().obstacles[o];
        if (dss::intersect(el[e].source->shape, X[s.link] * el[e].source->X_LS, ob.shape, ob.X_WO)
                .intersect)
          return true;
      }
  for (const auto& p : m.selfPairs()) {
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    for (int a = sa.first_element; a < sa.first_element + sa.num_elements; ++a)
      for (int b = sb.first_element; b < sb.first_element + sb.num_elements; ++b)
        if (dss::intersect(el[a].source->shape, X[sa.link] * el[a].source->X_LS,
                           el[b].source->shape, X[sb.link] * el[b].source->X_LS)
                .intersect)
          return true;
  }
  return false;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(wide_limits)

// Our arm in its shelf scene with revolute limits of +-1e300: states drawn with angles of every
// magnitude get the plain sweep's answer. The reference model keeps every obstacle (no
// pruning), builds no tables and no block balls; the checked one is built as the product is.
BOOST_AUTO_TEST_CASE(stages_change_no_answer_at_any_angle) {
  const dss::LoadedRobot robot = widened(dss_test::loadArm(), 1e300);
  const auto req = dss::loadPlanRequestYaml(dss_test::kArmDir + "/scenes/shelf_request.yaml");
  const dss::ModelSetup full =
      dss::setupModel(robot, dss::loadScene(dss_test::kArmDir + "/scenes/shelf.yaml"),
                      req.group_name, req.startState());
  dss::CollisionModelOptions plain_options;
  plain_options.prune_obstacles = false;
  plain_options.self_table_cells_1d = plain_options.self_table_cells_2d = 0;
  plain_options.pair_block_min_saving = 1e300;
  const std::vector<double> held = full.model->held();
  const dss::CollisionModel plain(robot.model, robot.srdf ? &*robot.srdf : nullptr,
                                  dss::loadScene(dss_test::kArmDir + "/scenes/shelf.yaml"),
                                  full.group_active, held, plain_options);
  const dss::DssChecker checker(full.model);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-M_PI, M_PI), expo(0, 300);
  int n = 0, hits = 0;
  for (int i = 0; i < 3000; ++i) {
    std::vector<double> q = held;
    for (int a : full.group_active) {
      // A third of the angles near the home turn, the others anywhere up to 1e300.
      const double turn = u(rng);
      q[a] = i % 3 == 0 ? turn : std::copysign(std::pow(10.0, expo(rng)), turn) + turn;
    }
    const dss::StateVerdict v = checker.check(q.data());
    BOOST_REQUIRE(v != dss::StateVerdict::kInvalidInput);
    const bool expected = plainSweepCollides(plain, q.data());
    BOOST_TEST((v == dss::StateVerdict::kColliding) == expected, "state " << i);
    ++n;
    hits += expected;
  }
  BOOST_TEST(hits > n / 10);
  BOOST_TEST(hits < n * 9 / 10);
}

// Two links on a base, 2 m apart, turning about their own axes with limits of +-1e300: they can
// never touch each other or the base, so no state collides.
BOOST_AUTO_TEST_CASE(links_that_never_meet_are_never_colliding) {
  const char* urdf = R"(<?xml version="1.0"?>
<robot name="apart">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="a"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.4 0.1 0.1"/></geometry></collision></link>
  <link name="b"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.4 0.1 0.1"/></geometry></collision></link>
  <joint name="ja" type="revolute"><parent link="base"/><child link="a"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit lower="-1e300" upper="1e300" effort="1" velocity="1"/></joint>
  <joint name="jb" type="revolute"><parent link="base"/><child link="b"/><origin xyz="0 0 3"/><axis xyz="0 0 1"/>
    <limit lower="-1e300" upper="1e300" effort="1" velocity="1"/></joint>
</robot>
)";
  const std::string path = dss_test::writeScratch("wide_limits", "apart.urdf", urdf);
  dss::LoadedRobot robot;
  robot.model = std::make_shared<const dss::RobotModel>(dss::loadUrdf(path));
  const dss::ModelSetup setup = dss::setupModel(robot, dss::Scene{}, "", {});
  const dss::DssChecker checker(setup.model);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> expo(-3, 300), sign(-1, 1);
  for (int i = 0; i < 2000; ++i) {
    std::vector<double> q(2);
    for (double& x : q) x = std::copysign(std::pow(10.0, expo(rng)), sign(rng));
    BOOST_TEST((checker.check(q.data()) == dss::StateVerdict::kFree),
               "state " << i << ": " << q[0] << ", " << q[1]);
  }
}

BOOST_AUTO_TEST_SUITE_END()
