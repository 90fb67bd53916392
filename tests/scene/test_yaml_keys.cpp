// Keys of PlanningScene and MotionPlanRequest YAML: a key that the ROS message at its place
// lacks (a misspelled `Pose` once became the identity pose, silently) is an error naming the
// key, the line and the fields the message has, as deserializing the ROS message would fail;
// the options turn it into a stored warning. A key given twice is always an error.
#include <boost/test/unit_test.hpp>
#include <string>

#include "dss/scene/plan_request.h"
#include "dss/scene/planning_scene_yaml.h"
#include "dss/scene/scene_error.h"
#include "scene/scene_test_util.h"

using namespace dss_test;

namespace {

// One box object; `extra` is added to the object's mapping (line 6).
std::string sceneWith(const std::string& extra) {
  return "world:\n"
         "  collision_objects:\n"
         "    - id: box\n"
         "      primitives: [{type: box, dimensions: [1, 1, 1]}]\n"
         "      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n" +
         extra;
}

std::string sceneError(const std::string& text, const dss::SceneLoadOptions& options = {}) {
  return thrownMessage<dss::SceneError>(
      [&] { dss::parsePlanningSceneYaml(text, "keys.yaml", options); });
}

const char* const kRequest =
    "group_name: arm\n"
    "start_state:\n"
    "  joint_state: {name: [j], position: [0]}\n"
    "goal_constraints:\n"
    "  - joint_constraints:\n"
    "      - {joint_name: j, position: 1}\n";

}  // namespace

BOOST_AUTO_TEST_SUITE(yaml_keys)

// The reproducer: `Pose` instead of `pose` moved the object to the origin without a word.
BOOST_AUTO_TEST_CASE(a_misspelled_pose_is_an_error_naming_key_and_line) {
  const std::string text =
      sceneWith("      Pose: {position: [5, 0, 0], orientation: [0, 0, 0, 1]}\n");
  BOOST_TEST(sceneError(text) ==
             "keys.yaml:6: object 'box': unknown key 'Pose' (moveit_msgs/CollisionObject has "
             "header, pose, id, type, primitives, primitive_poses, meshes, mesh_poses, planes, "
             "plane_poses, subframe_names, subframe_poses, operation; did you mean 'pose'?); "
             "SceneLoadOptions::unknown_keys_are_warnings = true reads it as a warning");
  // As a warning, stored with the key and the line; the object keeps its (identity) pose.
  dss::SceneLoadOptions o;
  o.unknown_keys_are_warnings = true;
  const dss::Scene s = dss::parsePlanningSceneYaml(text, "keys.yaml", o);
  BOOST_REQUIRE(s.warnings.size() == 1u);
  BOOST_TEST(contains(s.warnings[0], "keys.yaml:6: object 'box': unknown key 'Pose'"));
  BOOST_TEST(contains(s.warnings[0], ": ignored"));
  BOOST_TEST(s.obstacles.at(0).X_WO.translation().norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(unknown_keys_at_every_level) {
  struct Case {
    std::string text;
    std::string message_part;
  };
  const std::vector<Case> cases = {
      {sceneWith("      primitve_poses: []\n"),
       "keys.yaml:6: object 'box': unknown key 'primitve_poses'"},
      {"Name: s\n" + sceneWith(""), "keys.yaml:1: planning scene: unknown key 'Name'"},
      {"world:\n  collision_object: []\n  collision_objects: []\n",
       "keys.yaml:2: world: unknown key 'collision_object' (moveit_msgs/PlanningSceneWorld has "
       "collision_objects, octomap; did you mean 'collision_objects'?)"},
      {"world:\n  collision_objects:\n    - id: b\n      primitives: [{type: box, dimension: "
       "[1, 1, 1]}]\n      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n",
       "keys.yaml:4: object 'b' primitive 0: unknown key 'dimension' (shape_msgs/SolidPrimitive"},
      {"world:\n  collision_objects:\n    - id: b\n      primitives: [{type: box, dimensions: "
       "[1, 1, 1]}]\n      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1], "
       "scale: 2}]\n",
       "keys.yaml:5: object 'b' primitive 0 pose: unknown key 'scale' (geometry_msgs/Pose has "
       "position, orientation)"},
      {"world:\n  collision_objects:\n    - id: b\n      primitives: [{type: box, dimensions: "
       "[1, 1, 1]}]\n      primitive_poses: [{position: {x: 0, y: 0, zz: 0}, orientation: [0, 0, "
       "0, 1]}]\n",
       "unknown key 'zz' (geometry_msgs/Point has x, y, z; did you mean 'z'?)"},
      {"robot_state:\n  joint_state: {name: [a], positions: [1]}\n",
       "keys.yaml:2: robot_state.joint_state: unknown key 'positions'"},
      {"allowed_collision_matrix:\n  entry_name: [a]\n",
       "keys.yaml:2: allowed_collision_matrix: unknown key 'entry_name'"},
      {sceneWith("      header: {frame: base}\n"),
       "keys.yaml:6: object 'box' header: unknown key 'frame' (std_msgs/Header"},
  };
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.text) {
      const std::string m = sceneError(c.text);
      BOOST_TEST(contains(m, c.message_part), m);
      BOOST_TEST(contains(m, "SceneLoadOptions::unknown_keys_are_warnings"));
    }
  }
}

