// Group state spaces: bounded joints as a real-vector space with the URDF limits, continuous
// joints as SO2 parts of a compound space, values mapped by joint name; held joints outside
// their limits are reported. (The collision model's pairs and pruning: tests/checker.)
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <boost/test/unit_test.hpp>
#include <cmath>

#include "dss/planning/planning_problem.h"
#include "dss/robot/urdf_loader.h"

namespace ob = ompl::base;

namespace {
const std::string kRobots = std::string(DSS_SOURCE_DIR) + "/robots";
}

BOOST_AUTO_TEST_SUITE(group_state_space)

BOOST_AUTO_TEST_CASE(arm_group_is_a_bounded_real_vector_space) {
  const auto r =
      dss::loadRobot(kRobots + "/dss_arm7/dss_arm7.urdf", kRobots + "/dss_arm7/dss_arm7.srdf");
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
  // A turntable (continuous), a slide (prismatic) and a wrist (continuous).
  const char* urdf = R"(<robot name="t"><link name="w"/>
<link name="a"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
<link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
<link name="c"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
<joint name="turn" type="continuous"><parent link="w"/><child link="a"/><axis xyz="0 0 1"/></joint>
<joint name="slide" type="prismatic"><parent link="a"/><child link="b"/><origin xyz="0.5 0 0"/>
  <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
<joint name="wrist" type="continuous"><parent link="b"/><child link="c"/><origin xyz="0.3 0 0"/><axis xyz="0 1 0"/></joint>
</robot>)";
  dss::LoadedRobot r;
  r.model = std::make_shared<const dss::RobotModel>(dss::loadUrdfString(urdf, "t.urdf", "."));
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
  for (std::size_t i = 0; i < g.size(); ++i)
    g[i] = 0.5 * (p.map->lower(i) + p.map->upper(i)) + 0.01;
  ob::ScopedState<> s(p.map->space());
  p.map->fromGroupValues(g.data(), s.get());
  std::vector<double> back(g.size());
  p.map->toGroupValues(s.get(), back.data());
  for (std::size_t i = 0; i < g.size(); ++i) BOOST_TEST(std::abs(back[i] - g[i]) < 1e-12);
  auto c = dss::makeValidityChecker(p, {"dss"});
  (void)c->isValid(s.get());
  BOOST_TEST(c->counters().checks == 1u);
}

BOOST_AUTO_TEST_CASE(held_joint_outside_limits_is_reported) {
  const auto r =
      dss::loadRobot(kRobots + "/dss_arm7/dss_arm7.urdf", kRobots + "/dss_arm7/dss_arm7.srdf");
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

BOOST_AUTO_TEST_SUITE_END()
