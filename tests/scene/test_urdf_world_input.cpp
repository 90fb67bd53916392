// A URDF read as a world from a file we did not write: joints that do not form a tree (a link
// with two parents once sent the pose walk into endless recursion; links in a cycle detached
// from the root were dropped or ended in a bare map::at), a long chain of links (walked
// without recursion), nesting that would overflow the recursive XML parsers, and mesh scales
// that collapse the mesh.
#include <boost/test/unit_test.hpp>
#include <string>

#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"
#include "dss/scene/urdf_world.h"
#include "scene/scene_test_util.h"

using namespace dss_test;

namespace {

const char* const kBox = "<collision><geometry><box size=\"1 1 1\"/></geometry></collision>";

std::string worldError(const std::string& name, const std::string& text,
                       const dss::SceneLoadOptions& options = {}) {
  const std::string path = writeScratch(name, text);
  const std::string m = thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(path, options); });
  // Every message starts with the file.
  BOOST_TEST(m.rfind(path + ":", 0) == 0u, m);
  return m.substr(std::min(m.size(), path.size()));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(urdf_world_input)

// The reproducer: link 'a' is the child of j1 and of j3 (a cycle a -> b -> a below the root).
BOOST_AUTO_TEST_CASE(a_link_with_two_parents_is_an_error) {
  const std::string text = std::string("<robot name=\"w\">\n") +
                           "  <link name=\"base\"/>\n"
                           "  <link name=\"a\">" +
                           kBox +
                           "</link>\n"
                           "  <link name=\"b\"/>\n"
                           "  <joint name=\"j1\" type=\"fixed\"><parent link=\"base\"/><child "
                           "link=\"a\"/></joint>\n"
                           "  <joint name=\"j2\" type=\"fixed\"><parent link=\"a\"/><child "
                           "link=\"b\"/></joint>\n"
                           "  <joint name=\"j3\" type=\"fixed\"><parent link=\"b\"/><child "
                           "link=\"a\"/></joint>\n"
                           "</robot>\n";
  BOOST_TEST(worldError("two_parents.urdf", text) ==
             ": link 'a' (line 3) is the child of 2 joints, 'j1' (line 5) and 'j3' (line 7): a "
             "URDF must be a tree, each link with at most one parent joint (this is a closed "
             "kinematic chain or a cycle)");
}

// The reproducer: links c and d are each other's parent, apart from the root.
BOOST_AUTO_TEST_CASE(a_detached_cycle_is_an_error_naming_links_and_joints) {
  const std::string text = std::string("<robot name=\"w\">\n") + "  <link name=\"base\">" + kBox +
                           "</link>\n"
                           "  <link name=\"c\">" +
                           kBox +
                           "</link>\n"
                           "  <link name=\"d\"/>\n"
                           "  <joint name=\"jc\" type=\"fixed\"><parent link=\"d\"/><child "
                           "link=\"c\"/></joint>\n"
                           "  <joint name=\"jd\" type=\"fixed\"><parent link=\"c\"/><child "
                           "link=\"d\"/></joint>\n"
                           "</robot>\n";
  BOOST_TEST(worldError("detached.urdf", text) ==
             ": links 'c' (line 3) and 'd' (line 4) and joints 'jc' (line 5) and 'jd' (line 6) "
             "form a cycle that is not connected to the root link 'base'; 2 link(s) cannot be "
             "reached from the root: 'c' (line 3) and 'd' (line 4)");
  // A link hanging from the detached cycle is counted among the unreachable ones.
  std::string hanging = text;
  hanging.insert(hanging.find("</robot>"),
                 "  <link name=\"e\"/>\n  <joint name=\"je\" type=\"fixed\"><parent link=\"d\"/>"
                 "<child link=\"e\"/></joint>\n");
  BOOST_TEST(contains(worldError("hanging.urdf", hanging),
                      "3 link(s) cannot be reached from the root: 'c' (line 3), 'd' (line 4) and "
                      "'e' (line 7)"));
}

BOOST_AUTO_TEST_CASE(a_link_apart_from_the_tree_is_an_error) {
  const std::string text = std::string("<robot name=\"w\">\n") + "  <link name=\"base\">" + kBox +
                           "</link>\n  <link name=\"shelf\">" + kBox + "</link>\n</robot>\n";
  BOOST_TEST(worldError("apart.urdf", text) ==
             ": 2 links have no parent joint, 'base' (line 2) and 'shelf' (line 3): a URDF must "
             "be one tree with one root link (the others are not connected to it)");
}

