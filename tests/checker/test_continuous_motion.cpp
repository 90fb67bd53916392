// The conservative continuous motion check (continuous_motion.h): its motion bound
// (paddings) holds on finely sampled random motions and shrinks quadratically on short ones;
// on random motions it never accepts what dense sampling finds colliding, and its last valid
// fraction lies before the first colliding sample; a minimum fraction outside (0, 1] is
// refused. (The OMPL motion validator on top of it: tests/planning.)
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/checker/continuous_motion.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/motion_bounds.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"

namespace {

struct Arm {
  dss::LoadedRobot robot;
  std::shared_ptr<const dss::CollisionModel> model;
  std::shared_ptr<const dss::DssChecker> checker;
};

Arm loadArm(const std::string& urdf, const std::string& srdf, const std::string& scene_file,
            const std::string& request_file = "") {
  Arm a;
  a.robot = dss::loadRobot(urdf, srdf);
  if (!request_file.empty()) {  // a planar or floating base, bounded by the request's workspace
    const dss::PlanRequest r = dss::loadPlanRequestYaml(request_file);
    BOOST_REQUIRE(r.workspace.has_value());
    a.robot = dss::withWorkspace(a.robot, r.workspace->first, r.workspace->second);
  }
  a.model = dss::setupModel(a.robot, scene_file.empty() ? dss::Scene{} : dss::loadScene(scene_file),
                            "", {})
                .model;
  a.checker = std::make_shared<const dss::DssChecker>(a.model);
  return a;
}

// Group values -> full active-joint vector (held joints at their held values).
std::vector<double> fullJoints(const dss::CollisionModel& m, const std::vector<double>& g) {
  std::vector<double> q = m.held();
  for (std::size_t i = 0; i < g.size(); ++i) q[m.groupActive()[i]] = g[i];
  return q;
}

std::vector<double> randomGroupState(const Arm& a, std::mt19937_64& rng) {
  std::vector<double> g;
  for (int act : a.model->groupActive()) {
    const auto [lo, hi] = dss_test::sampleRange(*a.robot.model, act);
    g.push_back(std::uniform_real_distribution<double>(lo, hi)(rng));
  }
  return g;
}

// The state at fraction t of the straight motion q0 -> q1 as the continuous check moves it:
// joint values linearly, a ball joint's quaternion by slerp along the shorter arc.
void interpolate(const dss::RobotModel& robot, const std::vector<double>& q0,
                 const std::vector<double>& q1, double t, std::vector<double>* qt) {
  for (std::size_t i = 0; i < qt->size(); ++i) (*qt)[i] = q0[i] + t * (q1[i] - q0[i]);
  for (std::size_t a = 0; a < robot.numActiveJoints(); ++a) {
    const dss::RobotJoint& j = robot.joints[robot.active_joints[a]];
    if (j.type == dss::JointType::kBall && j.active_index == int(a))
      dss::slerpQuaternion(q0.data() + a, q1.data() + a, t, qt->data() + a);
  }
}

double distToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double len2 = d.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

// Every point of every moving slot's bounding sphere stays within paddings() of the segment
// between its end positions, sampled finely over seeded random motions of several lengths;
// and on short motions the padding shrinks quadratically (the bulge term), far below the
// linear bound half the path length.
void checkPaddings(const Arm& a, std::uint64_t seed) {
  const dss::ContinuousMotionChecker cmc(a.checker);
  const dss::CollisionModel& m = *a.model;
  const std::size_t nl = a.robot.model->links.size();
  std::vector<Eigen::Isometry3d> X0(nl), X1(nl), Xt(nl);
  std::vector<double> pad(m.slots().size()), pad_half(m.slots().size());
  std::vector<Eigen::Vector3d> probes;
  for (int s : {-1, 1})
    for (int ax = 0; ax < 3; ++ax) probes.push_back(s * Eigen::Vector3d::Unit(ax));
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) probes.push_back(Eigen::Vector3d(sx, sy, sz).normalized());
  std::mt19937_64 rng(seed);
  double worst = 0.0;  // largest measured deviation / padding
  int violations = 0, checked = 0;
  for (double scale : {1.0, 0.3, 0.05, 0.01}) {
    for (int k = 0; k < 40; ++k) {
      const auto g0 = randomGroupState(a, rng), g1r = randomGroupState(a, rng);
      std::vector<double> g1(g0.size());
      for (std::size_t i = 0; i < g0.size(); ++i) g1[i] = g0[i] + scale * (g1r[i] - g0[i]);
      const auto q0 = fullJoints(m, g0), q1 = fullJoints(m, g1);
      cmc.paddings(q0.data(), q1.data(), pad.data());
      m.kinematics().computeLinkPoses(q0.data(), X0.data());
      m.kinematics().computeLinkPoses(q1.data(), X1.data());
      std::vector<double> qt(q0.size());
      for (int step = 1; step < 64; ++step) {
        interpolate(m.robot(), q0, q1, step / 64.0, &qt);
        m.kinematics().computeLinkPoses(qt.data(), Xt.data());
        for (std::size_t sl = 0; sl < m.slots().size(); ++sl) {
          const auto& s = m.slots()[sl];
          if (!s.moves) continue;
          for (const auto& u : probes) {
            const Eigen::Vector3d pL = s.center_L + s.radius * u;
            const double d = distToSegment(Xt[s.link] * pL, X0[s.link] * pL, X1[s.link] * pL);
            ++checked;
            if (!(d <= pad[sl])) ++violations;  // a NaN is one
            if (pad[sl] > 0) worst = std::max(worst, d / pad[sl]);
          }
        }
      }
      if (scale == 0.01) {
        // Quadratic regime: the padding is at most the turn (radians) times the linear bound.
        std::vector<double> qh(q0.size());
        double turn = 0.0;
        for (std::size_t i = 0; i < q0.size(); ++i) turn += std::abs(q1[i] - q0[i]);
        interpolate(m.robot(), q0, q1, 0.5, &qh);
        cmc.paddings(q0.data(), qh.data(), pad_half.data());
        for (std::size_t sl = 0; sl < m.slots().size(); ++sl)
          if (pad[sl] > 1e-9)
            BOOST_TEST(pad_half[sl] < 0.3 * pad[sl]);  // 1/4 up to the 1e-12 floor
        BOOST_TEST(turn < 1.0);
      }
    }
  }
  BOOST_TEST(violations == 0);
  BOOST_TEST(checked > 10000);
  BOOST_TEST_MESSAGE("paddings: " << checked << " probe positions, largest deviation / padding "
                                  << worst);
}

