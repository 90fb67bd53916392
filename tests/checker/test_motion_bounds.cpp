// Kinematic motion bounds (motion_bounds.h), which the reach balls, self-pair tables, pair
// blocks and the continuous motion check all rest on: along finely sampled straight joint-space
// motions between seeded random states, no point of a link's geometry (its elements' hull
// vertices, or support points of a primitive) travels a longer path than
// motionBound(chainAbove(...)).length -- in the world and relative to every ancestor link -- nor
// turns by more than its `turn`; every point stays within the chain's reach of the ancestor's
// origin and every link origin within originOffsetBound of it. On our own arm, and on a small
// robot with prismatic joints (one a mimic) held outside their limits; prismaticTravel covers
// every value within the limits and the held value.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/checker/motion_bounds.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/urdf_loader.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"

namespace {

// A prismatic carriage (x), an arm turning about z on it, and two fingers sliding along y at
// the arm's end, the second a mimic of the first (-2 q + 0.05).
const char* kSliderUrdf = R"(<robot name="slider">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="carriage"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/><origin xyz="0 0 0.1"/>
    <axis xyz="1 0 0"/><limit lower="-0.2" upper="0.5" effort="1" velocity="1"/></joint>
  <link name="arm"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.6 0.05 0.05"/></geometry></collision></link>
  <joint name="turn" type="revolute"><parent link="carriage"/><child link="arm"/><origin xyz="0.05 0 0.1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="finger"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.02 0.02 0.04"/></geometry></collision></link>
  <joint name="finger_joint" type="prismatic"><parent link="arm"/><child link="finger"/><origin xyz="0.6 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-0.3" upper="0.1" effort="1" velocity="1"/></joint>
  <link name="mirror"><collision><origin xyz="0 0 0.02"/><geometry><cylinder radius="0.01" length="0.04"/></geometry></collision></link>
  <joint name="mirror_joint" type="prismatic"><parent link="arm"/><child link="mirror"/><origin xyz="0.6 0 0"/>
    <axis xyz="0 -1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="finger_joint" multiplier="-2" offset="0.05"/></joint>
</robot>)";

// Two links turning about parallel z axes (a planar arm): aligned, a point at the tip
// accelerates by exactly L1 w1^2 + L2 (w1 + w2)^2, which the bend bound reaches.
const char* kPlanarUrdf = R"(<robot name="planar">
  <link name="base"/>
  <link name="upper"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="fore"><collision><origin xyz="0.2 0 0"/><geometry><sphere radius="0.001"/></geometry></collision></link>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0.5 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-0.3" upper="0.3" effort="1" velocity="1"/></joint>
</robot>)";

dss::RobotModel sliderRobot() { return dss::loadUrdfString(kSliderUrdf, "slider.urdf", "."); }

// Points of a link's geometry in the link frame: the vertices of its hulls, and for a primitive
// its support points in the 26 directions of the unit cube's lattice and 64 seeded random ones
// (corners of a box, points of the rims and caps of a cylinder, points of a sphere).
std::vector<Eigen::Vector3d> geometryPoints(const dss::RobotLink& link) {
  std::vector<Eigen::Vector3d> dirs;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) dirs.emplace_back(x, y, z);
  std::mt19937_64 rng(41);
  std::normal_distribution<double> n;
  for (int k = 0; k < 64; ++k) dirs.emplace_back(n(rng), n(rng), n(rng));
  std::vector<Eigen::Vector3d> out;
  for (const dss::CollisionElement& e : link.collisions) {
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, dss::ConvexHull>) {
            for (const auto& p : s.points()) out.push_back(e.X_LS * p);
          } else {
            for (const auto& d : dirs) out.push_back(e.X_LS * s.support(d, dss::Vec3d::Zero()));
          }
        },
        e.shape);
  }
  return out;
}

