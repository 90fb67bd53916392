// Invalid input: the states a collision model's bounds hold for (CollisionModel::withinBounds)
// are those with every value finite, every group joint within its limits (a continuous joint:
// any value) and every other joint within its limits or exactly at its held value (which may lie
// outside them). Every state checker answers StateVerdict::kInvalidInput for any other state --
// never "free", never a collision count -- and counts it in counters().invalid_input; the DSS
// clearance of such a state is 0, and a motion from or to one is not clear.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/checker/continuous_motion.h"
#include "dss/checker/discrete_motion.h"
#include "dss/checker/dss_checker.h"
#include "dss/robot/srdf.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Our arm in its shelf scene with joint1 (active 0) held 0.5 rad beyond its upper limit and
// outside the group (joints 2..7), or inside the group (every joint) with the same held values.
struct HeldOutside {
  dss::LoadedRobot robot = dss_test::loadArm();
  std::vector<double> held;
  std::shared_ptr<const dss::CollisionModel> model;      // group: active joints 1..6
  std::shared_ptr<const dss::CollisionModel> all_group;  // group: every active joint
  HeldOutside() {
    held = dss_test::shelfSetup(robot).held;
    held[0] = joint(0).limits.upper + 0.5;
    const dss::Scene scene = dss::loadScene(dss_test::kArmDir + "/scenes/shelf.yaml");
    const dss::Srdf* srdf = robot.srdf ? &*robot.srdf : nullptr;
    model = std::make_shared<const dss::CollisionModel>(robot.model, srdf, scene,
                                                        std::vector<int>{1, 2, 3, 4, 5, 6}, held);
    all_group = std::make_shared<const dss::CollisionModel>(robot.model, srdf, scene,
                                                            std::vector<int>{}, held);
  }
  const dss::RobotJoint& joint(int active) const {
    return robot.model->joints[robot.model->active_joints[active]];
  }
};

// Group joint values that are not valid input, each with what it is.
std::vector<std::pair<double, std::string>> badGroupValues(const dss::RobotJoint& j) {
  return {{kNan, "NaN"},
          {-kNan, "-NaN"},
          {kInf, "+Inf"},
          {-kInf, "-Inf"},
          {std::nextafter(j.limits.upper, kInf), "one ulp above the upper limit"},
          {std::nextafter(j.limits.lower, -kInf), "one ulp below the lower limit"},
          {j.limits.upper + 1.0, "1 above the upper limit"},
          {1e300, "1e300"}};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(invalid_input)

BOOST_AUTO_TEST_CASE(within_bounds_takes_limits_and_held_values) {
  const HeldOutside f;
  const dss::CollisionModel& m = *f.model;
  std::vector<double> q = f.held;
  for (int a : m.groupActive()) q[a] = 0.5 * (f.joint(a).limits.lower + f.joint(a).limits.upper);
  BOOST_TEST(m.withinBounds(q.data()));
  // Group joints: the limits themselves are in; anything beyond them, or non-finite, is out.
  for (int a : m.groupActive()) {
    std::vector<double> v = q;
    for (double at : {f.joint(a).limits.lower, f.joint(a).limits.upper}) {
      v[a] = at;
      BOOST_TEST(m.withinBounds(v.data()), f.joint(a).name << " at its limit " << at);
    }
    for (const auto& [bad, what] : badGroupValues(f.joint(a))) {
      v[a] = bad;
      BOOST_TEST(!m.withinBounds(v.data()), f.joint(a).name << " " << what);
    }
  }
  // The held joint, outside the group: at its held value (beyond its limit) it is in, and so
  // is any value within its limits; another value beyond them, or a non-finite one, is out.
  const dss::RobotJoint& j0 = f.joint(0);
  BOOST_REQUIRE(f.held[0] > j0.limits.upper);
  std::vector<double> v = q;
  for (double in : {f.held[0], j0.limits.upper, j0.limits.lower, 0.0}) {
    v[0] = in;
    BOOST_TEST(m.withinBounds(v.data()), "held joint at " << in);
  }
  for (double out :
       {std::nextafter(f.held[0], kInf), std::nextafter(f.held[0], 0.0), j0.limits.upper + 0.25,
        std::nextafter(j0.limits.upper, kInf), j0.limits.lower - 1.0, kNan, kInf, -kInf}) {
    v[0] = out;
    BOOST_TEST(!m.withinBounds(v.data()), "held joint at " << out);
  }
  // With the same joint in the group, its held value gives it no exception.
  BOOST_TEST(f.all_group->withinBounds(q.data()) == false);
  v = q;
  v[0] = j0.limits.upper;
  BOOST_TEST(f.all_group->withinBounds(v.data()));
}

// A continuous joint takes any finite value (the value is an angle), but not NaN or Inf.
BOOST_AUTO_TEST_CASE(within_bounds_takes_any_finite_angle_of_a_continuous_joint) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_mobile_base";
  const dss::LoadedRobot r =
      dss::loadRobot(dir + "/dss_mobile_base.urdf", dir + "/dss_mobile_base.srdf");
  const int theta = r.model->variableIndex("base/theta");
  BOOST_REQUIRE(theta >= 0);
  BOOST_REQUIRE(r.model->joints[r.model->active_joints[theta]].type == dss::JointType::kContinuous);
  const std::vector<double> held = r.model->defaultState();
  const dss::CollisionModel m(r.model, r.srdf ? &*r.srdf : nullptr, dss::Scene{}, {}, held);
  std::vector<double> q = held;
  BOOST_TEST(m.withinBounds(q.data()));
  for (double angle : {-M_PI, M_PI, 7.0, -100.0, 1e6, -1e300}) {
    q[theta] = angle;
    BOOST_TEST(m.withinBounds(q.data()), "angle " << angle);
  }
  for (double bad : {kNan, kInf, -kInf}) {
    q[theta] = bad;
    BOOST_TEST(!m.withinBounds(q.data()), "angle " << bad);
  }
}

