// MoveIt .scene text: the shared files in both formats, object poses in the new format,
// meshes, and errors with line numbers.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <map>

#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"
#include "dss/scene/scene_text.h"
#include "scene/scene_test_util.h"
#include "support/shared_data.h"

using namespace dss_test;

BOOST_AUTO_TEST_SUITE(scene_text)

BOOST_AUTO_TEST_CASE(shared_scene_files_load, DSS_NEEDS_SHARED) {
  requireShared();
  // file -> (obstacles, objects); MANIFEST.md of the shared scenes.
  const std::map<std::string, std::pair<int, int>> expected = {
      {"example_box.scene", {1, 1}},
      {"example_distance.scene", {1, 1}},
      {"example_manipulate.scene", {3, 3}},
      {"example_moving_obstacle.scene", {1, 1}},
      {"g03_open_back_storage_shelf.scene", {8, 1}},
      {"kallax.scene", {8, 1}},
      {"baxter_pillar.scene", {1, 1}},
      {"publish_scene.scene", {1, 1}}};
  const auto files = filesMatching(scenesDir() + "/moveit_scene_files", ".*\\.scene");
  BOOST_TEST(files.size() == expected.size());
  for (const auto& f : files) {
    BOOST_TEST_CONTEXT(f) {
      const std::string name = std::filesystem::path(f).filename().string();
      BOOST_REQUIRE(expected.count(name));
      const dss::Scene s = dss::loadScene(f);
      BOOST_TEST(static_cast<int>(s.obstacles.size()) == expected.at(name).first);
      BOOST_TEST(static_cast<int>(s.objectIds().size()) == expected.at(name).second);
      BOOST_TEST(s.warnings.empty());
      for (const auto& o : s.obstacles) BOOST_TEST(o.shape.index() == 1u);  // boxes
    }
  }
}

BOOST_AUTO_TEST_CASE(old_format_details, DSS_NEEDS_SHARED) {
  requireShared();
  const dss::Scene s =
      dss::loadSceneText(scenesDir() + "/moveit_scene_files/exotica/example_box.scene");
  BOOST_TEST(s.name == "ExampleScene");
  BOOST_REQUIRE(s.obstacles.size() == 1u);
  // Quaternion (0, 0, 0.968912, -0.247404), normalised: a rotation about z.
  const double z = 0.968912, w = -0.247404, n = std::hypot(z, w);
  const Eigen::Quaterniond q(w / n, 0, 0, z / n);
  BOOST_TEST((s.obstacles[0].X_WO.linear() - q.toRotationMatrix()).norm() < 1e-12);
  const auto& box = std::get<dss::Box>(s.obstacles[0].shape);
  BOOST_TEST((box.half - Eigen::Vector3d(0.05, 0.05, 0.05)).norm() < 1e-15);

  const dss::Scene shelf = dss::loadSceneText(
      scenesDir() + "/moveit_scene_files/exotica/g03_open_back_storage_shelf.scene");
  BOOST_TEST(shelf.obstacles[2].name == "Shelf/2");
  BOOST_TEST((shelf.obstacles[2].X_WO.translation() - Eigen::Vector3d(-0.4575, 0, 1.0225)).norm() <
             1e-15);
}

BOOST_AUTO_TEST_CASE(new_format_object_pose_composes) {
  const std::string text =
      "composed\n"
      "* obj\n"
      "1 2 3\n"
      "0 0 0.7071067811865476 0.7071067811865476\n"  // 90 degrees about z
      "2\n"
      "box\n0.1 0.2 0.3\n1 0 0\n0 0 0 1\n0 0 0 0\n"
      "cylinder\n0.5 2\n0 0 0\n0 0 0 1\n1 0 0 1\n"
      "1\n"
      "tip\n0 0 1\n0 0 0 1\n"
      "* second\n"
      "0 0 0\n0 0 0 1\n1\nsphere\n0.25\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
      ".\n";
  const dss::Scene s = dss::parseSceneText(text, "composed.scene");
  BOOST_REQUIRE(s.obstacles.size() == 3u);
  // (1, 0, 0) rotated by 90 degrees about z is (0, 1, 0); plus the object position.
  BOOST_TEST((s.obstacles[0].X_WO.translation() - Eigen::Vector3d(1, 3, 3)).norm() < 1e-12);
  const auto& cyl = std::get<dss::Cylinder>(s.obstacles[1].shape);
  BOOST_TEST(cyl.radius == 0.5);  // .scene order: radius, length
  BOOST_TEST(cyl.half_length == 1.0);
  BOOST_TEST(s.obstacles[2].name == "second");
  BOOST_TEST(std::get<dss::Sphere>(s.obstacles[2].shape).radius == 0.25);
}

BOOST_AUTO_TEST_CASE(mesh_shape) {
  const std::string text =
      "m\n* tet\n1\nmesh\n5 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.1 0.1 0.1\n"
      "0 1 2\n0 1 3\n0 2 3\n1 2 3\n2 0 0\n0 0 0 1\n0 0 0 0\n.\n";
  const dss::Scene s = dss::parseSceneText(text, "mesh.scene");
  // The tetrahedron, then the vertex no triangle uses.
  BOOST_REQUIRE(s.obstacles.size() == 2u);
  BOOST_TEST(s.obstacles[0].name == "tet/0");
  BOOST_TEST(std::get<dss::ConvexHull>(s.obstacles[0].shape).size() == 4u);
  BOOST_TEST(s.obstacles[0].X_WO.translation().x() == 2.0);
  BOOST_TEST(std::get<dss::ConvexHull>(s.obstacles[1].shape).size() == 1u);
  BOOST_TEST(s.obstacles[1].X_WO.translation().x() == 2.0);
}

BOOST_AUTO_TEST_CASE(errors_name_file_and_line) {
  auto msgOf = [](const std::string& text) {
    return thrownMessage<dss::SceneError>([&] { dss::parseSceneText(text, "bad.scene"); });
  };
  std::string m = msgOf("s\n* a\n1\nbox\n1 -1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n");
  BOOST_TEST(contains(m, "bad.scene:5"));
  BOOST_TEST(contains(m, "negative"));
  BOOST_TEST(contains(m, "'a'"));
  m = msgOf("s\n* a\n1\nbox\n1 1 1\n0 0 0\n0 0 0 0\n0 0 0 0\n.\n");
  BOOST_TEST(contains(m, "bad.scene:7"));
  BOOST_TEST(contains(m, "zero quaternion"));
  m = msgOf("s\n* a\n1\nbox\n1 1 1\n0 0 0\nnan 0 0 1\n0 0 0 0\n.\n");
  BOOST_TEST(contains(m, "non-finite quaternion"));
  m = msgOf("s\n* a\n1\ntorus\n1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n");
  BOOST_TEST(contains(m, "bad.scene:4"));
  BOOST_TEST(contains(m, "unknown shape type 'torus'"));
  m = msgOf("s\n* a\n1\nbox\n1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n");
  BOOST_TEST(contains(m, "bad.scene:5"));
  BOOST_TEST(contains(m, "expected 3 numbers"));
  m = msgOf("s\n* a\n2\nbox\n1 1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n");
  BOOST_TEST(contains(m, "file ends"));
  m = msgOf("s\nbox\n");
  BOOST_TEST(contains(m, "bad.scene:2"));
  m = thrownMessage<dss::SceneError>([] { dss::loadScene("scene.obj"); });
  BOOST_TEST(contains(m, "unknown scene format"));
}

BOOST_AUTO_TEST_SUITE_END()
