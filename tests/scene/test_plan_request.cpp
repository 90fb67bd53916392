// MotionPlanRequest YAML: every MotionBenchMaker request loads (group, start state, joint
// goals), and bad requests are refused with the file and line.
#include <boost/test/unit_test.hpp>
#include <filesystem>

#include "dss/scene/plan_request.h"
#include "dss/scene/scene_error.h"
#include "scene/scene_test_util.h"
#include "support/shared_data.h"

using namespace dss_test;

BOOST_AUTO_TEST_SUITE(plan_request)

BOOST_AUTO_TEST_CASE(all_mbm_requests_load, DSS_NEEDS_SHARED) {
  requireShared();
  int n = 0;
  for (const char* robot : {"mbm_panda", "mbm_ur5"}) {
    const bool panda = std::string(robot) == "mbm_panda";
    for (const auto& f : filesMatching(scenesDir() + "/" + robot, "request[0-9]+\\.yaml")) {
      BOOST_TEST_CONTEXT(f) {
        const dss::PlanRequest r = dss::loadPlanRequestYaml(f);
        BOOST_TEST(r.group_name == (panda ? "panda_arm" : "manipulator"));
        BOOST_TEST(r.start_names.size() == (panda ? 9u : 12u));
        BOOST_TEST(r.start_positions.size() == r.start_names.size());
        BOOST_REQUIRE(r.goals.size() == 1u);
        BOOST_TEST(r.goals[0].joint_constraints.size() == (panda ? 7u : 6u));
        for (const auto& c : r.goals[0].joint_constraints) {
          BOOST_TEST(c.tolerance_above == 0.0);
          BOOST_TEST(c.tolerance_below == 0.0);
        }
        if (panda) BOOST_TEST(r.startState().at("panda_finger_joint1") == 0.065);
        BOOST_TEST(r.warnings.empty());
        ++n;
      }
    }
  }
  BOOST_TEST(n == 105);
}

BOOST_AUTO_TEST_CASE(key_order_and_values, DSS_NEEDS_SHARED) {
  requireShared();
  // request0001 of box lists `position` before `joint_name` for some joints.
  const dss::PlanRequest r =
      dss::loadPlanRequestYaml(scenesDir() + "/mbm_panda/box/request0001.yaml");
  const auto& g = r.goals[0].joint_constraints;
  BOOST_TEST(g[1].joint_name == "panda_joint2");
  BOOST_TEST(g[1].position == 1.7628);
  BOOST_TEST(g[2].joint_name == "panda_joint3");
  BOOST_TEST(g[2].position == 0.1941262264518609);
  BOOST_TEST(r.planner_id == "BKPIECEGood");
  BOOST_TEST(r.allowed_planning_time == 60.0);
  BOOST_TEST(r.num_planning_attempts == 2);
}

BOOST_AUTO_TEST_CASE(joints_checked_against_a_robot) {
  const std::string text =
      "group_name: g\nstart_state:\n  joint_state:\n    name: [a, b, grip]\n"
      "    position: [0, 1, 0]\ngoal_constraints:\n  - joint_constraints:\n"
      "      - {joint_name: a, position: 1}\n";
  const dss::PlanRequest r = dss::parsePlanRequestYaml(text, "req.yaml");
  const auto ignored = dss::checkRequestJoints(r, {"a", "b"}, {"grip"});
  BOOST_TEST(ignored == std::vector<std::string>{"grip"});
  std::string m = thrownMessage<dss::SceneError>([&] {
    dss::checkRequestJoints(r, {"a", "b"}, {});
  });
  BOOST_TEST(contains(m, "req.yaml"));
  BOOST_TEST(contains(m, "'grip'"));
  m = thrownMessage<dss::SceneError>([&] { dss::checkRequestJoints(r, {"b"}, {"a", "grip"}); });
  BOOST_TEST(contains(m, "goal_constraints[0]"));
  BOOST_TEST(contains(m, "'a'"));
}