// A floating joint's quaternion: any direction and scale, but not (nearly) zero.
BOOST_AUTO_TEST_CASE(within_bounds_refuses_a_quaternion_without_direction) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_free_flyer";
  dss::LoadedRobot r = dss::loadRobot(dir + "/dss_free_flyer.urdf", dir + "/dss_free_flyer.srdf");
  r = dss::withWorkspace(r, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  const int w = r.model->variableIndex("base/rot_w");
  BOOST_REQUIRE(w == 6);
  const std::vector<double> held = r.model->defaultState();
  const dss::CollisionModel m(r.model, &*r.srdf, dss::Scene{}, {}, held);
  std::vector<double> q = held;
  BOOST_TEST(m.withinBounds(q.data()));
  q[w] = 0.5;  // not unit: normalised by the kinematics
  q[3] = 0.5;
  BOOST_TEST(m.withinBounds(q.data()));
  for (int k = 3; k < 7; ++k) q[k] = 0.0;
  BOOST_TEST(!m.withinBounds(q.data()));
  q[w] = 1e-7;
  BOOST_TEST(!m.withinBounds(q.data()));
  q[w] = 2e-6;  // small but above the smallest norm
  BOOST_TEST(m.withinBounds(q.data()));
  // Non-finite components are out, and so is a squared norm that overflows.
  for (double bad : {kInf, -kInf, kNan}) {
    q[w] = bad;
    BOOST_TEST(!m.withinBounds(q.data()), "rot_w " << bad);
    q[w] = 1.0;
    q[3] = bad;
    BOOST_TEST(!m.withinBounds(q.data()), "rot_x " << bad);
    q[3] = 0.0;
  }
  q[3] = 1e200;
  BOOST_TEST(!m.withinBounds(q.data()));
  q[3] = 0.0;
  q[w] = 1e-7;
  const dss::DssChecker c(std::make_shared<const dss::CollisionModel>(
      r.model, &*r.srdf, dss::Scene{}, std::vector<int>{}, held));
  BOOST_TEST((c.check(q.data()) == dss::StateVerdict::kInvalidInput));
}

