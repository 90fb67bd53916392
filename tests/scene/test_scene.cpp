// Scene data: world bounding boxes of every shape type and the allowed collision matrix.
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "dss/scene/scene.h"

BOOST_AUTO_TEST_SUITE(scene_data)

BOOST_AUTO_TEST_CASE(world_aabb_of_rotated_shapes) {
  dss::Obstacle o;
  o.shape = dss::Box::fromSize(Eigen::Vector3d(1, 2, 4));
  o.X_WO = Eigen::Isometry3d::Identity();
  o.X_WO.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  o.X_WO.translation() = Eigen::Vector3d(1, 1, 1);
  dss::Aabb b = dss::worldAabb(o);
  BOOST_TEST((b.lower - Eigen::Vector3d(0, 0.5, -1)).norm() < 1e-12);
  BOOST_TEST((b.upper - Eigen::Vector3d(2, 1.5, 3)).norm() < 1e-12);

  o.shape = dss::Cylinder::fromLength(0.5, 2.0);  // along z, rotated onto x
  o.X_WO.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  o.X_WO.translation().setZero();
  b = dss::worldAabb(o);
  BOOST_TEST((b.upper - Eigen::Vector3d(1, 0.5, 0.5)).norm() < 1e-12);
  BOOST_TEST((b.lower + b.upper).norm() < 1e-12);
  BOOST_TEST(dss::describeShape(o.shape) == "cylinder r 0.5 length 2");
}

BOOST_AUTO_TEST_CASE(acm_and_object_ids) {
  dss::AllowedCollisionMatrix acm;
  acm.allow("b", "a");
  acm.allowAlways("table");
  BOOST_TEST(acm.allowed("a", "b"));
  BOOST_TEST(acm.allowed("table", "x"));
  BOOST_TEST(!acm.allowed("a", "c"));

  dss::Scene s;
  for (int i = 0; i < 5; ++i) {
    dss::Obstacle o;
    o.name = o.object_id = "o" + std::to_string(i);
    o.shape = dss::Sphere{0.1};
    o.X_WO.translation() = Eigen::Vector3d(i, 0, 0);
    s.obstacles.push_back(o);
  }
  BOOST_TEST(s.objectIds() == (std::vector<std::string>{"o0", "o1", "o2", "o3", "o4"}));
}

BOOST_AUTO_TEST_SUITE_END()
