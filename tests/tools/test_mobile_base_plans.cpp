// dss_plan on a planar and a floating base, headless, as a user runs it: our mobile base
// through its aisle (discrete and continuous motions, DSS and fcl-hull), our free flyer
// through its window and our quadrotor across its clearing; the solution path's CSV names the
// multi-DOF variables and reads back.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/run_tool.h"
#include "support/temp_files.h"

namespace {

const std::string kRobots = std::string(DSS_SOURCE_DIR) + "/robots";

std::vector<std::string> problem(const std::string& robot, const std::string& scene) {
  const std::string d = kRobots + "/" + robot;
  return {"--robot",   d + "/" + robot + ".urdf",
          "--srdf",    d + "/" + robot + ".srdf",
          "--scene",   d + "/scenes/" + scene + ".yaml",
          "--request", d + "/scenes/" + scene + "_request.yaml",
          "--seed",    "1",
          "--time",    "30"};
}

// dss_plan on the robot's problem with discrete motions, with continuous motions and with
// fcl-hull: each run's exit status and "solved" are tested; `check` takes each run's first
// JSON line (and the output, for messages).
template <class Check>
void planWithEachSetting(const std::string& robot, const std::string& scene, Check&& check) {
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{}, {"--motion", "continuous"}, {"--checker", "fcl-hull"}}) {
    std::vector<std::string> args = problem(robot, scene);
    args.insert(args.end(), extra.begin(), extra.end());
    const dss_test::ToolRun r = dss_test::runTool("dss_plan", args);
    BOOST_TEST(r.exit_code == 0, r.err);
    BOOST_TEST(r.out.find("\"solved\":true") != std::string::npos, r.out);
    check(nlohmann::json::parse(r.out.substr(0, r.out.find('\n'))), r.out);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mobile_base_plans)

BOOST_AUTO_TEST_CASE(the_mobile_base_plans_through_its_aisle) {
  planWithEachSetting("dss_mobile_base", "aisle",
                      [](const nlohmann::json& j, const std::string& out) {
                        // The states the planner asked about, and of them those found
                        // colliding: some of the base poses an RRT tries in the aisle run into
                        // its shelves.
                        const long checks = j.at("validity_checks").get<long>();
                        const long colliding = j.at("colliding_states").get<long>();
                        BOOST_TEST(checks > 0, out);
                        BOOST_TEST(colliding > 0, out);
                        BOOST_TEST(colliding < checks, out);
                        // The problem's setup time is reported (the model with its base-scene
                        // table is built).
                        const double setup = j.at("setup_s").get<double>();
                        BOOST_TEST((setup > 0.0 && std::isfinite(setup)), out);
                      });
}

// --base-table-cells: the mobile base's table against the aisle, by default and at a chosen
// size, or none; the per-state answers of dss_check and the plan do not change.
BOOST_AUTO_TEST_CASE(the_base_table_size_changes_no_answer) {
  const std::string d = kRobots + "/dss_mobile_base";
  std::vector<std::string> answers;
  for (const char* cells : {"", "0", "5000"}) {
    std::vector<std::string> args = {"--robot",     d + "/dss_mobile_base.urdf",
                                     "--srdf",      d + "/dss_mobile_base.srdf",
                                     "--scene",     d + "/scenes/aisle.yaml",
                                     "--group",     "whole_body",
                                     "--workspace", "0,-0.7,0,9,0.7,2",
                                     "--random",    "3000",
                                     "--checker",   "dss"};
    if (*cells) args.insert(args.end(), {"--base-table-cells", cells});
    const dss_test::ToolRun r = dss_test::runTool("dss_check", args);
    BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
    const bool table = r.err.find("base-scene table (") != std::string::npos;
    BOOST_TEST(table == (std::string(cells) != "0"), cells << ": " << r.err);
    answers.push_back(r.out);
  }
  BOOST_TEST(answers[0].size() > 3000u);
  BOOST_TEST(answers[0] == answers[1]);
  BOOST_TEST(answers[0] == answers[2]);
  // Discrete and continuous motions: the same path, motion checks and colliding states here.
  // The continuous check clears some sub-motions with the table that it would otherwise halve,
  // so it may check fewer midpoint states; the discrete validator checks the same states.
  for (const char* motion : {"discrete", "continuous"}) {
    std::vector<std::string> plans;
    for (const char* cells : {"0", "65536"}) {
      std::vector<std::string> args = problem("dss_mobile_base", "aisle");
      args.insert(args.end(), {"--base-table-cells", cells, "--motion", motion});
      const dss_test::ToolRun r = dss_test::runTool("dss_plan", args);
      BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
      const nlohmann::json j = nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
      std::string key = j.at("path_length").dump() + " " + j.at("motion_checks").dump() + " " +
                        j.at("colliding_states").dump();
      if (std::string(motion) == "discrete") key += " " + j.at("validity_checks").dump();
      plans.push_back(key);
    }
    BOOST_TEST(plans[0] == plans[1], motion);
  }
  const dss_test::ToolRun bad = dss_test::runTool(
      "dss_check",
      {"--robot", d + "/dss_mobile_base.urdf", "--random", "3", "--base-table-cells", "-1"});
  BOOST_TEST(bad.exit_code == 2);
  BOOST_TEST(bad.err.find("--base-table-cells") != std::string::npos, bad.err);
}