// A multi-DOF joint that the group does not move (the mobile base's planar joint when only its
// mast arm plans) is folded into the kinematics at its held values: a state must hold it there
// exactly, a finite value elsewhere (even within the workspace) is out, and so is NaN.
BOOST_AUTO_TEST_CASE(within_bounds_holds_an_unmoved_multi_dof_joint_at_its_values) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_mobile_base";
  const dss::LoadedRobot r =
      dss::loadRobot(dir + "/dss_mobile_base.urdf", dir + "/dss_mobile_base.srdf");
  std::vector<double> held = r.model->defaultState();
  const int x = r.model->variableIndex("base/x"), theta = r.model->variableIndex("base/theta");
  BOOST_REQUIRE(x >= 0);
  BOOST_REQUIRE(theta >= 0);
  held[x] = 1.25;
  held[theta] = 0.5;
  const std::vector<int> arm = dss::groupActiveJoints(*r.model, *r.srdf, "mast_arm");
  BOOST_REQUIRE(std::find(arm.begin(), arm.end(), x) == arm.end());
  const dss::CollisionModel m(r.model, &*r.srdf, dss::Scene{}, arm, held);
  std::vector<double> q = held;
  BOOST_TEST(m.withinBounds(q.data()));
  for (double v : {1.0, std::nextafter(1.25, kInf), 0.0, kNan, kInf}) {
    q[x] = v;
    BOOST_TEST(!m.withinBounds(q.data()), "base/x at " << v);
  }
  q = held;
  for (double v : {0.5 + 2 * M_PI, std::nextafter(0.5, 0.0), kNan, -kInf}) {
    q[theta] = v;
    BOOST_TEST(!m.withinBounds(q.data()), "base/theta at " << v);
  }
}

BOOST_AUTO_TEST_CASE(checkers_refuse_invalid_input_and_count_it) {
  const HeldOutside f;
  const dss::CollisionModel& m = *f.model;
  // Valid states: a free one and a colliding one (seeded search), and the same with the held
  // joint at a value within its limits instead of its held value.
  const dss::DssChecker reference(f.model);
  std::mt19937_64 rng(17);
  std::vector<double> free_q, colliding_q;
  for (int k = 0; k < 10000 && (free_q.empty() || colliding_q.empty()); ++k) {
    std::vector<double> q = dss_test::randomGroupState(m, rng);
    const dss::StateVerdict v = reference.check(q.data());
    BOOST_REQUIRE(v != dss::StateVerdict::kInvalidInput);
    (v == dss::StateVerdict::kFree ? free_q : colliding_q) = q;
  }
  BOOST_REQUIRE(!free_q.empty());
  BOOST_REQUIRE(!colliding_q.empty());
  std::vector<std::pair<std::vector<double>, std::string>> valid = {
      {free_q, "free state"}, {colliding_q, "colliding state"}};
  for (auto [q, what] : std::vector<std::pair<std::vector<double>, std::string>>(valid)) {
    q[0] = 0.3;
    valid.emplace_back(q, what + " with the held joint within its limits");
  }
  // Invalid states: each bad value in each group joint, and in the held joint.
  std::vector<std::pair<std::vector<double>, std::string>> invalid;
  for (int a : m.groupActive())
    for (const auto& [bad, what] : badGroupValues(f.joint(a))) {
      std::vector<double> q = free_q;
      q[a] = bad;
      invalid.emplace_back(q, f.joint(a).name + " " + what);
    }
  for (double bad : {kNan, kInf, std::nextafter(f.held[0], kInf), f.joint(0).limits.upper + 0.25}) {
    std::vector<double> q = free_q;
    q[0] = bad;
    invalid.emplace_back(q, "held joint at " + std::to_string(bad));
  }
  for (const char* name : {"dss", "fcl-hull", "fcl-mesh"})
    for (const char* prefilter : {"aabb", "shared"}) {
      if (std::string(name) == "dss" && std::string(prefilter) == "shared") continue;
      dss::CheckerConfig config;
      config.checker = name;
      config.fcl_prefilter = prefilter;
      const auto checker = dss::makeStateChecker(f.model, config);
      const std::string who = std::string(name) + "/" + prefilter;
      const dss::CheckerCounters start = checker->counters();
      BOOST_TEST(start.checks == 0u);
      std::uint64_t colliding = 0;
      for (const auto& [q, what] : valid) {
        const dss::StateVerdict v = checker->check(q.data());
        BOOST_TEST((v != dss::StateVerdict::kInvalidInput), who << ": " << what);
        colliding += v == dss::StateVerdict::kColliding;
      }
      const dss::CheckerCounters after_valid = checker->counters();
      for (const auto& [q, what] : invalid) {
        BOOST_TEST((checker->check(q.data()) == dss::StateVerdict::kInvalidInput),
                   who << ": " << what);
        BOOST_TEST(checker->collides(q.data()), who << ": " << what);
      }
      // Each invalid state checked twice (check and collides): counted as checked and as
      // invalid input, never as a collision, and with no narrow-phase test.
      const dss::CheckerCounters d = checker->counters() - after_valid;
      BOOST_TEST(d.checks == 2 * invalid.size(), who);
      BOOST_TEST(d.invalid_input == 2 * invalid.size(), who);
      BOOST_TEST(d.collisions == 0u, who);
      BOOST_TEST(d.pair_tests == 0u, who);
      const dss::CheckerCounters v = after_valid - start;
      BOOST_TEST(v.checks == valid.size(), who);
      BOOST_TEST(v.invalid_input == 0u, who);
      BOOST_TEST(v.collisions == colliding, who);
    }
  // The model with joint1 in the group refuses its held value (beyond the limit).
  const dss::DssChecker all(f.all_group);
  BOOST_TEST((all.check(free_q.data()) == dss::StateVerdict::kInvalidInput));
  BOOST_TEST(all.counters().invalid_input == 1u);
}

