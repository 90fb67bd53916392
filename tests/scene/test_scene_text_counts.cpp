// MoveIt .scene text: counts in the file are bounded before any arithmetic on them. A mesh
// whose vertex and triangle counts make 3 v + 3 t wrap around to a small number once made the
// reader index far past the numbers it had read; every count is now digits only, checked
// against its limit (SceneInputLimits) and refused with the file, the line and the limit.
#include <boost/test/unit_test.hpp>
#include <string>

#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"
#include "dss/scene/scene_text.h"
#include "scene/scene_test_util.h"

using namespace dss_test;

namespace {

// One object "m" whose single shape is a mesh with the given count line (line 5) and a
// tetrahedron's data; the counts decide how much of it the reader takes.
std::string meshScene(const std::string& counts) {
  return "s\n* m\n1\nmesh\n" + counts +
         "\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 1 2\n0 1 3\n0 2 3\n1 2 3\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n";
}

std::string errorOf(const std::string& text, const dss::SceneLoadOptions& options = {}) {
  return thrownMessage<dss::SceneError>(
      [&] { dss::parseSceneText(text, "counts.scene", options); });
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_text_counts)

// The reproducer: 6148914691236517206 vertices and 1 triangle, 3 v + 3 t = 3 (mod 2^64).
BOOST_AUTO_TEST_CASE(wrapping_mesh_counts_are_refused_before_reading) {
  const std::string m = errorOf(meshScene("6148914691236517206 1"));
  BOOST_TEST(m ==
             "counts.scene:5: object 'm' shape 0 vertex count 6148914691236517206 exceeds the "
             "limit of 5000000 (SceneInputLimits::max_mesh_vertices; raise it with "
             "SceneLoadOptions::limits.max_mesh_vertices)");
  // The same through a file and loadScene (the reader chosen by extension).
  const std::string path = writeScratch("wrap.scene", meshScene("6148914691236517206 1"));
  const std::string f = thrownMessage<dss::SceneError>([&] { dss::loadScene(path); });
  BOOST_TEST(f.rfind(path + ":5: ", 0) == 0u);
  BOOST_TEST(contains(f, "max_mesh_vertices"));
}

BOOST_AUTO_TEST_CASE(triangle_counts_and_overlong_numbers_are_bounded) {
  std::string m = errorOf(meshScene("4 6148914691236517206"));
  BOOST_TEST(m ==
             "counts.scene:5: object 'm' shape 0 triangle count 6148914691236517206 exceeds the "
             "limit of 10000000 (SceneInputLimits::max_mesh_triangles; raise it with "
             "SceneLoadOptions::limits.max_mesh_triangles)");
  // More digits than any integer type holds: refused digit by digit, no overflow.
  m = errorOf(meshScene("4 " + std::string(40, '9')));
  BOOST_TEST(contains(m, "counts.scene:5: object 'm' shape 0 triangle count 9999"));
  BOOST_TEST(contains(m, "max_mesh_triangles"));
  // Signs and other characters are not counts.
  m = errorOf(meshScene("-4 4"));
  BOOST_TEST(m == "counts.scene:5: object 'm' shape 0 vertex count: expected a count, got '-4'");
  m = errorOf(meshScene("4 +4"));
  BOOST_TEST(m == "counts.scene:5: object 'm' shape 0 triangle count: expected a count, got '+4'");
}

BOOST_AUTO_TEST_CASE(counts_within_limits_still_need_their_data) {
  // Plausible counts, too little data: the numbers are a token stream (as in MoveIt), so the
  // reader takes the following lines as mesh data until one is not a number.
  std::string m = errorOf(meshScene("1000 1000"));
  BOOST_TEST(m == "counts.scene:17: object 'm' shape 0 mesh data: expected a number, got '.'");
  m = errorOf("s\n* m\n1\nmesh\n1000 1000\n0 0 0\n");
  BOOST_TEST(m == "counts.scene:6: file ends before object 'm' shape 0 mesh data");
  // The exact counts read the tetrahedron.
  const dss::Scene s = dss::parseSceneText(meshScene("4 4"), "counts.scene");
  BOOST_REQUIRE(s.obstacles.size() == 1u);
  BOOST_TEST(std::get<dss::ConvexHull>(s.obstacles[0].shape).size() == 4u);
}

BOOST_AUTO_TEST_CASE(limits_are_exact_and_raised_by_the_options) {
  dss::SceneLoadOptions o;
  o.limits.max_mesh_vertices = 3;
  BOOST_TEST(
      contains(errorOf(meshScene("4 4"), o),
               "vertex count 4 exceeds the limit of 3 (SceneInputLimits::max_mesh_vertices"));
  o.limits.max_mesh_vertices = 4;
  o.limits.max_mesh_triangles = 3;
  BOOST_TEST(contains(errorOf(meshScene("4 4"), o), "triangle count 4 exceeds the limit of 3"));
  o.limits.max_mesh_triangles = 4;
  BOOST_TEST(dss::parseSceneText(meshScene("4 4"), "counts.scene", o).obstacles.size() == 1u);
  // Mesh vertices of the whole scene: two 4-vertex meshes against a budget of 7.
  const std::string two =
      "s\n* a\n1\nmesh\n4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n0 0 0 1\n"
      "0 0 0 0\n* b\n1\nmesh\n4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n"
      "0 0 0 1\n0 0 0 0\n.\n";
  o.limits.max_scene_mesh_vertices = 7;
  const std::string m = errorOf(two, o);
  BOOST_TEST(m ==
             "counts.scene:16: object 'b' shape 0: the scene's mesh vertices (4 before this mesh "
             "of 4 vertices) exceeds the limit of 7 (SceneInputLimits::max_scene_mesh_vertices; "
             "raise it with SceneLoadOptions::limits.max_scene_mesh_vertices)");
  o.limits.max_scene_mesh_vertices = 8;
  BOOST_TEST(dss::parseSceneText(two, "counts.scene", o).obstacles.size() == 2u);
}

BOOST_AUTO_TEST_CASE(shape_and_obstacle_counts_are_bounded) {
  // A shape count far beyond the file: refused on its line, not read until the file ends.
  std::string m = errorOf("s\n* a\n99999999999\nbox\n1 1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n");
  BOOST_TEST(m ==
             "counts.scene:3: object 'a' shape count 99999999999 exceeds the limit of 10000 "
             "(SceneInputLimits::max_shapes_per_object; raise it with "
             "SceneLoadOptions::limits.max_shapes_per_object)");
  const std::string box = "box\n1 1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n";
  const std::string three = "s\n* a\n2\n" + box + box + "* b\n1\n" + box + ".\n";
  dss::SceneLoadOptions o;
  o.limits.max_obstacles = 2;
  m = errorOf(three, o);
  BOOST_TEST(m ==
             "counts.scene:14: object 'b': 1 shapes after 2 obstacles exceeds the limit of 2 "
             "(SceneInputLimits::max_obstacles; raise it with "
             "SceneLoadOptions::limits.max_obstacles)");
  o.limits.max_obstacles = 3;
  BOOST_TEST(dss::parseSceneText(three, "counts.scene", o).obstacles.size() == 3u);
}

BOOST_AUTO_TEST_SUITE_END()
