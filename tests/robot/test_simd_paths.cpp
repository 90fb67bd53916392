// Forward kinematics on every instruction-set path (dss/core/simd_path.h) gives the same poses
// to the bit: random states within the limits and far beyond them (angles up to 1e4 rad), and
// quaternions of any scale, zero and NaN, on our arm, the mobile base's joints, planar and
// floating bases, and the shared robots (Panda, UR5 with its gripper's mimic joints, iiwa).
// The AVX2 cases report themselves skipped on a CPU without AVX2.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "dss/core/simd_path.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/urdf_loader.h"
#include "support/shared_data.h"

namespace {

const std::string kOwn = std::string(DSS_SOURCE_DIR) + "/robots";

// A body on a planar or floating joint with a turned origin, an arm on a revolute joint with
// a tilted axis (the general rotation path) and a prismatic joint along a tilted axis.
dss::RobotModel multiDofRobot(const std::string& type) {
  const std::string xml = R"(<robot name="r"><link name="world"/>
<link name="body"><collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision></link>
<link name="arm"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
<link name="tip"><collision><geometry><sphere radius="0.02"/></geometry></collision></link>
<joint name="base" type=")" +
                          type + R"("><parent link="world"/><child link="body"/>
  <origin xyz="1 2 0.5" rpy="0.1 -0.2 0.3"/></joint>
<joint name="elbow" type="revolute"><parent link="body"/><child link="arm"/>
  <origin xyz="0.2 0 0" rpy="1.5707963267948966 0 0"/><axis xyz="0.3 0.4 0.866"/>
  <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
<joint name="slide" type="prismatic"><parent link="arm"/><child link="tip"/>
  <origin xyz="0.3 0 0" rpy="0 0.7 0"/><axis xyz="0.6 0 0.8"/>
  <limit lower="-0.1" upper="0.4" effort="1" velocity="1"/></joint>
</robot>)";
  return dss::loadUrdfString(xml, type + ".urdf", ".");
}

bool sameBits(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  for (int k = 0; k < 16; ++k) {
    const double x = a.matrix().data()[k], y = b.matrix().data()[k];
    if (std::isnan(x) && std::isnan(y)) continue;
    if (std::memcmp(&x, &y, sizeof x) != 0) return false;
  }
  return true;
}

// The poses of `states` random states on `path` against the scalar path, for the links with
// geometry (folded steps) and for every link. Returns the states compared.
int comparePaths(const dss::RobotModel& m, dss::SimdPath path, int states, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n;
  const std::size_t na = m.numActiveJoints();
  int compared = 0;
  for (bool all : {false, true}) {
    const dss::Kinematics kin(m, all);
    std::vector<Eigen::Isometry3d> X0(m.links.size()), X1(m.links.size());
    std::vector<double> q(na);
    for (int k = 0; k < states; ++k) {
      for (std::size_t a = 0; a < na; ++a) {
        const dss::RobotJoint& j = m.joints[m.active_joints[a]];
        if (j.limits.has_position_limits && std::isfinite(j.limits.lower) &&
            std::isfinite(j.limits.upper))
          q[a] = j.limits.lower + u(rng) * (j.limits.upper - j.limits.lower);
        else
          q[a] = 20.0 * u(rng) - 10.0;
        if (k % 7 == 3) q[a] = 2e4 * u(rng) - 1e4;  // far beyond any limit
      }
      for (std::size_t a = 0; a < na; ++a) {
        const dss::RobotJoint& j = m.joints[m.active_joints[a]];
        if (j.type != dss::JointType::kBall || j.active_index != int(a)) continue;
        const double scale = std::ldexp(1.0, static_cast<int>(20 * u(rng)) - 10);
        for (int i = 0; i < 4; ++i) q[a + i] = scale * n(rng);
        if (k % 50 == 7) q[a] = q[a + 1] = q[a + 2] = q[a + 3] = 0.0;
        if (k % 50 == 9) q[a + 3] = std::nan("");
      }
      kin.computeLinkPoses(q.data(), X0.data(), dss::SimdPath::kScalar);
      kin.computeLinkPoses(q.data(), X1.data(), path);
      for (int l : kin.updatedLinks())
        BOOST_TEST_REQUIRE(sameBits(X0[l], X1[l]), m.name << " link " << m.links[l].name
                                                          << ", state " << k << ", path "
                                                          << dss::simdPathName(path));
      ++compared;
    }
  }
  return compared;
}

std::vector<dss::RobotModel> ownRobots() {
  std::vector<dss::RobotModel> r;
  r.push_back(dss::loadUrdf(kOwn + "/dss_arm7/dss_arm7.urdf"));
  r.push_back(dss::loadUrdf(kOwn + "/dss_mobile_base/dss_mobile_base.urdf"));
  r.push_back(multiDofRobot("planar"));
  r.push_back(multiDofRobot("floating"));
  return r;
}

std::vector<dss::RobotModel> sharedRobots() {
  std::vector<dss::RobotModel> r;
  for (const char* p : {"robots/panda/panda.urdf", "robots/ur5_robotiq85/ur5.urdf",
                        "robots/iiwa_description/iiwa14_primitive_collision.urdf"})
    r.push_back(dss::loadUrdf(dss_test::sharedPath(p)));
  return r;
}

bool haveAvx2(boost::unit_test::test_unit_id) {
  return dss::simdPathAvailable(dss::SimdPath::kAvx2);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(simd_paths)

BOOST_AUTO_TEST_CASE(paths_are_named_and_the_active_one_is_available) {
  BOOST_TEST(dss::simdPathAvailable(dss::SimdPath::kScalar));
  BOOST_TEST(dss::simdPathAvailable(dss::SimdPath::kSse2));
  BOOST_TEST(dss::simdPathAvailable(dss::activeSimdPath()));
  BOOST_TEST(dss::simdPathAvailable(dss::bestSimdPath()));
  BOOST_TEST(std::string(dss::simdPathName(dss::SimdPath::kAvx2)) == "avx2");
  BOOST_TEST_MESSAGE("best path on this CPU: " << dss::simdPathName(dss::bestSimdPath())
                                               << ", active: "
                                               << dss::simdPathName(dss::activeSimdPath()));
}

BOOST_AUTO_TEST_CASE(sse2_path_gives_the_scalar_poses_on_our_robots) {
  for (const dss::RobotModel& m : ownRobots())
    BOOST_TEST(comparePaths(m, dss::SimdPath::kSse2, 3000, 11) == 6000);
}

BOOST_AUTO_TEST_CASE(avx2_path_gives_the_scalar_poses_on_our_robots,
                     *boost::unit_test::precondition(haveAvx2)) {
  for (const dss::RobotModel& m : ownRobots())
    BOOST_TEST(comparePaths(m, dss::SimdPath::kAvx2, 3000, 12) == 6000);
}

BOOST_AUTO_TEST_CASE(every_path_gives_the_scalar_poses_on_the_shared_robots, DSS_NEEDS_SHARED) {
  for (const dss::RobotModel& m : sharedRobots()) {
    BOOST_TEST(comparePaths(m, dss::SimdPath::kSse2, 3000, 13) == 6000);
    if (dss::simdPathAvailable(dss::SimdPath::kAvx2))
      BOOST_TEST(comparePaths(m, dss::SimdPath::kAvx2, 3000, 14) == 6000);
    else
      BOOST_TEST_MESSAGE("AVX2 not available: " << m.name << " compared on SSE2 only");
  }
}

BOOST_AUTO_TEST_SUITE_END()
