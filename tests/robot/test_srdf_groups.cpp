// SRDF planning groups built from subgroups, from files we did not write: a diamond of
// subgroups (each level naming the next one twice) once took twice as long per level, a long
// chain of subgroups overflowed the stack, and a group that includes itself must be named.
// Each group is now expanded once, without recursion, with a bounded nesting depth.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "support/thrown_message.h"

namespace {

// base --j1 (revolute)--> l1 --j2 (revolute)--> l2
dss::RobotModel arm() {
  const char* const text = R"(<robot name="arm">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";
  return dss::loadUrdfString(text, "arm.urdf", ".");
}

// Groups g0 ... g<n>: g<i> names g<i+1> `copies` times; g<n> holds joint j2.
std::string chain(int n, int copies) {
  std::string s = "<robot name=\"arm\">\n";
  for (int i = 0; i < n; ++i) {
    s += "<group name=\"g" + std::to_string(i) + "\">";
    for (int c = 0; c < copies; ++c) s += "<group name=\"g" + std::to_string(i + 1) + "\"/>";
    s += "</group>\n";
  }
  s += "<group name=\"g" + std::to_string(n) + "\"><joint name=\"j2\"/></group>\n</robot>\n";
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(srdf_group_expansion)

// The reproducer, deeper: a diamond 60 levels deep has 2^60 paths to its bottom group.
// Expanding each group once makes it instantaneous; without that this test never ends.
BOOST_AUTO_TEST_CASE(a_deep_diamond_is_expanded_once_per_group) {
  const dss::RobotModel model = arm();
  const std::string text = chain(60, 2);
  BOOST_TEST(std::count(text.begin(), text.end(), '\n') == 63);
  const dss::Srdf srdf = dss::parseSrdf(text, "diamond.srdf");
  BOOST_TEST(dss::groupActiveJoints(model, srdf, "g0") == std::vector<int>{1});
  BOOST_TEST(dss::checkSrdfAgainstModel(model, srdf).empty());
}

BOOST_AUTO_TEST_CASE(a_group_that_includes_itself_is_named) {
  const dss::RobotModel model = arm();
  const std::string text = R"(<robot name="arm">
  <group name="g0"><group name="g1"/></group>
  <group name="g1"><joint name="j1"/><group name="g2"/></group>
  <group name="g2"><group name="g0"/></group>
  <group name="self"><group name="self"/></group>
</robot>)";
  const dss::Srdf srdf = dss::parseSrdf(text, "cycle.srdf");
  BOOST_TEST(dss_test::thrownMessage([&] { dss::groupActiveJoints(model, srdf, "g0"); }) ==
             "cycle.srdf: group 'g0' includes itself through its subgroups: 'g0' -> 'g1' -> "
             "'g2' -> 'g0'");
  BOOST_TEST(dss_test::thrownMessage([&] { dss::groupActiveJoints(model, srdf, "g2"); }) ==
             "cycle.srdf: group 'g2' includes itself through its subgroups: 'g2' -> 'g0' -> "
             "'g1' -> 'g2'");
  BOOST_TEST(dss_test::thrownMessage([&] { dss::groupActiveJoints(model, srdf, "self"); }) ==
             "cycle.srdf: group 'self' includes itself through its subgroups: 'self' -> 'self'");
  BOOST_TEST(dss::checkSrdfAgainstModel(model, srdf).size() == 4u);  // every group is in a cycle
}

// The reproducer: a chain of 100 000 subgroups overflowed the stack.
BOOST_AUTO_TEST_CASE(a_long_chain_is_bounded_by_the_depth_limit) {
  const dss::RobotModel model = arm();
  const std::string text = chain(100000, 1);
  const dss::Srdf srdf = dss::parseSrdf(text, "chain.srdf");
  BOOST_TEST(dss_test::thrownMessage([&] { dss::groupActiveJoints(model, srdf, "g0"); }) ==
             "chain.srdf: group 'g0': subgroups nest deeper than the limit of 64 ('g0' -> 'g1' "
             "-> 'g2' -> 'g3' -> ... (56 more) -> 'g60' -> 'g61' -> 'g62' -> 'g63'; "
             "RobotInputLimits::max_group_depth; raise it with the limits argument of loadSrdf, "
             "parseSrdf or loadRobot)");
  // Raised, the whole chain expands without recursion.
  dss::RobotInputLimits raised;
  raised.max_group_depth = 100001;
  const dss::Srdf deep = dss::parseSrdf(text, "chain.srdf", raised);
  BOOST_TEST(dss::groupActiveJoints(model, deep, "g0") == std::vector<int>{1});
  // The limit is exact: 65 groups nest 65 deep.
  raised.max_group_depth = 65;
  BOOST_TEST(dss::groupActiveJoints(model, dss::parseSrdf(chain(64, 1), "c.srdf", raised), "g0") ==
             std::vector<int>{1});
  raised.max_group_depth = 64;
  BOOST_TEST(dss_test::thrownMessage([&] {
               dss::groupActiveJoints(model, dss::parseSrdf(chain(64, 1), "c.srdf", raised), "g0");
             }).find("nest deeper than the limit of 64") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(missing_subgroups_and_joints_are_named) {
  const dss::RobotModel model = arm();
  const dss::Srdf srdf = dss::parseSrdf(R"(<robot name="arm">
  <group name="a"><group name="nope"/></group>
  <group name="b"><joint name="j9"/></group>
  <group name="c"><group name="b"/></group>
</robot>)",
                                        "missing.srdf");
  BOOST_TEST(dss_test::thrownMessage([&] { dss::groupActiveJoints(model, srdf, "a"); }) ==
             "missing.srdf: no group 'nope' (a subgroup of group 'a')");
  BOOST_TEST(dss_test::thrownMessage([&] { dss::groupActiveJoints(model, srdf, "c"); }) ==
             "missing.srdf: group 'b' names joint 'j9' that robot 'arm' lacks");
  BOOST_TEST(dss_test::thrownMessage([&] { dss::groupActiveJoints(model, srdf, "zz"); }) ==
             "missing.srdf: no group 'zz'");
}

BOOST_AUTO_TEST_CASE(a_group_state_joint_without_value_is_a_warning) {
  const dss::Srdf srdf = dss::parseSrdf(R"(<robot name="arm">
  <group name="g"><joint name="j1"/></group>
  <group_state name="home" group="g">
    <joint name="j1"/>
  </group_state>
</robot>)",
                                        "state.srdf");
  BOOST_REQUIRE(srdf.warnings.size() == 1u);
  BOOST_TEST(srdf.warnings[0] ==
             "state.srdf:4: group_state 'home' joint 'j1' has no value: the joint keeps its "
             "other value");
}

BOOST_AUTO_TEST_SUITE_END()