BOOST_AUTO_TEST_CASE(errors) {
  auto msgOf = [](const std::string& text) {
    return thrownMessage<dss::SceneError>([&] { dss::parsePlanRequestYaml(text, "req.yaml"); });
  };
  const std::string start =
      "start_state:\n  joint_state:\n    name: [a, b]\n    position: [0, 1]\n";
  const std::string goal =
      "goal_constraints:\n  - joint_constraints:\n"
      "      - {joint_name: a, position: 1, tolerance_above: 0.1}\n";
  const dss::PlanRequest ok =
      dss::parsePlanRequestYaml("group_name: g\n" + start + goal, "ok.yaml");
  BOOST_TEST(ok.goals[0].joint_constraints[0].tolerance_above == 0.1);
  std::string m = msgOf(start + goal);
  BOOST_TEST(contains(m, "group_name"));
  BOOST_TEST(contains(m, "req.yaml"));
  m = msgOf("group_name: g\nstart_state:\n  joint_state:\n    name: [a, b]\n    position: [0]\n" +
            goal);
  BOOST_TEST(contains(m, "2 names but 1 positions"));
  BOOST_TEST(contains(m, "req.yaml:4"));
  m = msgOf("group_name: g\n" + start +
            "goal_constraints:\n  - joint_constraints:\n"
            "      - {joint_name: a}\n");
  BOOST_TEST(contains(m, "joint 'a'"));
  BOOST_TEST(contains(m, "position"));
  m = msgOf("group_name: g\n" + start +
            "goal_constraints:\n  - position_constraints: [{}]\n"
            "    joint_constraints: []\n");
  BOOST_TEST(contains(m, "position_constraints"));
  m = msgOf("group_name: [g\n");
  BOOST_TEST(contains(m, "malformed YAML"));
}

BOOST_AUTO_TEST_CASE(start_state_attached_objects_are_read) {
  const std::string text =
      "group_name: g\nstart_state:\n  joint_state: {name: [a], position: [0]}\n"
      "  attached_collision_objects:\n"
      "    - link_name: hand\n      touch_links: [finger]\n      weight: 0.2\n"
      "      object:\n        id: cup\n        header: {frame_id: world}\n"
      "        primitives: [{type: cylinder, dimensions: [0.1, 0.03]}]\n"
      "        primitive_poses: [{position: [0.5, 0, 0.2], orientation: [0, 0, 0, 1]}]\n"
      "goal_constraints:\n  - joint_constraints: [{joint_name: a, position: 1}]\n";
  const dss::PlanRequest r = dss::parsePlanRequestYaml(text, "req.yaml");
  BOOST_TEST(r.warnings.empty());
  BOOST_REQUIRE(r.start_attached.size() == 1u);
  const dss::AttachedObject& a = r.start_attached[0];
  BOOST_TEST(a.id == "cup");
  BOOST_TEST(a.link == "hand");
  BOOST_TEST(a.touch_links == std::vector<std::string>{"finger"});
  BOOST_TEST(a.at_request_start);
  BOOST_TEST(a.at == "req.yaml:5");
  BOOST_REQUIRE(a.parts.size() == 1u);
  BOOST_TEST(a.parts[0].frame_id == "world");
  BOOST_TEST(a.parts[0].X_FO.translation().x() == 0.5);
  // A bad object is refused as in a scene: the file, the line and the field.
  std::string bad = text;
  bad.replace(bad.find("type: cylinder"), 14, "type: torus");
  const std::string m =
      thrownMessage<dss::SceneError>([&] { dss::parsePlanRequestYaml(bad, "req.yaml"); });
  BOOST_TEST(contains(m, "req.yaml:11: object 'cup' primitive 0"), m);
  BOOST_TEST(contains(m, "unknown primitive type 'torus'"), m);
}

BOOST_AUTO_TEST_CASE(path_and_trajectory_constraints_are_said_to_be_ignored) {
  const std::string base =
      "group_name: g\nstart_state:\n  joint_state: {name: [a], position: [0]}\n"
      "goal_constraints:\n  - joint_constraints: [{joint_name: a, position: 1}]\n";
  BOOST_TEST(dss::parsePlanRequestYaml(base + "path_constraints: {name: '', joint_constraints: "
                                              "[]}\ntrajectory_constraints: {constraints: []}\n",
                                       "req.yaml")
                 .warnings.empty());
  const dss::PlanRequest r = dss::parsePlanRequestYaml(
      base +
          "path_constraints:\n  orientation_constraints: [{link_name: hand}]\n"
          "trajectory_constraints:\n  constraints: [{name: c}]\n",
      "req.yaml");
  BOOST_REQUIRE(r.warnings.size() == 2u);
  BOOST_TEST(r.warnings[0] == "req.yaml:7: path_constraints not enforced (ignored)");
  BOOST_TEST(r.warnings[1] == "req.yaml:9: trajectory_constraints not enforced (ignored)");
}

BOOST_AUTO_TEST_SUITE_END()