double rotationAngle(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

struct Totals {
  std::size_t point_paths = 0;  // (point, link, ancestor, motion) paths compared
  double tightest = 0.0;        // largest sampled path length / bound
  double tightest_bend = 0.0;   // largest sampled second difference / bend
  std::size_t violations = 0;
  std::string first_violation;
};

// For every link with geometry and every ancestor `stop` of it (-1: the world), over `motions`
// straight motions between seeded random states (group joints uniform within their limits, the
// other joints at `held`, some motions shortened), sampled at `steps` points: the path each
// geometry point traces in stop's frame is no longer than the bound, the link turns by at most
// `turn` in that frame, every point stays within the reach at stop, the link's origin within
// originOffsetBound.
Totals checkBounds(const dss::RobotModel& robot, const std::vector<int>& group,
                   const std::vector<double>& held, std::uint64_t seed, int motions, int steps) {
  const dss::Kinematics kin(robot, /*all_links=*/true);
  std::mt19937_64 rng(seed);
  Totals totals;
  struct Chain {
    int link, stop;
    std::vector<Eigen::Vector3d> p_L;
    std::vector<dss::ChainTerm> terms;
    double reach_at_stop, offset_bound;
  };
  std::vector<Chain> chains;
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    if (!robot.links[l].hasGeometry()) continue;
    Chain c;
    c.link = int(l);
    c.p_L = geometryPoints(robot.links[l]);
    double radius = 0.0;
    for (const auto& p : c.p_L) radius = std::max(radius, p.norm());
    for (int stop = robot.links[l].parent_link;; stop = robot.links[stop].parent_link) {
      c.stop = stop;
      c.terms = dss::chainAbove(robot, c.link, stop, radius, held, &c.reach_at_stop);
      c.offset_bound = dss::originOffsetBound(robot, c.link, stop, held);
      BOOST_TEST_REQUIRE(std::isfinite(c.reach_at_stop));
      BOOST_TEST_REQUIRE(c.reach_at_stop >= radius);
      chains.push_back(c);
      if (stop < 0) break;
    }
  }
  BOOST_TEST_REQUIRE(!chains.empty());
  auto randomState = [&] {
    std::vector<double> q = held;
    for (int a : group) {
      const auto [lo, hi] = dss_test::sampleRange(robot, a);
      q[a] = std::uniform_real_distribution<double>(lo, hi)(rng);
    }
    return q;
  };
  std::vector<std::vector<Eigen::Isometry3d>> X(steps + 1);
  for (int k = 0; k < motions; ++k) {
    const std::vector<double> q0 = randomState(), q1r = randomState();
    // One motion in three is short, one in six moves a single group joint.
    const double scale = k % 3 == 2 ? 0.05 : 1.0;
    std::vector<double> q1 = q0;
    for (int a : group) q1[a] = q0[a] + scale * (q1r[a] - q0[a]);
    if (k % 6 == 5) {
      const int keep = group[k % group.size()];
      for (int a : group)
        if (a != keep) q1[a] = q0[a];
    }
    std::vector<double> qt(q0.size());
    for (int s = 0; s <= steps; ++s) {
      const double t = double(s) / steps;
      for (std::size_t i = 0; i < qt.size(); ++i) qt[i] = q0[i] + t * (q1[i] - q0[i]);
      X[s] = kin.linkPoses(qt);
    }
    for (const Chain& c : chains) {
      const dss::MotionBound b = dss::motionBound(c.terms, q0.data(), q1.data());
      BOOST_TEST_REQUIRE(std::isfinite(b.length));
      // The revolute angle of the chain: the sum of its revolute joints' |dq| (mimics scaled).
      double turn = 0.0;
      for (const dss::ChainTerm& term : c.terms)
        if (!term.prismatic && term.active >= 0)
          turn += std::abs(term.multiplier * (q1[term.active] - q0[term.active]));
      BOOST_TEST(std::abs(b.turn - turn) <= 1e-12 * (1.0 + turn));
      // From the joints' travel, as the continuous check reads it once per sub-motion: the
      // same bounds, bit for bit.
      std::vector<double> travel(q0.size());
      dss::jointTravel(q0.data(), q1.data(), q0.size(), {}, travel.data());
      const dss::MotionBound bt = dss::motionBound(c.terms, travel.data());
      BOOST_TEST((bt.length == b.length && bt.turn == b.turn && bt.bend == b.bend));
      const double length_tol = 1e-12 * (1.0 + b.length), turn_tol = 1e-9;
      auto inStop = [&](int s) {
        return c.stop < 0 ? X[s][c.link] : Eigen::Isometry3d(X[s][c.stop].inverse() * X[s][c.link]);
      };
      std::vector<Eigen::Vector3d> prev(c.p_L.size()), prev2(c.p_L.size()), first(c.p_L.size()),
          last(c.p_L.size());
      std::vector<double> path(c.p_L.size(), 0.0);
      Eigen::Isometry3d X0 = inStop(0);
      const Eigen::Isometry3d X1 = inStop(steps);
      for (std::size_t i = 0; i < c.p_L.size(); ++i) {
        prev[i] = first[i] = X0 * c.p_L[i];
        last[i] = X1 * c.p_L[i];
      }
      // The second difference (p(t+h) - 2 p(t) + p(t-h)) / h^2 is an average of p'' over
      // [t-h, t+h]; its rounding (positions of about a metre, h = 1 / steps) is covered by
      // the absolute tolerance.
      const double h2 = 1.0 / (double(steps) * steps);
      const double bend_tol = 1e-9 * (1.0 + b.bend) + 64.0 * 1e-16 / h2;
      const std::string what = robot.links[c.link].name + " relative to " +
                               (c.stop < 0 ? std::string("the world") : robot.links[c.stop].name) +
                               ", motion " + std::to_string(k) + ": ";
      auto fail = [&](const std::string& msg) {
        if (totals.violations++ == 0) totals.first_violation = what + msg;
      };
      // Plain comparisons in the loops (millions of them), one assertion per call at the end.
      for (int s = 0; s <= steps; ++s) {
        const Eigen::Isometry3d X_SL = inStop(s);
        if (!(X_SL.translation().norm() <= c.offset_bound * (1.0 + 1e-12) + 1e-12))
          fail("origin at " + std::to_string(X_SL.translation().norm()) +
               " beyond originOffsetBound " + std::to_string(c.offset_bound));
        const double angle = rotationAngle(X0.linear().transpose() * X_SL.linear());
        if (!(angle <= b.turn + turn_tol))
          fail("turned by " + std::to_string(angle) + " beyond the bound " +
               std::to_string(b.turn));
        const double t = double(s) / steps;
        for (std::size_t i = 0; i < c.p_L.size(); ++i) {
          const Eigen::Vector3d p = X_SL * c.p_L[i];
          if (!(p.norm() <= c.reach_at_stop * (1.0 + 1e-12) + 1e-12))
            fail("a point at " + std::to_string(p.norm()) + " beyond the reach " +
                 std::to_string(c.reach_at_stop));
          if (s >= 2) {
            const double accel = (p - 2.0 * prev[i] + prev2[i]).norm() / h2;
            if (!(accel <= b.bend + bend_tol))
              fail("a point's second difference " + std::to_string(accel) + " beyond the bend " +
                   std::to_string(b.bend));
            if (b.bend > 1e-6)
              totals.tightest_bend = std::max(totals.tightest_bend, accel / b.bend);
          }
          // The linear-interpolation error |p''| / 8 the continuous check pads by.
          const double off = (p - ((1.0 - t) * first[i] + t * last[i])).norm();
          if (!(off <= 0.125 * b.bend * (1.0 + 1e-9) + 1e-12))
            fail("a point " + std::to_string(off) +
                 " off its chord, beyond bend / 8 = " + std::to_string(0.125 * b.bend));
          path[i] += (p - prev[i]).norm();
          prev2[i] = prev[i];
          prev[i] = p;
        }
      }
      for (std::size_t i = 0; i < c.p_L.size(); ++i) {
        if (!(path[i] <= b.length + length_tol))
          fail("a point's path " + std::to_string(path[i]) + " beyond the bound " +
               std::to_string(b.length));
        if (b.length > 0) totals.tightest = std::max(totals.tightest, path[i] / b.length);
        ++totals.point_paths;
      }
    }
  }
  BOOST_TEST(totals.violations == 0u,
             totals.violations << " violations, the first: " << totals.first_violation);
  return totals;
}

