// dss_check --motions: motions between states checked by OMPL motion validators from the
// command line (tools/motion_checks.h): the validators' verdicts against each other, a path
// read from a states file, and the errors of a path or options that motions cannot take.
#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/run_tool.h"
#include "support/temp_files.h"

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
const std::string kBase = std::string(DSS_SOURCE_DIR) + "/robots/dss_mobile_base";

std::vector<std::string> armArgs(std::vector<std::string> more) {
  std::vector<std::string> a = {"--robot", kArm + "/dss_arm7.urdf",
                                "--srdf",  kArm + "/dss_arm7.srdf",
                                "--scene", kArm + "/scenes/shelf.yaml"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// The JSON summaries a run printed on stderr, one per motion validator.
std::vector<nlohmann::json> summaries(const std::string& err) {
  std::vector<nlohmann::json> out;
  for (const std::string& l : dss_test::outputLines(err))
    if (!l.empty() && l[0] == '{') out.push_back(nlohmann::json::parse(l));
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(motion_checks_cli)

BOOST_AUTO_TEST_CASE(the_validators_agree_where_they_must_on_random_motions) {
  // The same 400 random motions (the seed draws them) under every validator: the vector and
  // OMPL's validators check the discrete validator's states, so they give its verdicts motion
  // by motion; the continuous one never calls free a motion with a colliding state.
  const std::vector<std::string> common = {"--random", "400", "--seed", "3", "--repeat", "1"};
  std::vector<std::string> first_discrete = common, first_continuous = common;
  first_discrete.insert(first_discrete.end(), {"--motions", "discrete,vector,ompl,continuous"});
  first_continuous.insert(first_continuous.end(), {"--motions", "continuous"});
  const dss_test::ToolRun d = dss_test::runTool("dss_check", armArgs(first_discrete));
  const dss_test::ToolRun c = dss_test::runTool("dss_check", armArgs(first_continuous));
  BOOST_REQUIRE_MESSAGE(d.exit_code == 0, d.err);
  BOOST_REQUIRE_MESSAGE(c.exit_code == 0, c.err);
  const std::vector<nlohmann::json> s = summaries(d.err);
  BOOST_REQUIRE(s.size() == 4u);
  BOOST_TEST(s[0]["motion_validator"] == "discrete");
  BOOST_TEST(s[0]["motions"] == 400);
  BOOST_TEST(s[0]["source"] == "random");
  BOOST_TEST(s[1]["disagreements"] == 0);  // vector
  BOOST_TEST(s[2]["disagreements"] == 0);  // OMPL's own
  BOOST_TEST(s[0]["states_per_motion"].get<double>() >= 1.0);
  BOOST_TEST(s[3].contains("sub_motions_per_motion"));
  const std::vector<std::string> dv = dss_test::outputLines(d.out),
                                 cv = dss_test::outputLines(c.out);
  BOOST_REQUIRE(dv.size() == 400u);
  BOOST_REQUIRE(cv.size() == 400u);
  int free = 0, colliding = 0, refused_by_continuous_only = 0;
  for (std::size_t i = 0; i < dv.size(); ++i) {
    BOOST_REQUIRE(dv[i] == "0" || dv[i] == "1");
    free += dv[i] == "1";
    colliding += dv[i] == "0";
    if (cv[i] == "1") BOOST_TEST(dv[i] == "1", "motion " << i);
    refused_by_continuous_only += cv[i] == "0" && dv[i] == "1";
  }
  // Both verdicts occur, and the summary counts what the lines say.
  BOOST_TEST(free > 0);
  BOOST_TEST(colliding > 0);
  BOOST_TEST(s[0]["valid"] == free);
  BOOST_TEST(s[3]["disagreements"] == refused_by_continuous_only);
}

BOOST_AUTO_TEST_CASE(the_continuous_smallest_sub_motion_reaches_the_validator) {
  // At a smallest sub-motion of 1 the continuous validator clears each motion whole or refuses
  // it: one sub-motion per motion, never a motion with a colliding state, and fewer motions
  // than when it may halve them down to 1/1024 (the motions near the shelf need the halving).
  const std::vector<std::string> common = {"--random", "400", "--seed", "3", "--repeat", "1"};
  std::vector<std::string> whole = common, halved = common;
  whole.insert(whole.end(), {"--motions", "discrete,continuous", "--motion-min-fraction", "1"});
  halved.insert(halved.end(), {"--motions", "discrete,continuous"});
  const dss_test::ToolRun w = dss_test::runTool("dss_check", armArgs(whole));
  const dss_test::ToolRun h = dss_test::runTool("dss_check", armArgs(halved));
  BOOST_REQUIRE_MESSAGE(w.exit_code == 0, w.err);
  BOOST_REQUIRE_MESSAGE(h.exit_code == 0, h.err);
  const std::vector<nlohmann::json> sw = summaries(w.err), sh = summaries(h.err);
  BOOST_REQUIRE(sw.size() == 2u);
  BOOST_REQUIRE(sh.size() == 2u);
  BOOST_TEST(sw[1]["min_fraction"].get<double>() == 1.0);
  BOOST_TEST(sh[1]["min_fraction"].get<double>() == 1.0 / 1024.0);
  BOOST_TEST(sw[1]["sub_motions_per_motion"].get<double>() == 1.0);
  BOOST_TEST(sh[1]["sub_motions_per_motion"].get<double>() > 1.0);
  // The discrete verdicts are the same in both runs (the seed draws the same motions).
  BOOST_TEST(sw[0]["valid"] == sh[0]["valid"]);
  const long discrete_free = sw[0]["valid"].get<long>();
  const long whole_free = sw[1]["valid"].get<long>(), halved_free = sh[1]["valid"].get<long>();
  BOOST_TEST(whole_free > 0);
  BOOST_TEST(whole_free < halved_free);
  BOOST_TEST(halved_free <= discrete_free);
  // Every motion cleared whole is free at each discrete state: it refused what the discrete
  // validator refused (the difference is the motions it alone refused).
  BOOST_TEST(sw[1]["disagreements"].get<long>() == discrete_free - whole_free);
}

BOOST_AUTO_TEST_CASE(a_path_from_a_states_file_names_where_it_collides) {
  // The shelf request's start, its goal (the straight motion between them crosses the shelf),
  // the goal again (a motion of length zero) and back to the start.
  const std::string csv =
      "joint1,joint2,joint3,joint4,joint5,joint6,joint7\n"
      "0.19,0.5783,0,-1.6413,0,-0.6488,0.4\n"
      "-0.19,0.3763,0,-1.0201,0,0.1744,-0.6\n"
      "-0.19,0.3763,0,-1.0201,0,0.1744,-0.6\n";
  const std::string file = dss_test::writeScratch("motion_checks_cli", "path.csv", csv);
  const dss_test::ToolRun r = dss_test::runTool(
      "dss_check",
      armArgs({"--states", file, "--motions", "vector,discrete", "--contacts", "--repeat", "1"}));
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::vector<std::string> lines = dss_test::outputLines(r.out);
  BOOST_REQUIRE(lines.size() == 2u);
  BOOST_TEST(lines[0].rfind("0\tat ", 0) == 0, lines[0]);
  BOOST_TEST(lines[0].find(" of the motion: link ") != std::string::npos, lines[0]);
  BOOST_TEST(lines[0].find("with scene object '") != std::string::npos, lines[0]);
  BOOST_TEST(lines[1] == "1");
  const std::vector<nlohmann::json> s = summaries(r.err);
  BOOST_REQUIRE(s.size() == 2u);
  BOOST_TEST(s[0]["source"] == "path");
  BOOST_TEST(s[0]["motions"] == 2);
  BOOST_TEST(s[1]["disagreements"] == 0);
}

BOOST_AUTO_TEST_CASE(a_motion_to_or_from_a_non_finite_state_collides) {
  // NaN and Inf are never free: both motions touching the second row collide under every
  // validator, and the line says why; the last motion (finite ends) is checked as usual.
  const std::string file = dss_test::writeScratch(
      "motion_checks_cli", "non_finite.csv",
      "joint1,joint2,joint3,joint4,joint5,joint6,joint7\n0,0,0,-1,0,0,0\nnan,0,0,-1,0,0,0\n"
      "0,0,0,-1,0,0,inf\n0,0,0,-1,0,0,0.1\n0,0,0,-1,0,0,0.2\n");
  const dss_test::ToolRun r = dss_test::runTool(
      "dss_check", armArgs({"--states", file, "--motions", "discrete,vector,continuous,ompl",
                            "--contacts", "--repeat", "1"}));
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::vector<std::string> lines = dss_test::outputLines(r.out);
  BOOST_REQUIRE(lines.size() == 4u);
  for (int i = 0; i < 3; ++i)
    BOOST_TEST(lines[std::size_t(i)] ==
               "0\ta state of the motion holds a value that is not finite");
  BOOST_TEST(lines[3] == "1");
  const std::vector<nlohmann::json> s = summaries(r.err);
  BOOST_REQUIRE(s.size() == 4u);
  for (const auto& j : s) BOOST_TEST(j["valid"] == 1);
}

BOOST_AUTO_TEST_CASE(paths_and_options_motions_cannot_take_are_refused) {
  const std::string one_row =
      dss_test::writeScratch("motion_checks_cli", "one_row.csv",
                             "joint1,joint2,joint3,joint4,joint5,joint6,joint7\n0,0,0,-1,0,0,0\n");
  const dss_test::ToolRun r1 =
      dss_test::runTool("dss_check", armArgs({"--states", one_row, "--motions", "discrete"}));
  BOOST_TEST(r1.exit_code == 1);
  BOOST_TEST(r1.err.find(one_row + ": --motions needs a path of at least two states, got 1") !=
                 std::string::npos,
             r1.err);
  // The mobile base's arm group holds the base at the path's first state: a path that keeps the
  // base there is the arm's motions, one that moves it is not.
  auto baseRun = [](const std::string& file) {
    return dss_test::runTool("dss_check", {"--robot", kBase + "/dss_mobile_base.urdf", "--srdf",
                                           kBase + "/dss_mobile_base.srdf", "--group", "mast_arm",
                                           "--states", file, "--motions", "discrete"});
  };
  const std::string kept = dss_test::writeScratch(
      "motion_checks_cli", "kept_base.csv", "mast_lift,arm_pitch,base/x\n0.2,0,0.5\n0.3,0.1,0.5\n");
  const dss_test::ToolRun r0 = baseRun(kept);
  BOOST_TEST(r0.exit_code == 0, r0.err);
  BOOST_TEST(dss_test::outputLines(r0.out).size() == 1u);
  const std::string moved = dss_test::writeScratch(
      "motion_checks_cli", "moved_base.csv", "mast_lift,arm_pitch,base/x\n0.2,0,0\n0.3,0.1,0.5\n");
  const dss_test::ToolRun r2 = baseRun(moved);
  BOOST_TEST(r2.exit_code == 1);
  BOOST_TEST(
      r2.err.find(moved + ":3: joint 'base/x' is not in group 'mast_arm'") != std::string::npos,
      r2.err);
  auto usage = [](std::vector<std::string> more, const std::string& says) {
    const dss_test::ToolRun r = dss_test::runTool("dss_check", armArgs(more));
    BOOST_TEST(r.exit_code == 2, says);
    BOOST_TEST(r.err.find(says) != std::string::npos, r.err);
  };
  usage({"--random", "5", "--motions", "warp"}, "--motions: expected discrete, vector");
  usage({"--random", "5", "--motions", "discrete,"}, "--motions: expected a comma list");
  usage({"--random", "5", "--motions", "continuous", "--checker", "fcl-hull"},
        "the continuous validator needs --checker dss");
  usage({"--random", "5", "--motions", "discrete", "--checker", "dss,fcl-hull"},
        "every motion validator stands on one --checker");
  usage({"--random", "5", "--motions", "discrete", "--threads", "2"}, "one thread only");
  usage({"--random", "5", "--motions", "discrete", "--resolution", "0"}, "--resolution");
  usage({"--random", "5", "--motions", "discrete", "--motion-length", "2"}, "--motion-length");
  usage({"--random", "5", "--resolution", "0.02"}, "apply to --motions only");
  usage({"--random", "5", "--motions", "discrete,vector", "--motion-min-fraction", "0.5"},
        "--motion-min-fraction applies to --motions continuous only");
  usage({"--random", "5", "--motions", "continuous", "--motion-min-fraction", "0"},
        "--motion-min-fraction");
  usage({"--random", "5", "--motions", "continuous", "--motion-min-fraction", "nan"},
        "--motion-min-fraction");
  usage({"--random", "10000001", "--motions", "discrete"}, "--random takes at most 10000000");
}

BOOST_AUTO_TEST_SUITE_END()
