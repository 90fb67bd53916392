// The input budgets against real files: every scene, request, .scene file and URDF world in
// the shared data (and our own arm's) loads with the limits set to the largest value any of
// them needs, and lowering any one of those limits by one refuses at least one file with a
// message naming that limit. This pins the "largest seen" values documented in
// dss/scene/input_limits.h, and shows the defaults are far above them.
#include <boost/test/unit_test.hpp>
#include <functional>
#include <string>
#include <vector>

#include "dss/scene/input_limits.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"
#include "scene/scene_test_util.h"
#include "support/shared_data.h"

using namespace dss_test;

namespace {

// The largest value each limit needs over the files (input_limits.h says where each occurs).
dss::SceneInputLimits largestSeen() {
  dss::SceneInputLimits l;
  l.max_obstacles = 21;              // mbm bookshelf_thin scenes
  l.max_shapes_per_object = 8;       // kallax.scene, g03_open_back_storage_shelf.scene
  l.max_acm_entries = 20;            // mbm UR5 scenes
  l.max_mesh_vertices = 432;         // kitchen cupboard doors
  l.max_mesh_triangles = 0;          // no scene has an inline or .scene mesh
  l.max_scene_mesh_vertices = 1260;  // the kitchen world
  l.max_xml_depth = 5;               // the kitchen world
  l.max_request_joint_values = 18;   // mbm UR5 requests: 12 start joints and 6 goals
  return l;
}

struct Files {
  std::vector<std::string> scenes, requests;
};

Files sharedFiles() {
  Files f;
  const std::string arm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7/scenes";
  for (const std::string& dir : {scenesDir(), arm}) {
    for (const auto& p : filesMatching(dir, "(scene[0-9]+|scene_.*|shelf)\\.yaml"))
      f.scenes.push_back(p);
    for (const auto& p : filesMatching(dir, "(request[0-9]+|shelf_request)\\.yaml"))
      f.requests.push_back(p);
  }
  for (const auto& p : filesMatching(scenesDir(), ".*\\.scene")) f.scenes.push_back(p);
  for (const auto& p : filesMatching(scenesDir(), ".*\\.urdf")) f.scenes.push_back(p);
  return f;
}

dss::SceneLoadOptions sceneOptions(const dss::SceneInputLimits& limits) {
  dss::SceneLoadOptions o;
  o.package_dirs["motion_bench_maker"] = scenesDir() + "/mbm_templates";  // kitchen.orig.urdf
  o.limits = limits;
  return o;
}

// The first file refused under `limits`, with its message; empty when all load.
std::string firstRefusal(const Files& files, const dss::SceneInputLimits& limits) {
  const dss::SceneLoadOptions so = sceneOptions(limits);
  dss::PlanRequestOptions ro;
  ro.limits = limits;
  try {
    for (const auto& f : files.scenes) dss::loadScene(f, so);
    for (const auto& f : files.requests) dss::loadPlanRequestYaml(f, ro);
  } catch (const dss::SceneError& e) {
    return e.what();
  }
  return std::string();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_input_limits)

BOOST_AUTO_TEST_CASE(every_real_file_fits_the_largest_seen_values, DSS_NEEDS_SHARED) {
  requireShared();
  const Files files = sharedFiles();
  BOOST_TEST(files.scenes.size() == 6u + 70u + 35u + 1u + 8u + 2u);
  BOOST_TEST(files.requests.size() == 70u + 35u + 1u);
  BOOST_TEST(firstRefusal(files, largestSeen()) == "");
}

BOOST_AUTO_TEST_CASE(each_largest_seen_value_is_needed, DSS_NEEDS_SHARED) {
  requireShared();
  const Files files = sharedFiles();
  using Field = std::size_t dss::SceneInputLimits::*;
  const std::vector<std::pair<Field, std::string>> fields = {
      {&dss::SceneInputLimits::max_obstacles, "max_obstacles"},
      {&dss::SceneInputLimits::max_shapes_per_object, "max_shapes_per_object"},
      {&dss::SceneInputLimits::max_acm_entries, "max_acm_entries"},
      {&dss::SceneInputLimits::max_mesh_vertices, "max_mesh_vertices"},
      {&dss::SceneInputLimits::max_scene_mesh_vertices, "max_scene_mesh_vertices"},
      {&dss::SceneInputLimits::max_xml_depth, "max_xml_depth"},
      {&dss::SceneInputLimits::max_request_joint_values, "max_request_joint_values"}};
  for (const auto& [field, name] : fields) {
    BOOST_TEST_CONTEXT(name) {
      dss::SceneInputLimits lower = largestSeen();
      lower.*field -= 1;
      const std::string m = firstRefusal(files, lower);
      BOOST_TEST(contains(m, "(SceneInputLimits::" + name + "; raise it with "), m);
    }
  }
}

BOOST_AUTO_TEST_CASE(defaults_are_far_above_the_largest_seen_values) {
  const dss::SceneInputLimits d, seen = largestSeen();
  BOOST_TEST(d.max_obstacles >= 1000 * seen.max_obstacles);
  BOOST_TEST(d.max_shapes_per_object >= 1000 * seen.max_shapes_per_object);
  BOOST_TEST(d.max_acm_entries >= 50 * seen.max_acm_entries);
  BOOST_TEST(d.max_mesh_vertices >= 30 * 130419u);  // the largest mesh file of the robots
  BOOST_TEST(d.max_mesh_triangles >= 30 * 43473u);
  BOOST_TEST(d.max_scene_mesh_vertices >= 1000 * seen.max_scene_mesh_vertices);
  BOOST_TEST(d.max_xml_depth >= 50 * seen.max_xml_depth);
  BOOST_TEST(d.max_request_joint_values >= 1000 * seen.max_request_joint_values);
}

BOOST_AUTO_TEST_SUITE_END()
