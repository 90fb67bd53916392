// dss_plan --param NAME=VALUE as a user runs it, on our arm by its shelf: the parameter reaches
// the planner (RRTConnect with a short range grows its trees in short steps: more states on the
// path, more motion checks) and is echoed in the JSON; a parameter the planner does not have, a
// value it rejects, a value that is not a finite number and a malformed option are usage errors
// that name the planner and the parameter.
#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/run_tool.h"

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";

dss_test::ToolRun runPlan(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"--robot",   kArm + "/dss_arm7.urdf",
                                   "--srdf",    kArm + "/dss_arm7.srdf",
                                   "--scene",   kArm + "/scenes/shelf.yaml",
                                   "--request", kArm + "/scenes/shelf_request.yaml",
                                   "--seed",    "1"};
  args.insert(args.end(), extra.begin(), extra.end());
  return dss_test::runTool("dss_plan", args);
}

nlohmann::json plan(const std::vector<std::string>& extra) {
  const dss_test::ToolRun r = runPlan(extra);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  return nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
}

void checkUsageError(const std::vector<std::string>& extra, const std::string& text) {
  const dss_test::ToolRun r = runPlan(extra);
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.find(text) != std::string::npos, "stderr: " << r.err << " lacks: " << text);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planner_params_cli)

BOOST_AUTO_TEST_CASE(a_short_range_reaches_the_planner) {
  const nlohmann::json plain = plan({});
  const nlohmann::json shortr = plan({"--param", "range=0.05"});
  BOOST_TEST(plain.at("solved").get<bool>());
  BOOST_TEST(shortr.at("solved").get<bool>());
  BOOST_TEST(!plain.contains("planner_params"));
  BOOST_TEST(shortr.at("planner_params").at("range").get<std::string>() == "0.05");
  // Steps of at most 0.05 rad: a path at least as many states as its length takes steps, and
  // far more motion checks than the default range (a fifth of the space's extent) needs.
  const double length = shortr.at("path_length").get<double>();
  BOOST_TEST(shortr.at("path_states").get<double>() >= length / 0.05);
  BOOST_TEST(shortr.at("motion_checks").get<long>() > 4 * plain.at("motion_checks").get<long>());
  // The same setting given as OMPL's default makes the same plan as no setting.
  const nlohmann::json zero = plan({"--param", "range=0"});
  BOOST_TEST(zero.at("path_length").get<double>() == plain.at("path_length").get<double>());
  BOOST_TEST(zero.at("motion_checks").get<long>() == plain.at("motion_checks").get<long>());
}

BOOST_AUTO_TEST_CASE(bad_parameters_are_usage_errors) {
  checkUsageError({"--param", "radius=1"},
                  "--param: RRTConnect has no parameter 'radius' (it has: ");
  checkUsageError({"--param", "range=far"}, "RRTConnect parameter 'range': value 'far' rejected");
  checkUsageError({"--param", "range=nan"},
                  "RRTConnect parameter 'range': 'nan' is not a finite number");
  checkUsageError({"--param", "range=-inf"}, "'-inf' is not a finite number");
  checkUsageError({"--param", "range"}, "--param: expected NAME=VALUE, got 'range'");
  checkUsageError({"--param", "=1"}, "--param: expected NAME=VALUE, got '=1'");
  checkUsageError({"--param", "range="}, "--param: expected NAME=VALUE, got 'range='");
  checkUsageError({"--param", "range=1", "--param", "range=2"}, "--param: 'range' given twice");
  // PRM has no range: with a list of planners, each must have the parameter.
  checkUsageError({"--benchmark", "--planner", "RRTConnect,PRM", "--param", "range=1"},
                  "PRM has no parameter 'range'");
}

BOOST_AUTO_TEST_SUITE_END()