// Seeded random motions: when the continuous check accepts a motion, every state sampled
// 2000 times along it is free; when a sampled state collides, it rejects the motion, and its
// last valid fraction lies before the first colliding sample, at a free state.
void checkAgainstDenseSampling(const Arm& a, std::uint64_t seed, double scale, int motions) {
  const dss::ContinuousMotionChecker cmc(a.checker);
  const dss::CollisionModel& m = *a.model;
  std::mt19937_64 rng(seed);
  int accepted = 0, colliding = 0, conservative = 0, made = 0, ends_colliding = 0;
  while (made < motions) {
    const auto g0 = randomGroupState(a, rng), g1r = randomGroupState(a, rng);
    std::vector<double> g1(g0.size());
    for (std::size_t i = 0; i < g0.size(); ++i) g1[i] = g0[i] + scale * (g1r[i] - g0[i]);
    const auto q0 = fullJoints(m, g0), q1 = fullJoints(m, g1);
    if (a.checker->collides(q0.data())) continue;  // motions start at a free state
    ++made;
    double last = -1.0;
    const bool ok = cmc.clear(q0.data(), q1.data(), &last);
    // Without a last valid fraction two states are checked before the first midpoint, in either
    // order (the end and three quarters of the way; three quarters and nine tenths): the same
    // answer.
    const bool probed = cmc.clear(q0.data(), q1.data());
    BOOST_TEST(probed == ok, "motion " << made);
    const bool probed_end_last =
        cmc.clear(q0.data(), q1.data(), nullptr, dss::MotionOrder::kEndLast);
    BOOST_TEST(probed_end_last == ok, "motion " << made);
    ends_colliding += a.checker->collides(q1.data());
    int first_bad = -1;
    std::vector<double> qt(q0.size());
    const int kSamples = 2000;
    for (int step = 0; step <= kSamples && first_bad < 0; ++step) {
      for (std::size_t i = 0; i < qt.size(); ++i)
        qt[i] = q0[i] + (double(step) / kSamples) * (q1[i] - q0[i]);
      if (a.checker->collides(qt.data())) first_bad = step;
    }
    if (ok) {
      ++accepted;
      BOOST_TEST(first_bad < 0, "accepted motion " << made << " collides at sample " << first_bad);
      continue;
    }
    if (first_bad >= 0) {
      ++colliding;
      BOOST_TEST(last * kSamples < first_bad);
    } else {
      ++conservative;
    }
    BOOST_TEST(last >= 0.0);
    BOOST_TEST(last <= 1.0);
    for (std::size_t i = 0; i < qt.size(); ++i) qt[i] = q0[i] + last * (q1[i] - q0[i]);
    BOOST_TEST(!a.checker->collides(qt.data()),
               "the state at the last valid fraction " << last << " collides");
  }
  BOOST_TEST(accepted > 0);
  BOOST_TEST(colliding > 0);
  BOOST_TEST(ends_colliding > 0);
  BOOST_TEST_MESSAGE("dense sampling, scale "
                     << scale << ": " << motions << " motions, " << accepted << " accepted, "
                     << colliding << " colliding rejected, " << conservative
                     << " rejected though every sample is free; " << cmc.subMotions()
                     << " sub-motions, " << cmc.unitTests() << " swept tests");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(continuous_motion)

BOOST_AUTO_TEST_CASE(paddings_bound_every_point_of_a_moving_link) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  checkPaddings(loadArm(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf", ""), 5);
}

BOOST_AUTO_TEST_CASE(paddings_bound_every_point_of_a_moving_panda_link, DSS_NEEDS_SHARED) {
  const std::string panda = dss_test::sharedPath("robots/panda");
  checkPaddings(loadArm(panda + "/panda.urdf", panda + "/panda.srdf", ""), 6);
}

BOOST_AUTO_TEST_CASE(paddings_bound_every_point_of_a_ur5_link, DSS_NEEDS_SHARED) {
  const std::string ur5 = dss_test::sharedPath("robots/ur5_robotiq85");
  checkPaddings(loadArm(ur5 + "/ur5.urdf", ur5 + "/ur5.srdf", ""), 10);
}

// Planar (x, y prismatic under a turn) and floating bases (slides and a slerped quaternion).
BOOST_AUTO_TEST_CASE(paddings_bound_every_point_of_moving_bases) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/";
  checkPaddings(loadArm(dir + "dss_mobile_base/dss_mobile_base.urdf",
                        dir + "dss_mobile_base/dss_mobile_base.srdf", "",
                        dir + "dss_mobile_base/scenes/aisle_request.yaml"),
                11);
  checkPaddings(loadArm(dir + "dss_free_flyer/dss_free_flyer.urdf",
                        dir + "dss_free_flyer/dss_free_flyer.srdf", "",
                        dir + "dss_free_flyer/scenes/window_request.yaml"),
                12);
}

BOOST_AUTO_TEST_CASE(continuous_agrees_with_dense_sampling) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const Arm arm =
      loadArm(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf", dir + "/scenes/shelf.yaml");
  checkAgainstDenseSampling(arm, 7, 0.15, 150);
  checkAgainstDenseSampling(arm, 8, 1.0, 60);
}

BOOST_AUTO_TEST_CASE(continuous_agrees_with_dense_sampling_holding_an_object) {
  Arm arm;
  arm.robot = dss_test::loadArm();
  arm.model = dss_test::shelfSetupHoldingBar(arm.robot).model;
  arm.checker = std::make_shared<const dss::DssChecker>(arm.model);
  checkAgainstDenseSampling(arm, 17, 0.15, 120);
}

BOOST_AUTO_TEST_CASE(continuous_agrees_with_dense_sampling_on_the_panda, DSS_NEEDS_SHARED) {
  const std::string panda = dss_test::sharedPath("robots/panda");
  const std::string scene = dss_test::sharedPath("scenes/mbm_panda/bookshelf_small/scene0001.yaml");
  const Arm p = loadArm(panda + "/panda.urdf", panda + "/panda.srdf", scene);
  checkAgainstDenseSampling(p, 9, 0.15, 150);
}

// The UR5's joints turn through 4 pi: its motions are the longest of the shared robots.
BOOST_AUTO_TEST_CASE(continuous_agrees_with_dense_sampling_on_the_ur5, DSS_NEEDS_SHARED) {
  const std::string ur5 = dss_test::sharedPath("robots/ur5_robotiq85");
  const std::string scene = dss_test::sharedPath("scenes/mbm_ur5/table_pick/scene0001.yaml");
  const Arm a = loadArm(ur5 + "/ur5.urdf", ur5 + "/ur5.srdf", scene);
  checkAgainstDenseSampling(a, 14, 0.1, 400);
  checkAgainstDenseSampling(a, 15, 1.0, 100);
}

// The smallest sub-motion must be a fraction in (0, 1]: zero, negative, NaN and more than the
// whole motion are refused at construction; the ends of the range are accepted.
BOOST_AUTO_TEST_CASE(min_fraction_outside_zero_one_is_refused) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const Arm arm =
      loadArm(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf", dir + "/scenes/shelf.yaml");
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  for (double bad : {0.0, -0.0, -1e-3, -1.0, nan, -nan, std::nextafter(1.0, 2.0), 2.0, inf, -inf})
    BOOST_CHECK_THROW(dss::ContinuousMotionChecker(arm.checker, bad), std::invalid_argument);
  for (double good : {1.0, 0.5, 1.0 / 1024.0, std::numeric_limits<double>::denorm_min()})
    BOOST_CHECK_NO_THROW(dss::ContinuousMotionChecker(arm.checker, good));
  // The default is in range.
  BOOST_CHECK_NO_THROW(dss::ContinuousMotionChecker{arm.checker});
}

BOOST_AUTO_TEST_SUITE_END()
