// Group state spaces: bounded joints as a real-vector space with the URDF limits, continuous
// joints as SO2 parts of a compound space, values mapped by joint name; held joints outside
// their limits are reported; the model's pairs and pruning on our own robots.
#include <cmath>
#include <random>

#include <boost/test/unit_test.hpp>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "dss/planning/planning_problem.h"
#include "dss/scene/scene_loader.h"

namespace ob = ompl::base;

namespace {
const std::string kRobots = std::string(DSS_SOURCE_DIR) + "/robots";
}

BOOST_AUTO_TEST_CASE(arm_group_is_a_bounded_real_vector_space) {
  const auto r = dss::loadRobot(kRobots + "/dss_arm7/dss_arm7.urdf", kRobots + "/dss_arm7/dss_arm7.srdf");
  dss::Problem p = dss::makeProblem(r, dss::Scene{}, "arm", {});
  BOOST_TEST(p.map->dimension() == 7u);
  auto rv = std::dynamic_pointer_cast<ob::RealVectorStateSpace>(p.map->space());
  BOOST_REQUIRE(rv);
  for (std::size_t i = 0; i < 7; ++i) {
    const auto& j = r.model->joints[r.model->jointIndexOrThrow(p.map->jointNames()[i])];
    BOOST_TEST(rv->getBounds().low[i] == j.limits.lower);
    BOOST_TEST(rv->getBounds().high[i] == j.limits.upper);
  }
  // By-name mapping: state -> joint vector lands on the right active indices.
  std::map<std::string, double> values;
  for (std::size_t i = 0; i < 7; ++i) values[p.map->jointNames()[i]] = 0.01 * double(i + 1);
  const auto g = p.map->groupValues(values);
  ob::ScopedState<> s(p.map->space());
  p.map->fromGroupValues(g.data(), s.get());
  std::vector<double> q(r.model->numActiveJoints());
  BOOST_TEST(p.map->toJoints(s.get(), q.data()));
  for (std::size_t i = 0; i < 7; ++i) {
    const int a = r.model->joints[r.model->jointIndexOrThrow(p.map->jointNames()[i])].active_index;
    BOOST_TEST(q[a] == 0.01 * double(i + 1));
  }
}

BOOST_AUTO_TEST_CASE(continuous_joints_become_so2_parts) {
  const std::string dir = kRobots + "/dss_mobile_base";
  const auto r = dss::loadRobot(dir + "/dss_mobile_base.urdf", dir + "/dss_mobile_base.srdf");
  dss::Problem p = dss::makeProblem(r, dss::Scene{}, "", {});
  int continuous = 0;
  for (int a : p.map->groupActive())
    continuous += r.model->joints[r.model->active_joints[a]].type == dss::JointType::kContinuous;
  BOOST_REQUIRE(continuous > 0);
  auto compound = std::dynamic_pointer_cast<ob::CompoundStateSpace>(p.map->space());
  BOOST_REQUIRE(compound);
  int so2 = 0;
  for (unsigned k = 0; k < compound->getSubspaceCount(); ++k)
    so2 += compound->getSubspace(k)->getType() == ob::STATE_SPACE_SO2;
  BOOST_TEST(so2 == continuous);
  // Round trip with a wrapped angle.
  std::vector<double> g(p.map->dimension());
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = 0.5 * (p.map->lower(i) + p.map->upper(i)) + 0.01;
  ob::ScopedState<> s(p.map->space());
  p.map->fromGroupValues(g.data(), s.get());
  std::vector<double> back(g.size());
  p.map->toGroupValues(s.get(), back.data());
  for (std::size_t i = 0; i < g.size(); ++i) BOOST_TEST(std::abs(back[i] - g[i]) < 1e-12);
  auto c = dss::makeChecker(p, {"dss"});
  (void)c->isValid(s.get());
  BOOST_TEST(c->counters().checks == 1u);
}

BOOST_AUTO_TEST_CASE(held_joint_outside_limits_is_reported) {
  const auto r = dss::loadRobot(kRobots + "/dss_arm7/dss_arm7.urdf", kRobots + "/dss_arm7/dss_arm7.srdf");
  // Without an SRDF the group is every active joint: nothing is held, nothing to report.
  dss::LoadedRobot bare{r.model, std::nullopt};
  std::map<std::string, double> start;
  for (const auto& n : r.model->activeJointNames()) start[n] = 0.0;
  dss::Problem p = dss::makeProblem(bare, dss::Scene{}, "", start);
  BOOST_TEST(p.warnings.empty());
  // A group of joints 1 and 2 holding joint 0 beyond its upper limit: one warning naming it.
  std::vector<double> held(r.model->numActiveJoints(), 0.0);
  const auto& j0 = r.model->joints[r.model->active_joints[0]];
  if (j0.limits.has_position_limits) {
    held[0] = j0.limits.upper + 1.0;
    dss::GroupStateMap m(r.model, {1, 2}, held);
    BOOST_REQUIRE(m.warnings.size() == 1u);
    BOOST_TEST(m.warnings[0].find(j0.name) != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(shelf_model_pairs_and_pruning) {
  const std::string dir = kRobots + "/dss_arm7";
  const auto r = dss::loadRobot(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf");
  dss::Scene scene = dss::loadScene(dir + "/scenes/shelf.yaml");
  // A far-away obstacle that no link can reach is pruned.
  dss::Obstacle far = scene.obstacles.at(0);
  far.name = far.object_id = "far_away";
  far.X_WO.translation() += Eigen::Vector3d(50, 0, 0);
  far.X_FO = far.X_WO;
  scene.obstacles.push_back(far);
  const std::size_t n = scene.obstacles.size();
  dss::Problem p = dss::makeProblem(r, scene, "arm", {});
  const auto& m = *p.model;
  BOOST_TEST_MESSAGE(m.summary());
  BOOST_TEST(m.obstaclesBefore() == n);
  BOOST_TEST(m.scene().obstacles.size() == n - 1);
  for (const auto& o : m.scene().obstacles) BOOST_TEST(o.name != "far_away");
  // Non-moving links are never checked against the scene; every self pair has a moving link.
  for (const auto& s : m.slots())
    if (!s.moves) BOOST_TEST(s.obstacles.empty());
  for (const auto& sp : m.selfPairs()) BOOST_TEST((m.slots()[sp.a].moves || m.slots()[sp.b].moves));
  // Reach balls hold every element at random states.
  std::vector<double> q = m.held();
  std::mt19937_64 rng(5);
  for (int k = 0; k < 200; ++k) {
    for (std::size_t i = 0; i < p.map->dimension(); ++i)
      q[p.map->groupActive()[i]] = std::uniform_real_distribution<double>(p.map->lower(i), p.map->upper(i))(rng);
    const auto X = m.kinematics().linkPoses(q);
    for (const auto& s : m.slots()) {
      if (!s.moves) continue;
      BOOST_TEST((X[s.link] * s.center_L - s.reach_center_W).norm() + s.radius <= s.reach_radius + 1e-9);
    }
  }
}
