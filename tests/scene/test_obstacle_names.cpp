// Obstacle names are unique in a scene, in every reader: a collision object id given twice is
// an error naming both lines (PlanningScene YAML and .scene text), and an id holding a '/'
// that equals the name of another object's shape ("a/1" against shape 1 of "a") is renamed
// "a/1#2" (YAML, .scene text and URDF worlds). Found by fuzz/fuzz_planning_scene_yaml.
#include <boost/test/unit_test.hpp>
#include <set>

#include "dss/scene/planning_scene_yaml.h"
#include "dss/scene/scene_error.h"
#include "dss/scene/scene_text.h"
#include "dss/scene/urdf_world.h"
#include "scene_test_util.h"

using dss_test::contains;
using dss_test::thrownMessage;

namespace {

std::vector<std::string> names(const dss::Scene& scene) {
  std::vector<std::string> out;
  for (const auto& o : scene.obstacles) out.push_back(o.name);
  return out;
}

void checkUnique(const dss::Scene& scene) {
  const auto n = names(scene);
  BOOST_TEST(std::set<std::string>(n.begin(), n.end()).size() == n.size());
}

const char* const kBox = "{type: box, dimensions: [0.1, 0.1, 0.1]}";
const char* const kPose = "{position: [0, 0, 0], orientation: [0, 0, 0, 1]}";

std::string yamlObject(const std::string& id, int shapes) {
  std::string prims, poses;
  for (int k = 0; k < shapes; ++k) {
    prims += std::string(k ? ", " : "") + kBox;
    poses += std::string(k ? ", " : "") + kPose;
  }
  return "    - id: " + id + "\n      primitives: [" + prims + "]\n      primitive_poses: [" +
         poses + "]\n";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(obstacle_names)

BOOST_AUTO_TEST_CASE(yaml_object_id_given_twice_is_an_error) {
  const std::string text = "world:\n  collision_objects:\n" + yamlObject("Can2", 1) +
                           yamlObject("Can1", 1) + yamlObject("Can2", 1);
  const std::string msg =
      thrownMessage<dss::SceneError>([&] { dss::parsePlanningSceneYaml(text, "twice.yaml"); });
  BOOST_TEST(contains(msg, "twice.yaml:9"), msg);
  BOOST_TEST(contains(msg, "object 'Can2' given twice (first at twice.yaml:3)"), msg);
}

BOOST_AUTO_TEST_CASE(scene_text_object_id_given_twice_is_an_error) {
  const std::string object = "* pole\n1\nsphere\n0.1\n0 0 0\n0 0 0 1\n0 0 0 0\n";
  const std::string msg = thrownMessage<dss::SceneError>(
      [&] { dss::parseSceneText("name\n" + object + object + ".\n", "twice.scene"); });
  BOOST_TEST(contains(msg, "twice.scene:9: object 'pole' given twice (first at twice.scene:2)"),
             msg);
}

BOOST_AUTO_TEST_CASE(yaml_names_stay_unique) {
  const std::string text = "world:\n  collision_objects:\n" + yamlObject("a", 2) +
                           yamlObject("a/1", 1) + yamlObject("a/1#2", 1);
  const dss::Scene scene = dss::parsePlanningSceneYaml(text, "names.yaml");
  BOOST_TEST(names(scene) == (std::vector<std::string>{"a/0", "a/1", "a/1#3", "a/1#2"}),
             boost::test_tools::per_element());
  checkUnique(scene);
  BOOST_TEST(scene.obstacles[2].object_id == "a/1");
}

BOOST_AUTO_TEST_CASE(scene_text_names_stay_unique) {
  const std::string shape = "box\n0.1 0.1 0.1\n0 0 0\n0 0 0 1\n0 0 0 0\n";
  const std::string text = "name\n* a/1\n1\n" + shape + "* a\n2\n" + shape + shape + ".\n";
  const dss::Scene scene = dss::parseSceneText(text, "names.scene");
  BOOST_TEST(names(scene) == (std::vector<std::string>{"a/1", "a/0", "a/1#2"}),
             boost::test_tools::per_element());
  checkUnique(scene);
}

BOOST_AUTO_TEST_CASE(urdf_world_names_stay_unique) {
  const std::string box = "<collision><geometry><box size=\"1 1 1\"/></geometry></collision>";
  const std::string urdf = "<robot name=\"w\"><link name=\"a\">" + box + box +
                           "</link><link name=\"a/1\">" + box +
                           "</link><joint name=\"j\" type=\"fixed\"><parent link=\"a\"/>"
                           "<child link=\"a/1\"/></joint></robot>";
  const dss::Scene scene = dss::loadUrdfWorld(dss_test::writeScratch("names.urdf", urdf));
  checkUnique(scene);
  BOOST_TEST(scene.obstacles.size() == 3u);
}

BOOST_AUTO_TEST_SUITE_END()