BOOST_AUTO_TEST_CASE(the_free_flyer_plans_through_its_window_and_writes_its_path) {
  const std::string csv = (dss_test::scratchDir("tools") / "flyer_path.csv").string();
  std::vector<std::string> args = problem("dss_free_flyer", "window");
  args.insert(args.end(), {"--path", csv});
  const dss_test::ToolRun r = dss_test::runTool("dss_plan", args);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.out.find("\"solved\":true") != std::string::npos, r.out);
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  BOOST_TEST(header ==
             "base/trans_x,base/trans_y,base/trans_z,base/rot_x,base/rot_y,base/rot_z,"
             "base/rot_w");
  // Every state of the path is valid again for dss_check, read from the CSV.
  const std::string d = kRobots + "/dss_free_flyer";
  const dss_test::ToolRun c = dss_test::runTool(
      "dss_check", {"--robot", d + "/dss_free_flyer.urdf", "--srdf", d + "/dss_free_flyer.srdf",
                    "--scene", d + "/scenes/window.yaml", "--workspace", "-3,-2,0,3,2,3",
                    "--states", csv, "--checker", "dss,fcl-hull"});
  BOOST_TEST(c.exit_code == 0, c.err);
  BOOST_TEST(c.out.find('0') == std::string::npos, c.out);
  BOOST_TEST(c.out.find('1') != std::string::npos, c.out);
}

// The quadrotor flies across its clearing with discrete and continuous motions and with
// fcl-hull; the straight line runs through two trunks, so the planner meets colliding states.
BOOST_AUTO_TEST_CASE(the_quadrotor_plans_across_its_clearing) {
  planWithEachSetting("dss_quadrotor", "forest",
                      [](const nlohmann::json& j, const std::string& out) {
                        BOOST_TEST(j.at("colliding_states").get<long>() > 0, out);
                      });
}

// dss_check --describe names the links that keep a sphere chain: the flyer's body, with a point
// per slab of its beam and one for its fin, each inner ball inside its outer one.
BOOST_AUTO_TEST_CASE(describe_lists_the_sphere_chains) {
  const std::string d = kRobots + "/dss_free_flyer";
  const dss_test::ToolRun r = dss_test::runTool(
      "dss_check",
      {"--robot", d + "/dss_free_flyer.urdf", "--srdf", d + "/dss_free_flyer.srdf", "--scene",
       d + "/scenes/window.yaml", "--workspace", "-3,-2,0,3,2,3", "--describe"});
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_REQUIRE(j["sphere_chains"].size() == 1u);
  BOOST_TEST(j["sphere_chains"][0]["link"] == "body");
  BOOST_TEST(j["sphere_chains"][0]["points"].size() == 8u);
  for (const auto& p : j["sphere_chains"][0]["points"]) {
    BOOST_TEST(p["inner"].get<double>() > 0.0);
    BOOST_TEST(p["inner"].get<double>() < p["outer"].get<double>());
  }
  BOOST_TEST(j["clearance_grid"]["upper_bounds"] == true);
  BOOST_TEST(j["summary"].get<std::string>().find("sphere chains on 1 link (8 points)") !=
             std::string::npos);
}

// A goal that names only some of the group's values (here the arm's, not the base's) keeps
// the others at their start values, and dss_plan says so; a goal naming them all gets no note.
BOOST_AUTO_TEST_CASE(goal_values_not_named_keep_their_start_values_with_a_note) {
  const std::string d = kRobots + "/dss_mobile_base";
  std::ifstream in(d + "/scenes/aisle_request.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string request = text.str();
  // Drop the base's three goal constraints.
  for (const char* name : {"base/x", "base/y", "base/theta"}) {
    const std::size_t at = request.find("      - joint_name: " + std::string(name) + "\n");
    BOOST_REQUIRE(at != std::string::npos);
    const std::size_t end = request.find("      - joint_name:", at + 1);
    BOOST_REQUIRE(end != std::string::npos);
    request.erase(at, end - at);
  }
  const std::string file = dss_test::writeScratch("tools", "arm_goal_request.yaml", request);
  std::vector<std::string> args = problem("dss_mobile_base", "aisle");
  args[7] = file;  // --request
  const dss_test::ToolRun r = dss_test::runTool("dss_plan", args);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("goal_constraints[0] does not name 3 of the group's 5 values; they keep "
                        "their start values: base/x, base/y, base/theta") != std::string::npos,
             r.err);
  const dss_test::ToolRun full = dss_test::runTool("dss_plan", problem("dss_mobile_base", "aisle"));
  BOOST_TEST(full.exit_code == 0, full.err);
  BOOST_TEST(full.err.find("does not name") == std::string::npos, full.err);
}

BOOST_AUTO_TEST_CASE(a_floating_group_without_bounds_is_refused_clearly) {
  // No request: no workspace_parameters, and no --workspace.
  const std::string d = kRobots + "/dss_free_flyer";
  const dss_test::ToolRun c =
      dss_test::runTool("dss_check", {"--robot", d + "/dss_free_flyer.urdf", "--srdf",
                                      d + "/dss_free_flyer.srdf", "--random", "10"});
  BOOST_TEST(c.exit_code == 1);
  BOOST_TEST(c.err.find("has no finite bounds for base/trans_x") != std::string::npos, c.err);
}

BOOST_AUTO_TEST_SUITE_END()