BOOST_AUTO_TEST_CASE(a_long_chain_is_walked_without_recursion) {
  const int n = 20000;
  std::string text = "<robot name=\"chain\">\n<link name=\"l0\"/>\n";
  for (int i = 1; i <= n; ++i)
    text += "<link name=\"l" + std::to_string(i) + "\"/><joint name=\"j" + std::to_string(i) +
            "\" type=\"fixed\"><origin xyz=\"0.001 0 0\"/><parent link=\"l" +
            std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) + "\"/></joint>\n";
  // The last link carries a box: its pose sums every joint of the chain.
  text.replace(text.find("<link name=\"l" + std::to_string(n) + "\"/>"),
               ("<link name=\"l" + std::to_string(n) + "\"/>").size(),
               "<link name=\"l" + std::to_string(n) + "\">" + kBox + "</link>");
  text += "</robot>\n";
  const dss::Scene s = dss::loadUrdfWorld(writeScratch("chain.urdf", text));
  BOOST_REQUIRE(s.obstacles.size() == 1u);
  BOOST_TEST(std::abs(s.obstacles[0].X_WO.translation().x() - 0.001 * n) < 1e-6);
}

// The reproducer: 100 000 nested elements overflowed the stack of tinyxml's recursive parser.
BOOST_AUTO_TEST_CASE(deep_nesting_is_refused_before_parsing) {
  const std::string head = "<robot name=\"w\">";
  std::string text = head;
  for (int i = 0; i < 100000; ++i) text += "<a>";
  for (int i = 0; i < 100000; ++i) text += "</a>";
  text += "</robot>\n";
  // The robot element is level 1: the 256th <a> is level 257.
  const std::size_t column = head.size() + 255 * 3 + 1;
  BOOST_TEST(worldError("deep.urdf", text) == ":1:" + std::to_string(column) +
                                                  ": XML element nesting exceeds the limit of 256 "
                                                  "(SceneInputLimits::max_xml_depth; raise it with "
                                                  "SceneLoadOptions::limits.max_xml_depth)");
  // Exactly at the limit the text goes to the parser: robot, link, a and the empty a are
  // four levels.
  const std::string nested = "<link name=\"l\"><a><a/></a></link>";
  const std::string path = writeScratch("deep_ok.urdf", head + nested + "</robot>\n");
  dss::SceneLoadOptions o;
  o.limits.max_xml_depth = 4;
  BOOST_TEST(dss::loadUrdfWorld(path, o).obstacles.empty());
  o.limits.max_xml_depth = 3;
  BOOST_TEST(contains(thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(path, o); }),
                      ":1:" + std::to_string(head.size() + nested.find("<a/>") + 1) +
                          ": XML element nesting exceeds the limit of 3"));
  // Comments, CDATA, declarations and quoted '>' do not nest: robot and link are two levels.
  const std::string quiet =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE robot>\n<robot name=\"w\"><!-- <a><a><a> -->"
      "<![CDATA[<a><a><a>]]><link name=\"x>y\" /></robot>\n";
  o.limits.max_xml_depth = 2;
  BOOST_TEST(dss::loadUrdfWorld(writeScratch("quiet.urdf", quiet), o).obstacles.empty());
}

BOOST_AUTO_TEST_CASE(zero_mesh_scales_are_refused) {
  writeScratch("mesh/tetra.stl",
               "solid t\nfacet normal 0 0 -1\n outer loop\n vertex 0 0 0\n vertex 0 0.1 0\n "
               "vertex 0.1 0 0\n endloop\nendfacet\nfacet normal 0 -1 0\n outer loop\n vertex 0 0 "
               "0\n vertex 0.1 0 0\n vertex 0 0 0.1\n endloop\nendfacet\nendsolid t\n");
  auto world = [](const std::string& scale) {
    return "<robot name=\"w\">\n  <link name=\"base\"><collision><geometry><mesh "
           "filename=\"tetra.stl\" scale=\"" +
           scale + "\"/></geometry></collision></link>\n</robot>\n";
  };
  BOOST_TEST(worldError("mesh/zero.urdf", world("1 0 1")) ==
             ": link 'base' collision 0: mesh scale component y is 0 (scale \"1 0 1\"): it must "
             "be finite and non-zero, or the mesh collapses");
  // A negative component mirrors the mesh and is accepted.
  const dss::Scene s = dss::loadUrdfWorld(writeScratch("mesh/mirror.urdf", world("-1 1 1")));
  BOOST_REQUIRE(s.obstacles.size() == 1u);
  const auto& hull = std::get<dss::ConvexHull>(s.obstacles[0].shape);
  BOOST_TEST(hull.support(Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d::Zero()).x() ==
             -0.1f);  // STL stores floats
}

// tinyxml read past the buffer on a truncated UTF-8 character (see tests/robot/test_xml_utf8.cpp).
BOOST_AUTO_TEST_CASE(a_world_that_is_not_utf8_is_refused) {
  BOOST_TEST(worldError("latin1.urdf", "<robot name=\"w\">\n<link name=\"\xE1") ==
             ":2:13: the text is not UTF-8 (byte 0xE1); XML files are read as UTF-8");
}

BOOST_AUTO_TEST_SUITE_END()
