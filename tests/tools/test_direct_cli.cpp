// dss_plan --direct as a user runs it, on our arm by its shelf: a goal the start sees is
// reached by the straight motion alone (a path of two states, one motion check, "direct":
// true); the shelf problem's own goal, which it does not see, is planned by RRTConnect after
// the attempt. Without --direct the JSON has no "direct".
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/run_tool.h"
#include "support/temp_files.h"

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";

// The shelf request with its goal moved to the start turned by 0.1 rad at the first joint.
const char* kNearRequest = R"(group_name: arm
start_state:
  joint_state:
    name: [joint1, joint2, joint3, joint4, joint5, joint6, joint7]
    position: [0.19, 0.5783, 0, -1.6413, 0, -0.6488, 0.4]
goal_constraints:
  - joint_constraints:
      - {joint_name: joint1, position: 0.29}
      - {joint_name: joint2, position: 0.5783}
      - {joint_name: joint3, position: 0}
      - {joint_name: joint4, position: -1.6413}
      - {joint_name: joint5, position: 0}
      - {joint_name: joint6, position: -0.6488}
      - {joint_name: joint7, position: 0.4}
)";

nlohmann::json plan(const std::string& request, const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"--robot",   kArm + "/dss_arm7.urdf",
                                   "--srdf",    kArm + "/dss_arm7.srdf",
                                   "--scene",   kArm + "/scenes/shelf.yaml",
                                   "--request", request,
                                   "--seed",    "1"};
  args.insert(args.end(), extra.begin(), extra.end());
  const dss_test::ToolRun r = dss_test::runTool("dss_plan", args);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  return nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(direct_cli)

BOOST_AUTO_TEST_CASE(a_goal_in_sight_is_the_straight_motion) {
  const std::string near = dss_test::writeScratch("direct_cli", "near_request.yaml", kNearRequest);
  const nlohmann::json j = plan(near, {"--direct"});
  BOOST_TEST(j.at("solved").get<bool>());
  BOOST_TEST(j.at("direct").get<bool>());
  BOOST_TEST(j.at("path_states").get<int>() == 2);
  BOOST_TEST(j.at("motion_checks").get<int>() == 1);
  BOOST_TEST(std::abs(j.at("path_length").get<double>() - 0.1) < 1e-9);
  const nlohmann::json plain = plan(near, {});
  BOOST_TEST(plain.at("solved").get<bool>());
  BOOST_TEST(!plain.contains("direct"));
}

BOOST_AUTO_TEST_CASE(a_goal_out_of_sight_is_planned) {
  const std::string request = kArm + "/scenes/shelf_request.yaml";
  const nlohmann::json j = plan(request, {"--direct"});
  const nlohmann::json plain = plan(request, {});
  BOOST_TEST(j.at("solved").get<bool>());
  BOOST_TEST(!j.at("direct").get<bool>());
  // RRTConnect grows the same trees after the attempt: the same path, more checks.
  BOOST_TEST(j.at("path_length").get<double>() == plain.at("path_length").get<double>());
  BOOST_TEST(j.at("validity_checks").get<long>() > plain.at("validity_checks").get<long>());
  BOOST_TEST(j.at("motion_checks").get<long>() == plain.at("motion_checks").get<long>() + 1);
}

BOOST_AUTO_TEST_SUITE_END()
