// URDF and SRDF text nested deeper than any robot description: tinyxml (and urdfdom, inside)
// parse recursively, and 100 000 nested elements once overflowed the stack. The nesting is
// now bounded on the raw text before any parser sees it, with the file, line and column.
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "support/temp_files.h"
#include "support/thrown_message.h"

namespace fs = std::filesystem;

namespace {

std::string nested(const std::string& head, const std::string& tail, int depth) {
  std::string s = head;
  for (int i = 0; i < depth; ++i) s += "<a>";
  for (int i = 0; i < depth; ++i) s += "</a>";
  return s + tail;
}

const std::string kUrdfHead = "<?xml version=\"1.0\"?>\n<robot name=\"r\"><link name=\"base\">";

}  // namespace

BOOST_AUTO_TEST_SUITE(robot_xml_nesting)

// The reproducer: 100 000 nested elements in a URDF.
BOOST_AUTO_TEST_CASE(a_deeply_nested_urdf_is_refused_before_parsing) {
  const std::string text = nested(kUrdfHead, "</link></robot>\n", 100000);
  // robot and link are levels 1 and 2: the 255th <a> is level 257.
  const std::size_t column = kUrdfHead.size() - kUrdfHead.find('\n') - 1 + 254 * 3 + 1;
  const std::string expected = "deep.urdf:2:" + std::to_string(column) +
                               ": XML element nesting exceeds the limit of 256 "
                               "(RobotInputLimits::max_xml_depth; raise it with "
                               "LoadOptions::limits.max_xml_depth)";
  BOOST_TEST(dss_test::thrownMessage([&] { dss::loadUrdfString(text, "deep.urdf", "."); }) ==
             expected);
  // Through a file too.
  const fs::path file = dss_test::writeScratch("nesting", "deep.urdf", text);
  BOOST_TEST(dss_test::thrownMessage([&] { dss::loadUrdf(file.string()); })
                 .find(file.string() + ":2:" + std::to_string(column) +
                       ": XML element nesting exceeds the limit of 256") == 0u);
}

BOOST_AUTO_TEST_CASE(the_urdf_limit_is_exact_and_raised_by_the_options) {
  const std::string text = nested(kUrdfHead, "</link></robot>\n", 3);  // 5 levels
  dss::LoadOptions o;
  o.limits.max_xml_depth = 5;
  BOOST_TEST(dss::loadUrdfString(text, "ok.urdf", ".", o).links.size() == 1u);
  o.limits.max_xml_depth = 4;
  BOOST_TEST(dss_test::thrownMessage([&] {
               dss::loadUrdfString(text, "ok.urdf", ".", o);
             }).find("XML element nesting exceeds the limit of 4") != std::string::npos);
}

// The reproducer for SRDF: 100 000 nested elements.
BOOST_AUTO_TEST_CASE(a_deeply_nested_srdf_is_refused_before_parsing) {
  const std::string head = "<robot name=\"r\">\n<group name=\"g\">";
  const std::string text = nested(head, "</group></robot>\n", 100000);
  const std::size_t column = std::string("<group name=\"g\">").size() + 254 * 3 + 1;
  BOOST_TEST(dss_test::thrownMessage([&] { dss::parseSrdf(text, "deep.srdf"); }) ==
             "deep.srdf:2:" + std::to_string(column) +
                 ": XML element nesting exceeds the limit of 256 "
                 "(RobotInputLimits::max_xml_depth; raise it with the limits argument of "
                 "loadSrdf, parseSrdf or loadRobot)");
  dss::RobotInputLimits raised;
  raised.max_xml_depth = 5;
  const std::string shallow = nested(head, "</group></robot>\n", 3);
  BOOST_TEST(dss::parseSrdf(shallow, "ok.srdf", raised).groups.size() == 1u);
  raised.max_xml_depth = 4;
  BOOST_TEST(dss_test::thrownMessage([&] {
               dss::parseSrdf(shallow, "ok.srdf", raised);
             }).find("ok.srdf:2:") == 0u);
}

BOOST_AUTO_TEST_SUITE_END()