BOOST_AUTO_TEST_CASE(invalid_states_have_no_clearance_and_no_clear_motion) {
  const HeldOutside f;
  const auto checker = std::make_shared<const dss::DssChecker>(f.model);
  const dss::ContinuousMotionChecker motion(checker);
  std::mt19937_64 rng(19);
  std::vector<double> free_q;
  for (int k = 0; k < 10000 && free_q.empty(); ++k) {
    std::vector<double> q = dss_test::randomGroupState(*f.model, rng);
    if (checker->check(q.data()) == dss::StateVerdict::kFree && checker->clearance(q.data()) > 0.0)
      free_q = q;
  }
  BOOST_REQUIRE(!free_q.empty());
  // A motion that stays where it is, at a free state, is clear.
  double last = -1.0;
  BOOST_TEST(motion.clear(free_q.data(), free_q.data(), &last));
  const int a = f.model->groupActive()[2];
  for (const auto& [bad, what] : badGroupValues(f.joint(a))) {
    std::vector<double> q = free_q;
    q[a] = bad;
    BOOST_TEST(checker->clearance(q.data()) == 0.0, what);
    last = -1.0;
    BOOST_TEST(!motion.clear(free_q.data(), q.data(), &last), what);
    BOOST_TEST(last == 0.0, what);
    last = -1.0;
    BOOST_TEST(!motion.clear(q.data(), free_q.data(), &last), what);
    BOOST_TEST(last == 0.0, what);
  }
}