std::vector<int> allActive(const dss::RobotModel& robot) {
  std::vector<int> all;
  for (std::size_t a = 0; a < robot.numActiveJoints(); ++a) all.push_back(int(a));
  return all;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(motion_bounds)

BOOST_AUTO_TEST_CASE(no_point_of_our_arm_outruns_its_motion_bound) {
  const dss::LoadedRobot r = dss_test::loadArm();
  const dss::RobotModel& robot = *r.model;
  const Totals world = checkBounds(robot, allActive(robot), robot.defaultState(), 3, 60, 256);
  BOOST_TEST_MESSAGE("dss_arm7: " << world.point_paths << " point paths, largest path / bound "
                                  << world.tightest << ", second difference / bend "
                                  << world.tightest_bend);
  BOOST_TEST(world.point_paths > 100000u);
  // The bound is not vacuous: on single-joint motions a point near the reach comes close.
  BOOST_TEST(world.tightest > 0.5);
  BOOST_TEST(world.tightest_bend > 0.5);
  // A group without the first two joints, held away from zero.
  std::vector<double> held = robot.defaultState();
  held[0] = 1.1;
  held[1] = -0.7;
  const Totals part = checkBounds(robot, {2, 3, 4, 5, 6}, held, 4, 30, 256);
  BOOST_TEST(part.point_paths > 10000u);
}

BOOST_AUTO_TEST_CASE(the_bend_bound_is_reached_by_a_planar_arm) {
  const dss::RobotModel robot = dss::loadUrdfString(kPlanarUrdf, "planar.urdf", ".");
  const Totals t = checkBounds(robot, allActive(robot), std::vector<double>(2, 0.0), 8, 200, 256);
  BOOST_TEST_MESSAGE("planar arm: second difference / bend " << t.tightest_bend);
  BOOST_TEST(t.tightest_bend > 0.97);
}

BOOST_AUTO_TEST_CASE(prismatic_and_mimic_joints_held_outside_their_limits) {
  const dss::RobotModel robot = sliderRobot();
  BOOST_REQUIRE(robot.numActiveJoints() == 3u);  // slide, turn, finger_joint (mirror follows)
  const int slide = robot.joints[robot.jointIndexOrThrow("slide")].active_index;
  const int turn = robot.joints[robot.jointIndexOrThrow("turn")].active_index;
  const int finger = robot.joints[robot.jointIndexOrThrow("finger_joint")].active_index;
  // Every joint moving within its limits.
  const Totals all = checkBounds(robot, allActive(robot), std::vector<double>(3, 0.0), 5, 120, 512);
  BOOST_TEST(all.point_paths > 10000u);
  BOOST_TEST_MESSAGE("slider: second difference / bend " << all.tightest_bend);
  BOOST_TEST(all.tightest_bend > 0.2);
  // Only the arm turning, the carriage and the fingers held beyond their limits: the reach of
  // the fingers about the turning joint must include their held displacement.
  std::vector<double> held(3, 0.0);
  held[slide] = 0.8;    // limits [-0.2, 0.5]
  held[finger] = 0.45;  // limits [-0.3, 0.1]: the mirror at -2 * 0.45 + 0.05 = -0.85
  const Totals outside = checkBounds(robot, {turn}, held, 6, 60, 512);
  BOOST_TEST(outside.point_paths > 1000u);
  BOOST_TEST(outside.tightest > 0.5);
  held[slide] = -0.9;
  held[finger] = -0.6;  // the mirror at 1.25
  checkBounds(robot, {turn}, held, 7, 60, 512);
}

// A floating joint (slides and a ball): the bounds from jointTravel equal those from the two
// states, for random quaternions of any scale, a quaternion and its negation (no turn), and
// the same quaternion at both ends.
BOOST_AUTO_TEST_CASE(travel_bounds_equal_state_bounds_with_a_ball_joint) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_free_flyer/";
  const dss::LoadedRobot r =
      dss::loadRobot(dir + "dss_free_flyer.urdf", dir + "dss_free_flyer.srdf");
  const dss::RobotModel& robot = *r.model;
  std::vector<int> balls;
  for (std::size_t a = 0; a < robot.numActiveJoints(); ++a) {
    const dss::RobotJoint& j = robot.joints[robot.active_joints[a]];
    if (j.type == dss::JointType::kBall && j.active_index == int(a)) balls.push_back(int(a));
  }
  BOOST_REQUIRE(balls.size() == 1u);
  const std::vector<double> held(robot.numActiveJoints(), 0.0);
  std::vector<std::vector<dss::ChainTerm>> chains;
  for (std::size_t l = 0; l < robot.links.size(); ++l)
    if (robot.links[l].hasGeometry())
      chains.push_back(dss::chainAbove(robot, int(l), -1, 0.3, held));
  BOOST_REQUIRE(!chains.empty());
  std::mt19937_64 rng(13);
  std::normal_distribution<double> n;
  int compared = 0, turning = 0;
  for (int k = 0; k < 2000; ++k) {
    std::vector<double> q0(robot.numActiveJoints()), q1(q0.size());
    for (auto& x : q0) x = n(rng);
    for (auto& x : q1) x = n(rng);
    const int b = balls[0];
    if (k % 4 == 1)
      for (int i = 0; i < 4; ++i) q1[b + i] = q0[b + i];
    if (k % 4 == 2)
      for (int i = 0; i < 4; ++i) q1[b + i] = -3.0 * q0[b + i];
    std::vector<double> travel(q0.size());
    dss::jointTravel(q0.data(), q1.data(), q0.size(), balls, travel.data());
    for (const auto& c : chains) {
      const dss::MotionBound x = dss::motionBound(c, q0.data(), q1.data());
      const dss::MotionBound y = dss::motionBound(c, travel.data());
      BOOST_TEST((x.length == y.length && x.turn == y.turn && x.bend == y.bend), "state " << k);
      ++compared;
      turning += x.turn > 1e-6;
    }
  }
  BOOST_TEST(compared >= 2000);
  BOOST_TEST(turning > 500);
}