BOOST_AUTO_TEST_CASE(duplicate_keys_are_errors_even_as_warnings) {
  const std::string text = sceneWith(
      "      pose: {position: [1, 0, 0], orientation: [0, 0, 0, 1]}\n"
      "      pose: {position: [2, 0, 0], orientation: [0, 0, 0, 1]}\n");
  const std::string expected =
      "keys.yaml:7: object 'box': duplicate key 'pose' (first at keys.yaml:6; YAML keys must be "
      "unique)";
  BOOST_TEST(sceneError(text) == expected);
  dss::SceneLoadOptions o;
  o.unknown_keys_are_warnings = true;
  BOOST_TEST(sceneError(text, o) == expected);
}

BOOST_AUTO_TEST_CASE(every_message_field_is_accepted) {
  // Fields that the reader does not use but the messages have are not unknown keys.
  const std::string text =
      "name: s\nis_diff: false\nrobot_model_name: r\nlink_padding: []\nlink_scale: []\n"
      "object_colors: []\n"
      "robot_state:\n  is_diff: false\n  attached_collision_objects: []\n"
      "  joint_state: {header: {frame_id: ''}, name: [a], position: [1], velocity: [], effort: "
      "[]}\n"
      "  multi_dof_joint_state: {header: {seq: 0, stamp: 0, frame_id: ''}, joint_names: [], "
      "transforms: [], twist: [], wrench: []}\n"
      "world:\n  octomap: {}\n  collision_objects:\n"
      "    - {header: {frame_id: ''}, id: b, type: {key: '', db: ''}, operation: 0, planes: [], "
      "plane_poses: [], subframe_names: [], subframe_poses: [], meshes: [], mesh_poses: [], "
      "pose: {position: {x: 0, y: 0, z: 0}, orientation: {x: 0, y: 0, z: 0, w: 1}}, "
      "primitives: [{type: 1, dimensions: [1, 1, 1], polygon: {}}], primitive_poses: "
      "[{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]}\n";
  const dss::Scene s = dss::parsePlanningSceneYaml(text, "all.yaml");
  BOOST_TEST(s.obstacles.size() == 1u);
}

BOOST_AUTO_TEST_CASE(request_keys) {
  // The reader's own sample parses; each misspelling is an error naming key and line.
  BOOST_TEST(dss::parsePlanRequestYaml(kRequest, "r.yaml").goals.size() == 1u);
  struct Case {
    std::string text;
    std::string message_part;
  };
  const std::vector<Case> cases = {
      {std::string(kRequest) + "goal_constraint: []\n",
       "r.yaml:7: request: unknown key 'goal_constraint' (moveit_msgs/MotionPlanRequest has "},
      {"group_name: arm\nstart_state:\n  joint_states: {name: [j], position: [0]}\n"
       "goal_constraints: [{joint_constraints: [{joint_name: j, position: 1}]}]\n",
       "r.yaml:3: start_state: unknown key 'joint_states' (moveit_msgs/RobotState has "},
      {"group_name: arm\nstart_state: {}\n"
       "goal_constraints: [{joint_constraints: [{joint_name: j, Position: 1}]}]\n",
       "r.yaml:3: goal_constraints[0] joint constraint: unknown key 'Position' "
       "(moveit_msgs/JointConstraint has joint_name, position, tolerance_above, "
       "tolerance_below, weight; did you mean 'position'?)"},
      {"group_name: arm\nstart_state: {}\n"
       "goal_constraints: [{joint_constraint: [], joint_constraints: [{joint_name: j, "
       "position: 1}]}]\n",
       "r.yaml:3: goal_constraints[0]: unknown key 'joint_constraint' (moveit_msgs/Constraints"},
  };
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.text) {
      const std::string m =
          thrownMessage<dss::SceneError>([&] { dss::parsePlanRequestYaml(c.text, "r.yaml"); });
      BOOST_TEST(contains(m, c.message_part), m);
      BOOST_TEST(contains(m, "PlanRequestOptions::unknown_keys_are_warnings = true"));
    }
  }
  dss::PlanRequestOptions o;
  o.unknown_keys_are_warnings = true;
  const dss::PlanRequest r =
      dss::parsePlanRequestYaml(std::string(kRequest) + "goal_constraint: []\n", "r.yaml", o);
  BOOST_REQUIRE(r.warnings.size() == 1u);
  BOOST_TEST(contains(r.warnings[0], "r.yaml:7: request: unknown key 'goal_constraint'"));
  // Duplicates stay errors.
  BOOST_TEST(contains(thrownMessage<dss::SceneError>([&] {
                        dss::parsePlanRequestYaml(std::string(kRequest) + "group_name: b\n",
                                                  "r.yaml", o);
                      }),
                      "r.yaml:7: request: duplicate key 'group_name' (first at r.yaml:1"));
}

BOOST_AUTO_TEST_CASE(long_keys_are_cut_in_messages) {
  const std::string key(1000, 'k');  // YAML's longest implicit key is 1024 characters
  const std::string m = sceneError(sceneWith("      " + key + ": 1\n"));
  BOOST_TEST(contains(m, "unknown key '" + std::string(64, 'k') + "...'"), m);
  BOOST_TEST(m.size() < 600u);
}

BOOST_AUTO_TEST_SUITE_END()
