// URDF mesh scales in both URDF readers (robot and world): a zero component collapses the
// mesh and is refused; a negative one mirrors it, which URDF allows. The readers used to
// disagree (the world reader refused negative scales, the robot reader took them); both now
// accept them, and the same mesh with scale (-1, 1, 1) gives the same hull through both.
#include <unistd.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/robot/urdf_loader.h"
#include "dss/scene/scene_error.h"
#include "dss/scene/urdf_world.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return dss_test::scratchDir("mesh_scale"); }

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

// A tetrahedron with vertices exactly representable in float: (0,0,0), (0.5,0,0), (0,0.25,0),
// (0,0,2).
const char* const kTetra =
    "solid t\n"
    "facet normal 0 0 -1\n outer loop\n vertex 0 0 0\n vertex 0 0.25 0\n vertex 0.5 0 0\n "
    "endloop\nendfacet\n"
    "facet normal 0 -1 0\n outer loop\n vertex 0 0 0\n vertex 0.5 0 0\n vertex 0 0 2\n "
    "endloop\nendfacet\n"
    "facet normal -1 0 0\n outer loop\n vertex 0 0 0\n vertex 0 0 2\n vertex 0 0.25 0\n "
    "endloop\nendfacet\n"
    "facet normal 1 1 1\n outer loop\n vertex 0.5 0 0\n vertex 0 0.25 0\n vertex 0 0 2\n "
    "endloop\nendfacet\n"
    "endsolid t\n";

std::string urdf(const std::string& scale) {
  return "<robot name=\"r\">\n  <link name=\"base\"><collision><geometry><mesh "
         "filename=\"tetra.stl\" scale=\"" +
         scale + "\"/></geometry></collision></link>\n</robot>\n";
}

std::vector<std::array<double, 3>> sorted(const std::vector<Eigen::Vector3d>& points) {
  std::vector<std::array<double, 3>> out;
  for (const auto& p : points) out.push_back({p.x(), p.y(), p.z()});
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(urdf_mesh_scale)

BOOST_AUTO_TEST_CASE(a_mirrored_mesh_has_the_same_hull_in_both_readers) {
  write("tetra.stl", kTetra);
  const std::string path = write("mirrored.urdf", urdf("-1 1 1"));
  const dss::RobotModel robot = dss::loadUrdf(path);
  const dss::Scene world = dss::loadUrdfWorld(path);
  BOOST_REQUIRE(robot.links.at(0).collisions.size() == 1u);
  BOOST_REQUIRE(world.obstacles.size() == 1u);
  const auto& robot_hull = std::get<dss::ConvexHull>(robot.links[0].collisions[0].shape);
  const auto& world_hull = std::get<dss::ConvexHull>(world.obstacles[0].shape);
  const std::vector<std::array<double, 3>> mirrored = {
      {-0.5, 0, 0}, {0, 0, 0}, {0, 0, 2}, {0, 0.25, 0}};
  BOOST_TEST(sorted(robot_hull.points()) == mirrored);
  BOOST_TEST(sorted(world_hull.points()) == mirrored);
  BOOST_TEST(robot.links[0].collisions[0].mesh_scale == Eigen::Vector3d(-1, 1, 1));
  // Mirrored in two axes (an even mirroring) too.
  const std::string two = write("mirrored2.urdf", urdf("-1 -2 1"));
  const std::vector<std::array<double, 3>> mirrored2 = {
      {-0.5, 0, 0}, {0, -0.5, 0}, {0, 0, 0}, {0, 0, 2}};
  BOOST_TEST(
      sorted(std::get<dss::ConvexHull>(dss::loadUrdf(two).links[0].collisions[0].shape).points()) ==
      mirrored2);
  BOOST_TEST(
      sorted(std::get<dss::ConvexHull>(dss::loadUrdfWorld(two).obstacles[0].shape).points()) ==
      mirrored2);
}

BOOST_AUTO_TEST_CASE(a_zero_scale_is_refused_by_both_readers) {
  write("tetra.stl", kTetra);
  const std::string path = write("zero.urdf", urdf("1 0 1"));
  std::string robot_error;
  try {
    dss::loadUrdf(path);
  } catch (const std::runtime_error& e) {
    robot_error = e.what();
  }
  BOOST_TEST(robot_error == path +
                                ":2: link 'base' collision[0] <mesh> scale '1 0 1': component y "
                                "is zero (the mesh would collapse); scales must be non-zero");
  std::string world_error;
  try {
    dss::loadUrdfWorld(path);
  } catch (const dss::SceneError& e) {
    world_error = e.what();
  }
  BOOST_TEST(world_error == path +
                                ": link 'base' collision 0: mesh scale component y is 0 (scale "
                                "\"1 0 1\"): it must be finite and non-zero, or the mesh "
                                "collapses");
}

BOOST_AUTO_TEST_SUITE_END()
