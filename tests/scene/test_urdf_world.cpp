// A URDF as a world: the MotionBenchMaker kitchen (5 mesh links, 3 revolute doors held at 0),
// its package:// original, the joint policy, and malformed XML.
#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"
#include "dss/scene/urdf_world.h"
#include "scene/scene_test_util.h"
#include "support/shared_data.h"

using namespace dss_test;

namespace {
std::string kitchenDir() { return scenesDir() + "/mbm_templates/configs/scenes/kitchen"; }

std::string writeTemp(const std::string& name, const std::string& text) {
  return writeScratch(name, text);
}
}  // namespace

BOOST_AUTO_TEST_SUITE(urdf_world)

BOOST_AUTO_TEST_CASE(kitchen_loads, DSS_NEEDS_SHARED) {
  requireShared();
  const dss::Scene s = dss::loadScene(kitchenDir() + "/kitchen.urdf");
  BOOST_TEST(s.name == "kitchen");
  // The meshes' separate parts: the cupboard's body and shelf, each door's panel and handle,
  // the dishwasher door, the counter's three blocks.
  BOOST_TEST(s.obstacles.size() == 10u);
  std::map<std::string, int> per_link;
  for (const auto& o : s.obstacles) {
    BOOST_TEST(std::holds_alternative<dss::ConvexHull>(o.shape));
    BOOST_TEST(std::get<dss::ConvexHull>(o.shape).size() >= 4u);
    ++per_link[o.object_id];
  }
  BOOST_TEST(per_link["cupboard"] == 2);
  BOOST_TEST(per_link["cupboard_door_l"] == 2);
  BOOST_TEST(per_link["cupboard_door_r"] == 2);
  BOOST_TEST(per_link["dishwasher_door"] == 1);
  BOOST_TEST(per_link["kitchen_counter"] == 3);
  // Three revolute doors held at 0, and the parts whose hulls reach well beyond their meshes:
  // the cupboard's carcass (open at the front) and two blocks of the counter.
  BOOST_TEST(s.warnings.size() == 6u);
  int held = 0, reaching = 0;
  for (const auto& w : s.warnings) {
    held += contains(w, "movable joint held at 0");
    if (contains(w, "its convex hull reaches at least")) {
      ++reaching;
      BOOST_TEST((contains(w, "link 'cupboard' collision 0") ||
                  contains(w, "link 'kitchen_counter' collision 0")),
                 w);
    }
  }
  BOOST_TEST(held == 3);
  BOOST_TEST(reaching == 3);
  // cupboard_door_l sits at its joint origin (door joint at 0).
  int doors = 0;
  for (const auto& o : s.obstacles)
    if (o.object_id == "cupboard_door_l") {
      BOOST_TEST((o.name == "cupboard_door_l/0" || o.name == "cupboard_door_l/1"));
      BOOST_TEST((o.X_WO.translation() - Eigen::Vector3d(0.44637, 0.54793, 1.6839)).norm() < 1e-12);
      ++doors;
    }
  BOOST_TEST(doors == 2);
  // One hull per mesh on request.
  dss::SceneLoadOptions whole;
  whole.max_mesh_parts = 1;
  const dss::Scene one = dss::loadUrdfWorld(kitchenDir() + "/kitchen.urdf", whole);
  BOOST_TEST(one.obstacles.size() == 5u);
  // As single hulls the doors reach over the gap to their handles too.
  int doors_reaching = 0;
  for (const auto& w : one.warnings)
    doors_reaching += contains(w, "link 'cupboard_door_") && contains(w, "reaches at least");
  BOOST_TEST(doors_reaching == 2);

  // The original, with package:// URIs, through a package directory.
  dss::SceneLoadOptions opt;
  opt.package_dirs["motion_bench_maker"] = scenesDir() + "/mbm_templates";
  const dss::Scene orig = dss::loadUrdfWorld(kitchenDir() + "/kitchen.orig.urdf", opt);
  BOOST_TEST(orig.obstacles.size() == 10u);
}