BOOST_AUTO_TEST_CASE(prismatic_travel_covers_limits_and_held_values) {
  const dss::RobotModel robot = sliderRobot();
  std::mt19937_64 rng(9);
  const double held_values[] = {0.0, 0.5, -0.2, 0.8, -0.9, 0.45, -0.6, 3.0};
  for (double hs : held_values)
    for (double hf : held_values) {
      std::vector<double> held(3, 0.0);
      held[robot.joints[robot.jointIndexOrThrow("slide")].active_index] = hs;
      held[robot.joints[robot.jointIndexOrThrow("finger_joint")].active_index] = hf;
      for (const dss::RobotJoint& j : robot.joints) {
        const double travel = dss::prismaticTravel(robot, j, held);
        if (j.type != dss::JointType::kPrismatic) {
          BOOST_TEST(travel == 0.0, j.name);
          continue;
        }
        BOOST_TEST_REQUIRE(std::isfinite(travel));
        // The joint's own value (its leader's for a mimic) over its limits and its held value.
        const int lead = j.active_index >= 0 ? j.active_index : j.mimic_active;
        BOOST_TEST_REQUIRE(lead >= 0);
        const dss::RobotJoint& leader = robot.joints[robot.active_joints[lead]];
        std::vector<double> values = {leader.limits.lower, leader.limits.upper, held[lead]};
        for (int k = 0; k < 200; ++k)
          values.push_back(std::uniform_real_distribution<double>(leader.limits.lower,
                                                                  leader.limits.upper)(rng));
        auto displacement = [&](double v) {
          return j.active_index >= 0 ? v : j.mimic_multiplier * v + j.mimic_offset;
        };
        for (double v : values)
          BOOST_TEST(std::abs(displacement(v)) <= travel,
                     j.name << " at leader value " << v << ", travel " << travel);
        // An active joint's travel is exactly the largest of those.
        if (j.active_index >= 0)
          BOOST_TEST(travel == std::max({std::abs(j.limits.lower), std::abs(j.limits.upper),
                                         std::abs(held[lead])}),
                     j.name);
      }
    }
}

