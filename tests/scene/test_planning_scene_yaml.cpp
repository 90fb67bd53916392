// PlanningScene YAML: every MotionBenchMaker scene and template loads with the right objects,
// object poses compose with primitive poses, and bad input is refused with a message that
// names the file, the line and the object.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>

#include "dss/scene/planning_scene_yaml.h"
#include "dss/scene/scene_error.h"
#include "scene/scene_test_util.h"
#include "support/shared_data.h"

using namespace dss_test;

namespace {

struct TypeCounts {
  int objects, cylinders, boxes;
};

// MANIFEST.md of the shared scenes: every scene of a type has the same object set.
const std::map<std::string, TypeCounts> kExpected = {{"bookshelf_small", {7, 3, 4}},
                                                     {"bookshelf_tall", {15, 9, 6}},
                                                     {"bookshelf_thin", {21, 10, 11}},
                                                     {"box", {7, 1, 6}},
                                                     {"cage", {8, 0, 8}},
                                                     {"table_pick", {12, 2, 10}},
                                                     {"table_under_pick", {12, 2, 10}}};

// Independent count from the text: one "type: <primitive>" line per primitive.
int countTypeLines(const std::string& text, const std::string& type) {
  const std::regex re("^\\s*(- )?type:\\s*" + type + "\\s*$");
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line))
    if (std::regex_match(line, re)) ++n;
  return n;
}

std::map<std::string, int> shapeCounts(const dss::Scene& s) {
  std::map<std::string, int> m;
  for (const auto& o : s.obstacles) m[dss::shapeTypeName(o.shape)]++;
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planning_scene_yaml)

BOOST_AUTO_TEST_CASE(all_mbm_scenes_load_with_their_objects, DSS_NEEDS_SHARED) {
  requireShared();
  int files = 0;
  for (const char* robot : {"mbm_panda", "mbm_ur5"}) {
    for (const auto& f : filesMatching(scenesDir() + "/" + robot, "scene[0-9]+\\.yaml")) {
      BOOST_TEST_CONTEXT(f) {
        const std::string type = std::filesystem::path(f).parent_path().filename().string();
        const dss::Scene s = dss::loadPlanningSceneYaml(f);
        const std::string text = readAll(f);
        const auto counts = shapeCounts(s);
        BOOST_REQUIRE(kExpected.count(type));
        const TypeCounts& want = kExpected.at(type);
        BOOST_TEST(static_cast<int>(s.obstacles.size()) == want.objects);
        BOOST_TEST(static_cast<int>(s.objectIds().size()) == want.objects);
        BOOST_TEST((counts.count("box") ? counts.at("box") : 0) == want.boxes);
        BOOST_TEST((counts.count("cylinder") ? counts.at("cylinder") : 0) == want.cylinders);
        BOOST_TEST(countTypeLines(text, "box") == want.boxes);
        BOOST_TEST(countTypeLines(text, "cylinder") == want.cylinders);
        BOOST_TEST(s.unresolvedFrames().empty());
        BOOST_TEST(s.warnings.empty());
        BOOST_TEST(!s.robot_state.empty());
        BOOST_TEST(!s.allowed_collisions.empty());
        for (const auto& o : s.obstacles) {
          BOOST_TEST(o.frame_resolved);
          BOOST_TEST(o.X_WO.translation().allFinite());
          BOOST_TEST(std::abs(o.X_WO.linear().determinant() - 1.0) < 1e-12);
        }
        ++files;
      }
    }
  }
  BOOST_TEST(files == 7 * 10 + 7 * 5);
}

BOOST_AUTO_TEST_CASE(panda_scene_state_and_acm, DSS_NEEDS_SHARED) {
  requireShared();
  const dss::Scene s = dss::loadPlanningSceneYaml(scenesDir() + "/mbm_panda/box/scene0001.yaml");
  BOOST_TEST(s.robot_model_name == "panda");
  BOOST_TEST(s.robot_state.size() == 9u);
  BOOST_TEST(s.robot_state.at("panda_finger_joint1") == 0.0);  // the request says 0.065
  BOOST_TEST(s.fixed_frames.count("world") == 1u);
  // Adjacent links of the Panda are allowed to touch; the base and the hand are not.
  BOOST_TEST(s.allowed_collisions.allowed("panda_link0", "panda_link1"));
  BOOST_TEST(s.allowed_collisions.allowed("panda_link1", "panda_link0"));
  BOOST_TEST(!s.allowed_collisions.allowed("panda_link0", "panda_hand"));
}