// The discrete motion check (one by one and in batches) of a motion from or to an invalid
// state: never clear, whatever the number of segments (with one segment only the end would be
// checked); with the first colliding state asked for, the first state (fraction 0).
BOOST_AUTO_TEST_CASE(a_discrete_motion_from_or_to_an_invalid_state_is_not_clear) {
  const HeldOutside f;
  const auto checker = std::make_shared<const dss::DssChecker>(f.model);
  std::mt19937_64 rng(23);
  std::vector<double> free_q;
  for (int k = 0; k < 10000 && free_q.empty(); ++k) {
    std::vector<double> q = dss_test::randomGroupState(*f.model, rng);
    if (checker->check(q.data()) == dss::StateVerdict::kFree) free_q = q;
  }
  BOOST_REQUIRE(!free_q.empty());
  const int a = f.model->groupActive()[2];
  for (const bool batched : {false, true}) {
    const dss::DiscreteMotionChecker motion(checker, batched);
    BOOST_TEST(motion.clear(free_q.data(), free_q.data(), 1));
    for (const auto& [bad, what] : badGroupValues(f.joint(a)))
      for (const int segments : {1, 2, 9}) {
        std::vector<double> q = free_q;
        q[a] = bad;
        const std::string at =
            what + ", " + std::to_string(segments) + " segments" + (batched ? ", batched" : "");
        BOOST_TEST(!motion.clear(free_q.data(), q.data(), segments), at);
        BOOST_TEST(!motion.clear(q.data(), free_q.data(), segments), at << " (start)");
        double last = -1.0;
        BOOST_TEST(!motion.clear(q.data(), free_q.data(), segments, &last), at << " (start)");
        BOOST_TEST(last == 0.0, at);
      }
  }
}

// Eight states at once (CollisionModel::boundedHeldLanes, the batches' first test): bit l is
// withinBounds && heldMatch of state l, on lanes drawn from the limits, one ulp beyond them,
// held values, non-finite values and quaternions without direction (seeded), on each path.
BOOST_AUTO_TEST_CASE(bounded_held_lanes_are_within_bounds_and_held_match_per_state) {
  const HeldOutside f;
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_free_flyer";
  dss::LoadedRobot flyer =
      dss::loadRobot(dir + "/dss_free_flyer.urdf", dir + "/dss_free_flyer.srdf");
  flyer = dss::withWorkspace(flyer, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  const dss::CollisionModel flyer_model(flyer.model, &*flyer.srdf, dss::Scene{}, {},
                                        flyer.model->defaultState());
  std::mt19937_64 rng(7);
  for (const dss::CollisionModel* m : {f.model.get(), f.all_group.get(), &flyer_model}) {
    const dss::RobotModel& robot = m->robot();
    const std::size_t nq = robot.numActiveJoints();
    int passed = 0, failed = 0;
    for (int round = 0; round < 400; ++round) {
      std::vector<std::vector<double>> states(8, m->held());
      std::vector<double> lanes(nq * 8);
      for (int l = 0; l < 8; ++l) {
        for (std::size_t a = 0; a < nq; ++a) {
          const dss::RobotJoint& j = robot.joints[robot.active_joints[a]];
          const double lo = std::max(j.limits.lower, -2.0), hi = std::min(j.limits.upper, 2.0);
          // Mostly valid values, so that whole lanes pass; one in five a limit, one ulp
          // beyond one, the held value or a non-finite value.
          const double odd[] = {lo,
                                hi,
                                std::nextafter(lo, -kInf),
                                std::nextafter(hi, kInf),
                                kNan,
                                kInf,
                                m->held()[a],
                                m->held()[a]};
          const std::size_t pick = rng() % 40;
          states[l][a] = pick < 8 ? odd[pick] : lo + (hi - lo) * double(rng() % 1000) / 999.0;
        }
        if (m == &flyer_model && rng() % 8 == 0)  // a quaternion without direction
          for (std::size_t k = 3; k < 7; ++k) states[l][k] = 0.0;
        for (std::size_t a = 0; a < nq; ++a) lanes[a * 8 + std::size_t(l)] = states[l][a];
      }
      for (dss::SimdPath path : {dss::SimdPath::kSse2, dss::SimdPath::kAvx2}) {
        const unsigned bits = m->boundedHeldLanes(lanes.data(), path);
        for (int l = 0; l < 8; ++l) {
          const bool expect = m->withinBounds(states[l].data()) && m->heldMatch(states[l].data());
          BOOST_TEST(((bits >> l) & 1u) == unsigned(expect), "round " << round << " lane " << l);
          (expect ? passed : failed) += 1;
        }
      }
    }
    // Both answers were asked for.
    BOOST_TEST(passed > 100);
    BOOST_TEST(failed > 100);
  }
}

BOOST_AUTO_TEST_SUITE_END()