BOOST_AUTO_TEST_CASE(kitchen_joint_policy, DSS_NEEDS_SHARED) {
  requireShared();
  dss::SceneLoadOptions opt;
  opt.urdf_require_fixed_joints = true;
  std::string m = thrownMessage<dss::SceneError>(
      [&] { dss::loadUrdfWorld(kitchenDir() + "/kitchen.urdf", opt); });
  BOOST_TEST(contains(m, "kitchen.urdf"));
  BOOST_TEST(contains(m, "_joint'"));

  // An open door: rotated about its z axis by the given value (limits [-3.14, 0]).
  dss::SceneLoadOptions open;
  open.joint_values["cupboard_door_l_joint"] = -1.0;
  const dss::Scene s = dss::loadUrdfWorld(kitchenDir() + "/kitchen.urdf", open);
  int turned = 0;
  for (const auto& o : s.obstacles)
    if (o.object_id == "cupboard_door_l") {
      BOOST_TEST(
          (o.X_WO.linear() - Eigen::AngleAxisd(-1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix())
              .norm() < 1e-12);
      ++turned;
    }
  BOOST_TEST(turned == 2);
  dss::SceneLoadOptions typo;
  typo.joint_values["no_such_joint"] = 0.0;
  m = thrownMessage<dss::SceneError>(
      [&] { dss::loadUrdfWorld(kitchenDir() + "/kitchen.urdf", typo); });
  BOOST_TEST(contains(m, "no_such_joint"));
}

BOOST_AUTO_TEST_CASE(primitives_and_errors) {
  const std::string ok = writeTemp("dss_scene_world_ok.urdf", R"(<?xml version="1.0"?>
<robot name="w">
  <link name="base">
    <collision><origin xyz="0 0 1" rpy="0 0 0"/><geometry><box size="1 2 3"/></geometry></collision>
    <collision><geometry><sphere radius="0.5"/></geometry></collision>
  </link>
  <link name="post">
    <collision><geometry><cylinder radius="0.1" length="2"/></geometry></collision>
  </link>
  <joint name="j" type="fixed"><parent link="base"/><child link="post"/>
    <origin xyz="3 0 0" rpy="0 0 0"/></joint>
</robot>)");
  const dss::Scene s = dss::loadUrdfWorld(ok);
  BOOST_REQUIRE(s.obstacles.size() == 3u);
  BOOST_TEST(s.warnings.empty());
  BOOST_TEST(s.obstacles[0].name == "base/0");
  BOOST_TEST(s.obstacles[0].X_WO.translation().z() == 1.0);
  BOOST_TEST(s.obstacles[2].name == "post");
  BOOST_TEST(s.obstacles[2].X_WO.translation().x() == 3.0);

  const std::string broken =
      writeTemp("dss_scene_world_broken.urdf",
                "<robot name=\"w\">\n  <link name=\"a\">\n  </lnk>\n</robot>\n");
  std::string m = thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(broken); });
  BOOST_TEST(contains(m, broken + ":3"));
  BOOST_TEST(contains(m, "malformed XML"));

  const std::string capsule = writeTemp("dss_scene_world_capsule.urdf", R"(<robot name="w">
  <link name="a">
    <collision><geometry><capsule radius="0.1" length="1"/></geometry></collision>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
</robot>)");
  m = thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(capsule); });
  BOOST_TEST(contains(m, "link 'a'"));

  const std::string negative = writeTemp("dss_scene_world_negative.urdf", R"(<robot name="w">
  <link name="a"><collision><geometry><mesh filename="missing.stl"/></geometry></collision></link>
</robot>)");
  m = thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(negative); });
  BOOST_TEST(contains(m, "missing.stl"));
  BOOST_TEST(contains(m, "link 'a'"));
  // An empty mesh file: the error names the link and the file.
  const std::string empty_stl = writeTemp("dss_scene_world_empty.stl", "");
  const std::string empty = writeTemp("dss_scene_world_empty.urdf", R"(<robot name="w">
  <link name="slab"><collision><geometry><mesh filename="dss_scene_world_empty.stl"/></geometry></collision></link>
</robot>)");
  m = thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(empty); });
  BOOST_TEST(contains(m, "link 'slab'"));
  BOOST_TEST(contains(m, "dss_scene_world_empty.stl"));
  // A negative box size.
  const std::string neg_box = writeTemp("dss_scene_world_negbox.urdf", R"(<robot name="w">
  <link name="b"><collision><geometry><box size="1 -1 1"/></geometry></collision></link>
</robot>)");
  m = thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(neg_box); });
  BOOST_TEST(contains(m, "dss_scene_world_negbox.urdf"));
  BOOST_TEST(contains(m, "link 'b'"));
  BOOST_TEST(contains(m, "negative box size"));
  for (const auto& f : {ok, broken, capsule, negative, empty_stl, empty, neg_box})
    std::remove(f.c_str());
}

BOOST_AUTO_TEST_SUITE_END()