// UR5 table_pick: object-level pose composed with the primitive pose (X_WO = pose * prim).
BOOST_AUTO_TEST_CASE(ur5_table_pick_poses_are_composed, DSS_NEEDS_SHARED) {
  requireShared();
  const dss::Scene s =
      dss::loadPlanningSceneYaml(scenesDir() + "/mbm_ur5/table_pick/scene0001.yaml");
  const dss::Obstacle* can = nullptr;
  const dss::Obstacle* top = nullptr;
  for (const auto& o : s.obstacles) {
    if (o.name == "Can1") can = &o;
    if (o.name == "table_top") top = &o;
  }
  BOOST_REQUIRE(can && top);
  // By hand from the file: pose p = (-0.06371788662107358, -0.1102475820769556,
  // 0.08705641176758652), q = (0, 0, z = 0.9972514405491772, w = 0.07409159414259425), a
  // rotation about z by theta with cos = w^2 - z^2, sin = 2 z w (after normalising);
  // primitive at (0.85, 0, 0.8): p + (0.85 cos, 0.85 sin, 0.8).
  const double z = 0.9972514405491772, w = 0.07409159414259425, n = std::hypot(z, w);
  const double c = (w * w - z * z) / (n * n), sn = 2 * z * w / (n * n);
  const Eigen::Vector3d expected(-0.06371788662107358 + 0.85 * c, -0.1102475820769556 + 0.85 * sn,
                                 0.08705641176758652 + 0.8);
  // The same, evaluated once outside the program: (-0.904385627272669, 0.015361931208232468,
  // 0.8870564117675865).
  BOOST_TEST((can->X_WO.translation() - expected).norm() < 1e-12);
  BOOST_TEST((can->X_WO.translation() -
              Eigen::Vector3d(-0.904385627272669, 0.015361931208232468, 0.8870564117675865))
                 .norm() < 1e-12);
  // Ignoring `pose` would have put the can at its primitive position (0.85, 0, 0.8).
  BOOST_TEST((can->X_WO.translation() - Eigen::Vector3d(0.85, 0, 0.8)).norm() > 1.0);
  // The can stands inside the table top's footprint (in the table's frame).
  const Eigen::Vector3d p_T = top->X_WO.inverse() * can->X_WO.translation();
  const auto& half = std::get<dss::Box>(top->shape).half;
  BOOST_TEST(std::abs(p_T.x()) < half.x());
  BOOST_TEST(std::abs(p_T.y()) < half.y());
  BOOST_TEST(p_T.z() > half.z());
  // The rotation composes too: the object's yaw (the primitive's is identity).
  const Eigen::Matrix3d R = can->X_WO.linear();
  BOOST_TEST(std::abs(R(0, 0) - c) < 1e-12);
  BOOST_TEST(std::abs(R(1, 0) - sn) < 1e-12);
}

BOOST_AUTO_TEST_CASE(templates_load_in_base_link_frame, DSS_NEEDS_SHARED) {
  requireShared();
  const auto files =
      filesMatching(scenesDir() + "/mbm_templates/configs/scenes", "scene_.*\\.yaml");
  BOOST_TEST(files.size() == 6u);
  for (const auto& f : files) {
    BOOST_TEST_CONTEXT(f) {
      dss::Scene s = dss::loadPlanningSceneYaml(f);
      const std::string text = readAll(f);
      BOOST_TEST(static_cast<int>(s.obstacles.size()) ==
                 countTypeLines(text, "box") + countTypeLines(text, "cylinder"));
      BOOST_TEST(s.unresolvedFrames() == std::vector<std::string>{"base_link"});
      // Unknown frame: an error that names the frame and an object.
      const std::string msg =
          thrownMessage<dss::SceneError>([&] { dss::resolveFrames(s, dss::FrameMap{}, true); });
      BOOST_TEST(contains(msg, "base_link"));
      BOOST_TEST(contains(msg, f));
      dss::FrameMap frames;
      Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
      X_WB.translation() = Eigen::Vector3d(0.2, 0.4, -0.7);
      frames["base_link"] = X_WB;
      dss::resolveFrames(s, frames);
      BOOST_TEST(s.unresolvedFrames().empty());
      for (const auto& o : s.obstacles)
        BOOST_TEST((o.X_WO.translation() - (o.X_FO.translation() + X_WB.translation())).norm() <
                   1e-12);
    }
  }
}

