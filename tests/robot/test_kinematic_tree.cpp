// URDF joints that do not form a tree, which urdfdom accepts: a link that is the child of two
// joints (the robot loader once walked the cycle a -> b -> a forever, allocating as it went)
// and links in a cycle apart from the root (once dropped without a word). Both are errors
// naming the file, the links and the joints, with their lines.
#include <boost/test/unit_test.hpp>
#include <stdexcept>
#include <string>

#include "dss/robot/urdf_loader.h"
#include "support/thrown_message.h"

namespace {

const char* const kBox = "<collision><geometry><box size=\"1 1 1\"/></geometry></collision>";

std::string joint(const std::string& name, const std::string& parent, const std::string& child,
                  const std::string& type = "fixed") {
  std::string limit = type == "revolute"
                          ? "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" "
                            "velocity=\"1\"/>"
                          : "";
  return "  <joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/>" + limit + "</joint>\n";
}

std::string loadError(const std::string& text) {
  return dss_test::thrownMessage([&] { dss::loadUrdfString(text, "tree.urdf", "."); });
}

}  // namespace

BOOST_AUTO_TEST_SUITE(urdf_kinematic_tree)

// The reproducer: link 'a' is the child of j1 and of j3.
BOOST_AUTO_TEST_CASE(a_link_with_two_parent_joints_is_an_error) {
  const std::string text = std::string("<robot name=\"r\">\n") +
                           "  <link name=\"base\"/>\n"
                           "  <link name=\"a\">" +
                           kBox +
                           "</link>\n"
                           "  <link name=\"b\"/>\n" +
                           joint("j1", "base", "a", "revolute") + joint("j2", "a", "b") +
                           joint("j3", "b", "a") + "</robot>\n";
  BOOST_TEST(loadError(text) ==
             "tree.urdf: link 'a' (line 3) is the child of 2 joints, 'j1' (line 5) and 'j3' "
             "(line 7): a URDF must be a tree, each link with at most one parent joint (this is "
             "a closed kinematic chain or a cycle)");
}

BOOST_AUTO_TEST_CASE(a_closed_chain_is_an_error) {
  // Two branches from the root meet again at 'c' (no cycle in the directed sense).
  const std::string text = std::string("<robot name=\"r\">\n") +
                           "  <link name=\"base\"/>\n  <link name=\"a\"/>\n  <link name=\"b\"/>\n"
                           "  <link name=\"c\"/>\n" +
                           joint("ja", "base", "a") + joint("jb", "base", "b") +
                           joint("jc1", "a", "c") + joint("jc2", "b", "c") + "</robot>\n";
  BOOST_TEST(loadError(text) ==
             "tree.urdf: link 'c' (line 5) is the child of 2 joints, 'jc1' (line 8) and 'jc2' "
             "(line 9): a URDF must be a tree, each link with at most one parent joint (this is "
             "a closed kinematic chain or a cycle)");
}

// The reproducer: links c and d are each other's parent; the root never reaches them.
BOOST_AUTO_TEST_CASE(a_detached_cycle_is_an_error) {
  const std::string text = std::string("<robot name=\"r\">\n") + "  <link name=\"base\">" + kBox +
                           "</link>\n"
                           "  <link name=\"c\">" +
                           kBox +
                           "</link>\n"
                           "  <link name=\"d\"/>\n" +
                           joint("jc", "d", "c", "revolute") + joint("jd", "c", "d") + "</robot>\n";
  BOOST_TEST(loadError(text) ==
             "tree.urdf: links 'c' (line 3) and 'd' (line 4) and joints 'jc' (line 5) and 'jd' "
             "(line 6) form a cycle that is not connected to the root link 'base'; 2 link(s) "
             "cannot be reached from the root: 'c' (line 3) and 'd' (line 4)");
}

BOOST_AUTO_TEST_CASE(a_cycle_through_every_link_and_a_second_root_are_errors) {
  // No link lacks a parent: urdfdom would only say that it found no root.
  const std::string cycle = std::string("<robot name=\"r\">\n") + "  <link name=\"a\">" + kBox +
                            "</link>\n  <link name=\"b\"/>\n" + joint("ja", "a", "b") +
                            joint("jb", "b", "a") + "</robot>\n";
  BOOST_TEST(loadError(cycle) ==
             "tree.urdf: links 'a' (line 2) and 'b' (line 3) and joints 'jb' (line 5) and 'ja' "
             "(line 4) form a cycle, and every link has a parent joint: a URDF must be a tree "
             "with one root link");
  // A link that no joint names is a second root, not connected to the first.
  const std::string apart = std::string("<robot name=\"r\">\n") +
                            "  <link name=\"base\"/>\n  <link name=\"a\"/>\n"
                            "  <link name=\"x\">" +
                            kBox + "</link>\n" + joint("ja", "base", "a") + "</robot>\n";
  BOOST_TEST(loadError(apart) ==
             "tree.urdf: 2 links have no parent joint, 'base' (line 2) and 'x' (line 4): a URDF "
             "must be one tree with one root link (the others are not connected to it)");
}

BOOST_AUTO_TEST_CASE(long_cycles_are_named_briefly) {
  // A detached cycle of 100 links: the message names 8 of them and counts the rest.
  std::string text = "<robot name=\"r\">\n  <link name=\"base\"/>\n";
  for (int i = 0; i < 100; ++i) text += "  <link name=\"c" + std::to_string(100 + i) + "\"/>\n";
  for (int i = 0; i < 100; ++i)
    text += joint("j" + std::to_string(100 + i), "c" + std::to_string(100 + i),
                  "c" + std::to_string(100 + (i + 1) % 100));
  text += "</robot>\n";
  const std::string m = loadError(text);
  BOOST_TEST(
      m.find("form a cycle that is not connected to the root link 'base'") != std::string::npos, m);
  BOOST_TEST(m.find("and 92 more") != std::string::npos, m);
  BOOST_TEST(m.size() < 1000u, m);
}

BOOST_AUTO_TEST_CASE(a_tree_still_loads_in_depth_first_order) {
  const std::string text = std::string("<robot name=\"r\">\n") +
                           "  <link name=\"base\"/>\n  <link name=\"a\"/>\n  <link name=\"b\"/>\n"
                           "  <link name=\"c\"/>\n" +
                           joint("ja", "base", "a", "revolute") + joint("jb", "base", "b") +
                           joint("jc", "a", "c") + "</robot>\n";
  const dss::RobotModel m = dss::loadUrdfString(text, "tree.urdf", ".");
  BOOST_REQUIRE(m.links.size() == 4u);
  BOOST_TEST(m.links[0].name == "base");
  BOOST_TEST(m.links[1].name == "a");
  BOOST_TEST(m.links[2].name == "c");
  BOOST_TEST(m.links[3].name == "b");
}

BOOST_AUTO_TEST_SUITE_END()
