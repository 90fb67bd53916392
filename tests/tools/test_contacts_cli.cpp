// The colliding pairs named where a user meets a colliding state: dss_check --contacts after
// each state it calls colliding, and dss_plan's warning about a start or goal state in
// collision.
#include <boost/test/unit_test.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "support/run_tool.h"
#include "support/temp_files.h"

namespace {

const std::string kRobots = std::string(DSS_SOURCE_DIR) + "/robots";

}  // namespace

BOOST_AUTO_TEST_SUITE(contacts_cli)

BOOST_AUTO_TEST_CASE(dss_check_names_the_pairs_of_each_colliding_state) {
  const std::string d = kRobots + "/dss_arm7";
  const std::vector<std::string> args = {"--robot",  d + "/dss_arm7.urdf",
                                         "--srdf",   d + "/dss_arm7.srdf",
                                         "--scene",  d + "/scenes/shelf.yaml",
                                         "--random", "300",
                                         "--repeat", "1"};
  const dss_test::ToolRun plain = dss_test::runTool("dss_check", args);
  std::vector<std::string> with_args = args;
  with_args.push_back("--contacts");
  const dss_test::ToolRun named = dss_test::runTool("dss_check", with_args);
  BOOST_TEST(plain.exit_code == 0, plain.err);
  BOOST_TEST(named.exit_code == 0, named.err);
  const std::vector<std::string> a = dss_test::outputLines(plain.out),
                                 b = dss_test::outputLines(named.out);
  BOOST_REQUIRE(a.size() == 300u);
  BOOST_REQUIRE(b.size() == 300u);
  int colliding = 0, scene = 0, self = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // The same verdict first; a colliding state's line then names its pairs after a tab.
    BOOST_TEST(b[i].substr(0, 1) == a[i], "state " << i);
    if (a[i] == "1") {
      BOOST_TEST(b[i] == "1");
      continue;
    }
    ++colliding;
    BOOST_TEST(b[i].rfind("0\tlink ", 0) == 0, b[i]);
    scene += b[i].find("with scene object '") != std::string::npos;
    self += b[i].find("with link ") != std::string::npos;
  }
  BOOST_TEST(colliding > 0);
  BOOST_TEST(scene > 0);
  BOOST_TEST(self > 0);
}

BOOST_AUTO_TEST_CASE(dss_plan_names_the_pairs_of_a_goal_in_collision) {
  // The free flyer's goal moved into the middle wall, below the window.
  const std::string d = kRobots + "/dss_free_flyer";
  std::ifstream in(d + "/scenes/window_request.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string request = text.str();
  for (const auto& [name, from, to] :
       {std::tuple<std::string, std::string, std::string>{"base/trans_x", "1.6", "0.0"},
        {"base/trans_y", "-0.8", "1.0"},
        {"base/trans_z", "1.2", "0.6"}}) {
    const std::string key = "joint_name: " + name + "\n        position: " + from;
    const std::size_t at = request.find(key);
    BOOST_REQUIRE_MESSAGE(at != std::string::npos, key);
    request.replace(at, key.size(), "joint_name: " + name + "\n        position: " + to);
  }
  const std::string file = dss_test::writeScratch("contacts_cli", "goal_in_wall.yaml", request);
  const dss_test::ToolRun r = dss_test::runTool(
      "dss_plan", {"--robot", d + "/dss_free_flyer.urdf", "--srdf", d + "/dss_free_flyer.srdf",
                   "--scene", d + "/scenes/window.yaml", "--request", file, "--time", "0.2"});
  BOOST_TEST(r.exit_code == 3, r.err);  // not solved
  BOOST_TEST(r.out.find("\"goal_invalid\":true") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("\"goal_invalid_why\":\"link body collision[") != std::string::npos, r.out);
  // With no valid goal state there is nothing to plan: the planner is not run (it would spend
  // the time limit sampling for a valid goal) and no state is checked.
  const nlohmann::json j = nlohmann::json::parse(dss_test::outputLines(r.out).at(0));
  BOOST_TEST(j["planned"] == false);
  BOOST_TEST(j["status"] == "Invalid goal");
  BOOST_TEST(j["validity_checks"] == 0);
  BOOST_TEST(j["planning_time_s"] == 0.0);
  BOOST_TEST(r.err.find("goal state invalid under dss: link body collision[") != std::string::npos,
             r.err);
  BOOST_TEST(r.err.find("with scene object 'middle_wall/") != std::string::npos, r.err);
  // Its boxes are primitives: no hull advice.
  BOOST_TEST(r.err.find("--meshes decomposed") == std::string::npos, r.err);
}

BOOST_AUTO_TEST_SUITE_END()