// The lowest common ancestor of two links: the lower one on a chain (our arm), the link two
// branches hang from (the Panda's fingers on its hand), a link with itself.
BOOST_AUTO_TEST_CASE(lowest_common_ancestors) {
  const dss::LoadedRobot r = dss_test::loadArm();
  const dss::RobotModel& robot = *r.model;
  auto link = [&](const dss::RobotModel& m, const std::string& name) {
    for (std::size_t i = 0; i < m.links.size(); ++i)
      if (m.links[i].name == name) return int(i);
    BOOST_FAIL("no link " << name);
    return -1;
  };
  BOOST_TEST(dss::lowestCommonAncestor(robot, link(robot, "link2"), link(robot, "link6")) ==
             link(robot, "link2"));
  BOOST_TEST(dss::lowestCommonAncestor(robot, link(robot, "tcp"), link(robot, "link3")) ==
             link(robot, "link3"));
  BOOST_TEST(dss::lowestCommonAncestor(robot, link(robot, "link5"), link(robot, "link5")) ==
             link(robot, "link5"));
  BOOST_TEST(dss::lowestCommonAncestor(robot, link(robot, "link0"), link(robot, "tool")) ==
             link(robot, "link0"));
}

BOOST_AUTO_TEST_CASE(lowest_common_ancestor_of_the_panda_fingers, DSS_NEEDS_SHARED) {
  const auto r =
      dss::loadRobot(dss_test::kPandaDir + "/panda.urdf", dss_test::kPandaDir + "/panda.srdf");
  const dss::RobotModel& m = *r.model;
  auto link = [&](const std::string& name) {
    for (std::size_t i = 0; i < m.links.size(); ++i)
      if (m.links[i].name == name) return int(i);
    BOOST_FAIL("no link " << name);
    return -1;
  };
  BOOST_TEST(dss::lowestCommonAncestor(m, link("panda_leftfinger"), link("panda_rightfinger")) ==
             link("panda_hand"));
  BOOST_TEST(dss::lowestCommonAncestor(m, link("panda_rightfinger"), link("panda_link3")) ==
             link("panda_link3"));
}

