// YAML aliases let a short file stand for a huge one: a 60 KB scene of a thousand objects that
// share one aliased list of a thousand primitives (a million obstacles), or an allowed
// collision matrix whose rows are all one alias (millions of pairs). The readers count after
// alias expansion and refuse, before reading, whatever exceeds SceneInputLimits, naming the
// file, the line, the limit and the option that raises it.
#include <boost/test/unit_test.hpp>
#include <string>

#include "dss/scene/plan_request.h"
#include "dss/scene/planning_scene_yaml.h"
#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"
#include "scene/scene_test_util.h"

using namespace dss_test;

namespace {

// "[&a X, *a, *a, ...]" with `n` entries.
std::string aliasedList(const std::string& anchor, const std::string& first, std::size_t n) {
  std::string s = "[&" + anchor + " " + first;
  for (std::size_t i = 1; i < n; ++i) s += ", *" + anchor;
  return s + "]";
}

// `objects` collision objects ("box", "box2", ...: ids are unique), each with the same
// aliased list of `prims` boxes.
std::string amplifiedScene(std::size_t objects, std::size_t prims) {
  std::string s = "world:\n  collision_objects:\n    - id: box\n      primitives: &B " +
                  aliasedList("b", "{type: box, dimensions: [0.1, 0.1, 0.1]}", prims) +
                  "\n      primitive_poses: &P " +
                  aliasedList("p", "{position: [0, 0, 0], orientation: [0, 0, 0, 1]}", prims) +
                  "\n";
  for (std::size_t i = 1; i < objects; ++i)
    s += "    - {id: box" + std::to_string(i + 1) + ", primitives: *B, primitive_poses: *P}\n";
  return s;
}

std::string sceneError(const std::string& text, const dss::SceneLoadOptions& options = {}) {
  return thrownMessage<dss::SceneError>(
      [&] { dss::parsePlanningSceneYaml(text, "amplified.yaml", options); });
}

}  // namespace

BOOST_AUTO_TEST_SUITE(yaml_alias_budgets)

// The reproducer: 1000 x 1000 = 1 000 000 obstacles from a few kilobytes.
BOOST_AUTO_TEST_CASE(a_million_obstacles_are_refused_before_reading) {
  const std::string text = amplifiedScene(1000, 1000);
  BOOST_TEST(text.size() < 70000u);
  const std::string path = writeScratch("amplified.yaml", text);
  const std::string m = thrownMessage<dss::SceneError>([&] { dss::loadScene(path); });
  BOOST_TEST(m == path +
                      ":3: world.collision_objects: 1000000 primitives and meshes in 1000 objects "
                      "exceeds the limit of 100000 (SceneInputLimits::max_obstacles; raise it "
                      "with SceneLoadOptions::limits.max_obstacles)");
}

BOOST_AUTO_TEST_CASE(obstacle_and_shape_limits_are_exact) {
  dss::SceneLoadOptions o;
  o.limits.max_obstacles = 11;  // 3 objects x 4 boxes = 12
  BOOST_TEST(contains(sceneError(amplifiedScene(3, 4), o),
                      "12 primitives and meshes in 3 objects exceeds the limit of 11"));
  o.limits.max_obstacles = 12;
  BOOST_TEST(dss::parsePlanningSceneYaml(amplifiedScene(3, 4), "ok.yaml", o).obstacles.size() ==
             12u);
  o.limits.max_shapes_per_object = 3;
  BOOST_TEST(sceneError(amplifiedScene(3, 4), o) ==
             "amplified.yaml:3: object 'box': 4 primitives and meshes exceeds the limit of 3 "
             "(SceneInputLimits::max_shapes_per_object; raise it with "
             "SceneLoadOptions::limits.max_shapes_per_object)");
  // The default per-object limit, with aliases: one object of 20 000 boxes.
  BOOST_TEST(contains(sceneError(amplifiedScene(1, 20000)),
                      "object 'box': 20000 primitives and meshes exceeds the limit of 10000"));
}