BOOST_AUTO_TEST_CASE(inline_mesh_map_forms_and_all_primitives) {
  const std::string text = R"(world:
  collision_objects:
    - id: thing
      header: {frame_id: world}
      pose: {position: {x: 1, y: 0, z: 0}, orientation: {x: 0, y: 0, z: 0, w: 1}}
      primitives:
        - {type: sphere, dimensions: [0.5]}
        - {type: cone, dimensions: [0.4, 0.1]}
        - {type: 3, dimensions: [2.0, 0.25]}
      primitive_poses:
        - {position: [0, 0, 1], orientation: [0, 0, 0, 2]}
        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}
        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}
      meshes:
        - vertices: [[0,0,0],[1,0,0],[0,1,0],[0,0,1],[1,1,1],[0.2,0.2,0.2]]
          triangles: [{vertex_indices: [0,1,2]}, [0,1,3]]
      mesh_poses:
        - {position: [0, 2, 0], orientation: [0, 0, 0, 1]}
)";
  const dss::Scene s = dss::parsePlanningSceneYaml(text, "inline.yaml");
  // The mesh: its triangles' part, then the two vertices no triangle uses.
  BOOST_REQUIRE(s.obstacles.size() == 5u);
  BOOST_TEST(s.obstacles[0].name == "thing/0");
  BOOST_TEST(s.obstacles[3].name == "thing/3");
  BOOST_TEST(s.obstacles[4].name == "thing/4");
  BOOST_TEST(std::get<dss::Sphere>(s.obstacles[0].shape).radius == 0.5);
  BOOST_TEST((s.obstacles[0].X_WO.translation() - Eigen::Vector3d(1, 0, 1)).norm() < 1e-15);
  const auto& cone = std::get<dss::Cone>(s.obstacles[1].shape);
  BOOST_TEST(cone.radius == 0.1);
  BOOST_TEST(cone.half_length == 0.2);
  const auto& cyl = std::get<dss::Cylinder>(s.obstacles[2].shape);
  BOOST_TEST(cyl.radius == 0.25);  // [height, radius]
  BOOST_TEST(cyl.half_length == 1.0);
  BOOST_TEST(std::get<dss::ConvexHull>(s.obstacles[3].shape).size() == 4u);
  BOOST_TEST((s.obstacles[3].X_WO.translation() - Eigen::Vector3d(1, 2, 0)).norm() < 1e-15);
  const dss::Aabb box = dss::worldAabb(s.obstacles[3]);
  BOOST_TEST((box.lower - Eigen::Vector3d(1, 2, 0)).norm() < 1e-15);
  BOOST_TEST((box.upper - Eigen::Vector3d(2, 3, 1)).norm() < 1e-15);
  BOOST_TEST(std::get<dss::ConvexHull>(s.obstacles[4].shape).size() == 2u);
  const dss::Aabb unused = dss::worldAabb(s.obstacles[4]);
  BOOST_TEST((unused.lower - Eigen::Vector3d(1.2, 2.2, 0.2)).norm() < 1e-15);
  BOOST_TEST((unused.upper - Eigen::Vector3d(2, 3, 1)).norm() < 1e-15);
  BOOST_TEST(s.obstacles[4].description.find("mesh 0 part 1 of 2") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(mesh_by_resource, DSS_NEEDS_SHARED) {
  requireShared();
  const std::string stl =
      scenesDir() + "/mbm_templates/configs/scenes/kitchen/meshes/cupboard_door_l.stl";
  const std::string text =
      "world:\n  collision_objects:\n    - id: door\n      meshes:\n"
      "        - resource: file://" +
      stl +
      "\n"
      "          dimensions: [2, 2, 2]\n"
      "      mesh_poses:\n        - position: [0, 0, 0]\n"
      "          orientation: [0, 0, 0, 1]\n";
  const dss::Scene s = dss::parsePlanningSceneYaml(text, "/tmp/inline.yaml");
  // The door's panel and its handle, apart: one hull each.
  BOOST_REQUIRE(s.obstacles.size() == 2u);
  BOOST_TEST(s.obstacles[0].name == "door/0");
  BOOST_TEST(s.obstacles[1].name == "door/1");
  for (const auto& o : s.obstacles) {
    BOOST_TEST(o.object_id == "door");
    BOOST_TEST(std::get<dss::ConvexHull>(o.shape).size() >= 4u);
  }
  // Missing resource: the error names the URI and the object.
  const std::string bad =
      "world:\n  collision_objects:\n    - id: ghost\n      meshes:\n"
      "        - resource: package://nowhere/x.stl\n"
      "      mesh_poses:\n        - position: [0, 0, 0]\n"
      "          orientation: [0, 0, 0, 1]\n";
  const std::string msg =
      thrownMessage<dss::SceneError>([&] { dss::parsePlanningSceneYaml(bad, "/tmp/ghost.yaml"); });
  BOOST_TEST(contains(msg, "package://nowhere/x.stl"));
  BOOST_TEST(contains(msg, "'ghost'"));
  BOOST_TEST(contains(msg, "/tmp/ghost.yaml:"));
}

BOOST_AUTO_TEST_CASE(bad_input_names_file_line_and_object) {
  const std::string head = "world:\n  collision_objects:\n    - id: Crate\n";
  const std::string prims =
      "      primitives:\n        - type: box\n          dimensions: [1, 1, 1]\n";
  const std::string poses =
      "      primitive_poses:\n        - position: [0, 0, 0]\n          orientation: ";
  auto msgOf = [](const std::string& text) {
    return thrownMessage<dss::SceneError>([&] { dss::parsePlanningSceneYaml(text, "bad.yaml"); });
  };
  // Malformed YAML: the line of the error.
  std::string m = msgOf("world:\n  collision_objects:\n    - id: [unclosed\n");
  BOOST_TEST(contains(m, "bad.yaml:"));
  BOOST_TEST(contains(m, "malformed YAML"));
  m = msgOf("a: 1\n b: 2\n  - c\n");
  BOOST_TEST(contains(m, "bad.yaml:"));
  // Missing field.
  m = msgOf(head + prims);
  BOOST_TEST(contains(m, "Crate"));
  BOOST_TEST(contains(m, "primitive_poses"));
  BOOST_TEST(contains(m, "bad.yaml:3"));
  m = msgOf("world:\n  collision_objects:\n    - primitives: []\n");
  BOOST_TEST(contains(m, "missing field 'id'"));
  // NaN and zero quaternions.
  m = msgOf(head + prims + poses + "[0, 0, .nan, 1]\n");
  BOOST_TEST(contains(m, "Crate"));
  BOOST_TEST(contains(m, "non-finite quaternion"));
  BOOST_TEST(contains(m, "bad.yaml:9"));
  m = msgOf(head + prims + poses + "[0, 0, 0, 0]\n");
  BOOST_TEST(contains(m, "zero quaternion"));
  BOOST_TEST(contains(m, "Crate"));
  // Negative size.
  m = msgOf(head + "      primitives:\n        - type: box\n          dimensions: [1, -2, 1]\n" +
            poses + "[0, 0, 0, 1]\n");
  BOOST_TEST(contains(m, "negative"));
  BOOST_TEST(contains(m, "Crate"));
  BOOST_TEST(contains(m, "bad.yaml:6"));
  // Unknown primitive type.
  m = msgOf(head + "      primitives:\n        - type: torus\n          dimensions: [1, 1]\n" +
            poses + "[0, 0, 0, 1]\n");
  BOOST_TEST(contains(m, "unknown primitive type 'torus'"));
  BOOST_TEST(contains(m, "Crate"));
  BOOST_TEST(contains(m, "bad.yaml:5"));
  // Wrong number of dimensions.
  m = msgOf(head + "      primitives:\n        - type: cylinder\n          dimensions: [1]\n" +
            poses + "[0, 0, 0, 1]\n");
  BOOST_TEST(contains(m, "needs 2 dimensions"));
  // Not a number.
  m = msgOf(head + "      primitives:\n        - type: sphere\n          dimensions: [big]\n" +
            poses + "[0, 0, 0, 1]\n");
  BOOST_TEST(contains(m, "'big'"));
  // Planes are unbounded.
  m = msgOf(head + "      planes:\n        - coef: [0, 0, 1, 0]\n      plane_poses: []\n");
  BOOST_TEST(contains(m, "planes"));
  // A missing file.
  m = thrownMessage<dss::SceneError>([] { dss::loadPlanningSceneYaml("/nonexistent/scene.yaml"); });
  BOOST_TEST(contains(m, "/nonexistent/scene.yaml"));
}

BOOST_AUTO_TEST_SUITE_END()