// slerpQuaternion: the normalised ends at t = 0 and 1 (up to sign), the shorter arc (a
// quaternion and a negated neighbour: the turn is the small one), a constant rate (the
// midpoint is half the angle from both ends), and unnormalised inputs.
BOOST_AUTO_TEST_CASE(slerp_moves_along_the_shorter_arc_at_a_constant_rate) {
  std::mt19937_64 rng(77);
  std::normal_distribution<double> g;
  for (int k = 0; k < 2000; ++k) {
    double a[4], b[4], out0[4], out1[4], mid[4];
    for (int i = 0; i < 4; ++i) a[i] = 3.0 * g(rng), b[i] = 0.5 * g(rng);
    dss::slerpQuaternion(a, b, 0.0, out0);
    dss::slerpQuaternion(a, b, 1.0, out1);
    dss::slerpQuaternion(a, b, 0.5, mid);
    BOOST_TEST(dss::quaternionAngle(out0, a) < 1e-6);
    BOOST_TEST(dss::quaternionAngle(out1, b) < 1e-6);
    const double whole = dss::quaternionAngle(a, b);
    BOOST_TEST(whole <= M_PI + 1e-9);  // the shorter arc
    BOOST_TEST(std::abs(dss::quaternionAngle(a, mid) - 0.5 * whole) < 1e-6);
    BOOST_TEST(std::abs(dss::quaternionAngle(mid, b) - 0.5 * whole) < 1e-6);
    double n = 0.0;
    for (double x : mid) n += x * x;
    BOOST_TEST(std::abs(n - 1.0) < 1e-12);
  }
  // A quaternion and its near-opposite: the same rotation nearly, so a tiny turn.
  const double a[4] = {0.0, 0.0, 0.0, 1.0}, b[4] = {1e-3, 0.0, 0.0, -1.0};
  double mid[4];
  dss::slerpQuaternion(a, b, 0.5, mid);
  BOOST_TEST(dss::quaternionAngle(a, mid) < 2e-3);
}

BOOST_AUTO_TEST_SUITE_END()