// The reproducer: 1414 names, every row the same alias: 2 million allowed pairs.
BOOST_AUTO_TEST_CASE(an_aliased_collision_matrix_is_refused) {
  std::string names, row = "&r [true";
  for (int i = 0; i < 1414; ++i) names += (i ? ", n" : "n") + std::to_string(i);
  for (int i = 1; i < 1414; ++i) row += ", true";
  row += "]";
  std::string values = row;
  for (int i = 1; i < 1414; ++i) values += ", *r";
  const std::string text = "allowed_collision_matrix:\n  entry_names: [" + names +
                           "]\n  entry_values: [" + values + "]\n";
  BOOST_TEST(text.size() < 45000u);
  BOOST_TEST(sceneError(text) ==
             "amplified.yaml:2: allowed_collision_matrix: 1414 entry_names exceeds the limit of "
             "1000 (SceneInputLimits::max_acm_entries; raise it with "
             "SceneLoadOptions::limits.max_acm_entries)");
  // Exact limits, on a small matrix (read in full when allowed).
  const std::string small =
      "allowed_collision_matrix:\n  entry_names: [a, b, c]\n  entry_values: [&t [true, true, "
      "true], *t, *t]\n  default_entry_names: [d, e, f]\n  default_entry_values: [true, "
      "false, true]\n";
  dss::SceneLoadOptions o;
  o.limits.max_acm_entries = 2;
  BOOST_TEST(contains(sceneError(small, o),
                      "amplified.yaml:2: allowed_collision_matrix: 3 entry_names exceeds the "
                      "limit of 2"));
  o.limits.max_acm_entries = 3;
  const dss::Scene s = dss::parsePlanningSceneYaml(small, "acm.yaml", o);
  BOOST_TEST(s.allowed_collisions.pairs().size() == 3u);
  BOOST_TEST(s.allowed_collisions.alwaysAllowed().size() == 2u);
  const std::string defaults =
      "allowed_collision_matrix:\n  default_entry_names: [a, b, c]\n  default_entry_values: "
      "[true, true, true]\n";
  o.limits.max_acm_entries = 2;
  BOOST_TEST(contains(sceneError(defaults, o),
                      "amplified.yaml:2: allowed_collision_matrix: 3 default_entry_names exceeds "
                      "the limit of 2 (SceneInputLimits::max_acm_entries"));
}

// Attached objects: 1000 objects sharing one list of 1000 touch links (a million names), and
// 1000 sharing 1000 primitives, each refused before any object is read.
BOOST_AUTO_TEST_CASE(aliased_attached_objects_are_bounded) {
  auto attached = [](const std::string& touch, const std::string& prims, const std::string& poses) {
    std::string s =
        "robot_state:\n  attached_collision_objects:\n    - link_name: hand\n"
        "      touch_links: &T " +
        touch + "\n      object: {id: o, primitives: &B " + prims + ", primitive_poses: &P " +
        poses + "}\n";
    for (int i = 1; i < 1000; ++i)
      s += "    - {link_name: hand, touch_links: *T, object: {id: o" + std::to_string(i) +
           ", primitives: *B, primitive_poses: *P}}\n";
    return s;
  };
  const std::string box = "{type: box, dimensions: [0.1, 0.1, 0.1]}";
  const std::string pose = "{position: [0, 0, 0], orientation: [0, 0, 0, 1]}";
  std::string m =
      sceneError(attached(aliasedList("t", "finger", 1000), "[" + box + "]", "[" + pose + "]"));
  BOOST_TEST(m == "amplified.yaml:3: robot_state.attached_collision_objects: 1000000 touch "
                  "links exceeds the limit of 1000 (SceneInputLimits::max_acm_entries; raise it "
                  "with SceneLoadOptions::limits.max_acm_entries)",
             m);
  m = sceneError(attached("[finger]", aliasedList("b", box, 1000), aliasedList("p", pose, 1000)));
  BOOST_TEST(m == "amplified.yaml:3: robot_state.attached_collision_objects: 1000000 primitives "
                  "and meshes after 0 obstacles exceeds the limit of 100000 "
                  "(SceneInputLimits::max_obstacles; raise it with "
                  "SceneLoadOptions::limits.max_obstacles)",
             m);
  // Within the limits the same shape of file reads: 1000 objects of one box and one touch link.
  const dss::Scene ok = dss::parsePlanningSceneYaml(
      attached("[finger]", "[" + box + "]", "[" + pose + "]"), "ok.yaml");
  BOOST_TEST(ok.attached.size() == 1000u);
}

