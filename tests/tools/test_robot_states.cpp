// Whole robot states between the executables: dss_plan --path writes every joint (the group's,
// the held ones, mimic joints), and dss_check --states reads such a file back, joints outside
// the group included, and answers every row as the planner's checker did.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_tool.h"
#include "support/shared_data.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;

namespace {
const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7/";
const std::string kPanda = std::string(DSS_SHARED_DIR) + "/robots/panda/";
const std::string kMbm = std::string(DSS_SHARED_DIR) + "/scenes/mbm_panda/box/";

fs::path scratch(const std::string& name) { return dss_test::scratchDir("robot_states") / name; }

}  // namespace

BOOST_AUTO_TEST_SUITE(robot_states)

BOOST_AUTO_TEST_CASE(a_planned_path_reads_back_into_dss_check) {
  const std::string path = scratch("arm_path.csv").string();
  const auto plan = dss_test::runTool("dss_plan", {"--path", path});
  BOOST_REQUIRE_MESSAGE(plan.exit_code == 0, plan.err);
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  BOOST_TEST(header == "joint1,joint2,joint3,joint4,joint5,joint6,joint7");
  const auto check = dss_test::runTool(
      "dss_check", {"--robot", kArm + "dss_arm7.urdf", "--srdf", kArm + "dss_arm7.srdf", "--scene",
                    kArm + "scenes/shelf.yaml", "--states", path, "--checker", "dss,fcl-hull"});
  BOOST_REQUIRE_MESSAGE(check.exit_code == 0, check.err);
  const auto answers = dss_test::outputLines(check.out);
  BOOST_TEST(answers.size() >= 2u);
  for (const std::string& a : answers)
    BOOST_TEST(a == "1");  // every waypoint of a solution is free
  BOOST_TEST(check.err.find("\"disagreements\":0") != std::string::npos, check.err);
}

// The Panda with its fingers held outside the arm group (and above their URDF limit, as
// MotionBenchMaker starts them): the path file carries both finger columns (one a mimic), and
// dss_check takes them as the rows' values.
BOOST_AUTO_TEST_CASE(full_panda_states_with_finger_columns, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::exists(kPanda + "panda.urdf") && fs::exists(kMbm + "request0001.yaml"));
  const std::string path = scratch("panda_path.csv").string();
  const auto plan =
      dss_test::runTool("dss_plan", {"--robot", kPanda + "panda.urdf", "--srdf",
                                     kPanda + "panda.srdf", "--scene", kMbm + "scene0001.yaml",
                                     "--request", kMbm + "request0001.yaml", "--path", path});
  BOOST_REQUIRE_MESSAGE(plan.exit_code == 0, plan.err);
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  BOOST_TEST(header.find("panda_finger_joint1") != std::string::npos, header);
  BOOST_TEST(header.find("panda_finger_joint2") != std::string::npos, header);
  const std::vector<std::string> args = {
      "--robot",   kPanda + "panda.urdf",   "--srdf",   kPanda + "panda.srdf",
      "--scene",   kMbm + "scene0001.yaml", "--states", path,
      "--checker", "dss,fcl-mesh"};
  const auto check = dss_test::runTool("dss_check", args);
  BOOST_REQUIRE_MESSAGE(check.exit_code == 0, check.err);
  for (const std::string& a : dss_test::outputLines(check.out)) BOOST_TEST(a == "1");
  BOOST_TEST(check.err.find("panda_finger_joint1 has values in") != std::string::npos, check.err);
  BOOST_TEST(check.err.find("\"disagreements\":0") != std::string::npos, check.err);

  // A mimic finger that disagrees with its leader is refused with the row's line.
  std::ifstream src(path);
  std::ostringstream bad;
  std::string line;
  for (int k = 0; std::getline(src, line); ++k) {
    if (k == 2) line = line.substr(0, line.rfind(',')) + ",0.01";
    bad << line << "\n";
  }
  const std::string bad_path = scratch("panda_bad.csv").string();
  std::ofstream(bad_path) << bad.str();
  std::vector<std::string> bad_args = args;
  bad_args[7] = bad_path;
  const auto refused = dss_test::runTool("dss_check", bad_args);
  BOOST_TEST(refused.exit_code == 1);
  BOOST_TEST(refused.err.find("panda_bad.csv:3") != std::string::npos, refused.err);
  BOOST_TEST(refused.err.find("mimic joint 'panda_finger_joint2'") != std::string::npos,
             refused.err);
}

BOOST_AUTO_TEST_SUITE_END()
