// A scene mesh of separate solids becomes one hull per solid in every reader (PlanningScene
// YAML inline, MoveIt .scene, URDF world with an STL file): the space between the solids is
// free, every mesh vertex is still inside an obstacle, and SceneLoadOptions::max_mesh_parts = 1
// gives back the single hull that fills the gap.
#include <boost/test/unit_test.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "dss/core/any_shape_query.h"
#include "dss/scene/planning_scene_yaml.h"
#include "dss/scene/scene_error.h"
#include "dss/scene/scene_text.h"
#include "dss/scene/urdf_world.h"
#include "scene/scene_test_util.h"

using namespace dss_test;
using Eigen::Vector3d;

namespace {

// Two boxes a metre apart, [0, 1]^3 and [2, 3] x [0, 1] x [0, 1]: shared-vertex triangles.
struct TwoBoxes {
  std::vector<Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  TwoBoxes() {
    for (double x0 : {0.0, 2.0}) {
      const int base = static_cast<int>(vertices.size());
      for (int i = 0; i < 8; ++i)
        vertices.emplace_back(x0 + (i & 1 ? 1.0 : 0.0), i & 2 ? 1.0 : 0.0, i & 4 ? 1.0 : 0.0);
      static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                      {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      for (const auto& f : faces) {
        triangles.push_back({base + f[0], base + f[1], base + f[2]});
        triangles.push_back({base + f[0], base + f[2], base + f[3]});
      }
    }
  }
  std::string yaml() const {
    std::ostringstream s;
    s << "world:\n  collision_objects:\n    - id: pair\n      meshes:\n        - vertices: [";
    for (std::size_t i = 0; i < vertices.size(); ++i)
      s << (i ? ", " : "") << "[" << vertices[i].x() << ", " << vertices[i].y() << ", "
        << vertices[i].z() << "]";
    s << "]\n          triangles: [";
    for (std::size_t t = 0; t < triangles.size(); ++t)
      s << (t ? ", " : "") << "[" << triangles[t][0] << ", " << triangles[t][1] << ", "
        << triangles[t][2] << "]";
    s << "]\n      mesh_poses:\n        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}\n";
    return s.str();
  }
  std::string sceneText() const {
    std::ostringstream s;
    s << "pair_scene\n* pair\n1\nmesh\n" << vertices.size() << " " << triangles.size() << "\n";
    for (const auto& v : vertices) s << v.x() << " " << v.y() << " " << v.z() << "\n";
    for (const auto& t : triangles) s << t[0] << " " << t[1] << " " << t[2] << "\n";
    s << "0 0 0\n0 0 0 1\n0 0 0 0\n.\n";
    return s.str();
  }
  std::string asciiStl() const {
    std::ostringstream s;
    s << "solid pair\n";
    for (const auto& t : triangles) {
      s << " facet normal 0 0 0\n  outer loop\n";
      for (int c : t)
        s << "   vertex " << vertices[c].x() << " " << vertices[c].y() << " " << vertices[c].z()
          << "\n";
      s << "  endloop\n endfacet\n";
    }
    s << "endsolid pair\n";
    return s.str();
  }
};

bool touchesAny(const dss::Scene& s, const Vector3d& c, double r) {
  const dss::AnyShape ball = dss::Sphere{r};
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = c;
  for (const auto& o : s.obstacles)
    if (dss::intersect(ball, X, o.shape, o.X_WO, {}).intersect) return true;
  return false;
}

// The checks every reader must pass, with the scene loaded by `load(max_mesh_parts)`.
template <class Load>
void checkTwoBoxes(const Load& load, const std::string& reader) {
  BOOST_TEST_CONTEXT(reader) {
    const TwoBoxes boxes;
    const dss::Scene parts = load(16);
    BOOST_REQUIRE(parts.obstacles.size() == 2u);
    BOOST_TEST(parts.obstacles[0].name == "pair/0");
    BOOST_TEST(parts.obstacles[1].name == "pair/1");
    for (const auto& o : parts.obstacles) {
      BOOST_TEST(o.object_id == "pair");
      BOOST_TEST(std::get<dss::ConvexHull>(o.shape).size() == 8u);
    }
    // The gap between the boxes is free; a ball reaching 1 mm into either box is not.
    BOOST_TEST(!touchesAny(parts, Vector3d(1.5, 0.5, 0.5), 0.499));
    BOOST_TEST(touchesAny(parts, Vector3d(1.5, 0.5, 0.5), 0.501));
    // Every vertex of the mesh is inside an obstacle.
    for (const auto& v : boxes.vertices) BOOST_TEST(touchesAny(parts, v, 1e-9));
    // One hull per mesh: the gap is filled.
    const dss::Scene whole = load(1);
    BOOST_REQUIRE(whole.obstacles.size() == 1u);
    BOOST_TEST(whole.obstacles[0].name == "pair");
    BOOST_TEST(touchesAny(whole, Vector3d(1.5, 0.5, 0.5), 0.1));
    // ... and the scene says so; each box's own hull reaches nowhere beyond it.
    BOOST_TEST(parts.warnings.empty());
    BOOST_REQUIRE(whole.warnings.size() == 1u);
    BOOST_TEST(contains(whole.warnings[0], "its convex hull reaches at least 0.5"),
               whole.warnings[0]);
    BOOST_TEST(contains(whole.warnings[0], "mesh"), whole.warnings[0]);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_mesh_parts)

BOOST_AUTO_TEST_CASE(every_reader_keeps_the_gap_between_a_meshs_solids) {
  const TwoBoxes boxes;
  checkTwoBoxes(
      [&](std::size_t cap) {
        dss::SceneLoadOptions opt;
        opt.max_mesh_parts = cap;
        return dss::parsePlanningSceneYaml(boxes.yaml(), "pair.yaml", opt);
      },
      "PlanningScene YAML");
  checkTwoBoxes(
      [&](std::size_t cap) {
        dss::SceneLoadOptions opt;
        opt.max_mesh_parts = cap;
        return dss::parseSceneText(boxes.sceneText(), "pair.scene", opt);
      },
      "MoveIt .scene");
  const std::string stl = writeScratch("mesh_parts/pair.stl", boxes.asciiStl());
  const std::string urdf = writeScratch(
      "mesh_parts/pair.urdf",
      "<robot name=\"w\"><link name=\"pair\"><collision><geometry><mesh filename=\"pair.stl\"/>"
      "</geometry></collision></link></robot>\n");
  (void)stl;
  checkTwoBoxes(
      [&](std::size_t cap) {
        dss::SceneLoadOptions opt;
        opt.max_mesh_parts = cap;
        return dss::loadUrdfWorld(urdf, opt);
      },
      "URDF world");
}

BOOST_AUTO_TEST_CASE(mesh_parts_count_against_the_obstacle_limit) {
  const TwoBoxes boxes;
  dss::SceneLoadOptions opt;
  opt.limits.max_obstacles = 1;
  const std::string m = thrownMessage<dss::SceneError>(
      [&] { dss::parsePlanningSceneYaml(boxes.yaml(), "pair.yaml", opt); });
  BOOST_TEST(contains(m, "pair.yaml:"));
  BOOST_TEST(contains(m, "2 shapes and mesh parts"));
  BOOST_TEST(contains(m, "max_obstacles"));
  const std::string t = thrownMessage<dss::SceneError>(
      [&] { dss::parseSceneText(boxes.sceneText(), "pair.scene", opt); });
  BOOST_TEST(contains(t, "pair.scene:2"));
  BOOST_TEST(contains(t, "max_obstacles"));
  const std::string urdf = writeScratch(
      "mesh_parts/limit/pair.urdf",
      "<robot name=\"w\"><link name=\"pair\"><collision><geometry><mesh filename=\"pair.stl\"/>"
      "</geometry></collision></link></robot>\n");
  writeScratch("mesh_parts/limit/pair.stl", boxes.asciiStl());
  const std::string u = thrownMessage<dss::SceneError>([&] { dss::loadUrdfWorld(urdf, opt); });
  BOOST_TEST(contains(u, "pair.urdf: link 'pair'"));
  BOOST_TEST(contains(u, "max_obstacles"));
  opt.max_mesh_parts = 1;  // one hull: within the limit
  BOOST_TEST(dss::parsePlanningSceneYaml(boxes.yaml(), "pair.yaml", opt).obstacles.size() == 1u);
}

BOOST_AUTO_TEST_SUITE_END()