BOOST_AUTO_TEST_CASE(aliased_mesh_vertices_are_bounded) {
  // One inline mesh of 1000 vertices (one aliased point and a tetrahedron), used by 3 objects.
  std::string verts = "[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], &v [0.1, 0.1, 0.1]";
  for (int i = 5; i < 1000; ++i) verts += ", *v";
  verts += "]";
  const std::string text =
      "world:\n  collision_objects:\n    - id: m\n      meshes: &M [{vertices: " + verts +
      "}]\n      mesh_poses: &P [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n    - {id: "
      "m2, meshes: *M, mesh_poses: *P}\n    - {id: m3, meshes: *M, mesh_poses: *P}\n";
  dss::SceneLoadOptions o;
  o.limits.max_mesh_vertices = 999;
  BOOST_TEST(contains(sceneError(text, o),
                      "amplified.yaml:4: object 'm' mesh 0: a mesh of 1000 vertices exceeds the "
                      "limit of 999 (SceneInputLimits::max_mesh_vertices; raise it with "
                      "SceneLoadOptions::limits.max_mesh_vertices)"));
  o.limits.max_mesh_vertices = 1000;
  o.limits.max_scene_mesh_vertices = 2999;
  BOOST_TEST(contains(sceneError(text, o),
                      "the scene's mesh vertices (2000 before this mesh of 1000 vertices) exceeds "
                      "the limit of 2999 (SceneInputLimits::max_scene_mesh_vertices"));
  o.limits.max_scene_mesh_vertices = 3000;
  const dss::Scene s = dss::parsePlanningSceneYaml(text, "mesh.yaml", o);
  BOOST_TEST(s.obstacles.size() == 3u);
  // Triangles of one mesh.
  o.limits.max_mesh_triangles = 1;
  BOOST_TEST(contains(sceneError("world:\n  collision_objects:\n    - id: t\n      meshes: "
                                 "[{vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], triangles: "
                                 "[[0, 1, 2], [0, 2, 1]]}]\n      mesh_poses: [{position: [0, 0, "
                                 "0], orientation: [0, 0, 0, 1]}]\n",
                                 o),
                      "object 't' mesh 0: 2 triangles exceeds the limit of 1 "
                      "(SceneInputLimits::max_mesh_triangles"));
}

BOOST_AUTO_TEST_CASE(aliased_request_goals_are_bounded) {
  // 1000 goals (one aliased) of 1000 constraints (one aliased): a million joint values.
  std::string text =
      "group_name: arm\nstart_state:\n  joint_state: {name: [j], position: [0]}\n"
      "goal_constraints: " +
      aliasedList(
          "g",
          "{joint_constraints: " + aliasedList("c", "{joint_name: j, position: 0}", 1000) + "}",
          1000) +
      "\n";
  const std::string m =
      thrownMessage<dss::SceneError>([&] { dss::parsePlanRequestYaml(text, "request.yaml"); });
  BOOST_TEST(m ==
             "request.yaml:4: goal_constraints: 1000000 joint constraints in 1000 goals (and 1 "
             "start joints) exceeds the limit of 100000 "
             "(SceneInputLimits::max_request_joint_values; raise it with "
             "PlanRequestOptions::limits.max_request_joint_values)");
  // Exact limit: 1 start joint and 3 goals of 2 constraints are 7 joint values.
  const std::string small =
      "group_name: arm\nstart_state:\n  joint_state: {name: [j], position: [0]}\n"
      "goal_constraints: " +
      aliasedList(
          "g", "{joint_constraints: " + aliasedList("c", "{joint_name: j, position: 0}", 2) + "}",
          3) +
      "\n";
  dss::PlanRequestOptions o;
  o.limits.max_request_joint_values = 7;
  BOOST_TEST(dss::parsePlanRequestYaml(small, "request.yaml", o).goals.size() == 3u);
  o.limits.max_request_joint_values = 6;
  BOOST_TEST(contains(
      thrownMessage<dss::SceneError>([&] { dss::parsePlanRequestYaml(small, "request.yaml", o); }),
      "6 joint constraints in 3 goals (and 1 start joints) exceeds the limit of 6"));
  // The start state alone.
  o.limits.max_request_joint_values = 0;
  BOOST_TEST(contains(
      thrownMessage<dss::SceneError>([&] { dss::parsePlanRequestYaml(small, "request.yaml", o); }),
      "request.yaml:3: start_state: 1 joints exceeds the limit of 0"));
}

// Nesting: yaml-cpp bounds its own recursion (2000 levels) and throws; the reader turns that
// into a malformed-YAML error with the line, for a scene and for a request.
BOOST_AUTO_TEST_CASE(deep_yaml_nesting_is_a_malformed_yaml_error) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string scene = sceneError("world:\n  collision_objects: " + deep + "\n");
  BOOST_TEST(scene.rfind("amplified.yaml:2:", 0) == 0u, scene);
  BOOST_TEST(contains(scene, "malformed YAML"), scene);
  const std::string request = thrownMessage<dss::SceneError>(
      [&] { dss::parsePlanRequestYaml("group_name: " + deep + "\n", "request.yaml"); });
  BOOST_TEST(request.rfind("request.yaml:1:", 0) == 0u, request);
  BOOST_TEST(contains(request, "malformed YAML"), request);
}

BOOST_AUTO_TEST_SUITE_END()
