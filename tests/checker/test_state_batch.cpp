// Eight states at once (state_batch.h, kinematics_batch.h): the float kinematics stay within
// their stated error of the double kinematics on random states (within the limits, continuous
// joints far beyond a turn, NaN lanes); a state the batch proves free is one the exact checker
// finds free, on every instruction-set path, for random states and for the states of short
// motions (our arm in its shelf; the Panda in MotionBenchMaker scenes and the UR5 and iiwa
// with the shared data); the scalar path, lanes past n, non-finite and out-of-bounds states
// prove nothing; a discrete motion check in batches gives the same verdicts and the same last
// valid fraction as one state at a time.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "dss/checker/discrete_motion.h"
#include "dss/checker/dss_checker.h"
#include "dss/robot/kinematics_batch.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"

namespace {

using dss::KinematicsBatch;
constexpr int kLanes = KinematicsBatch::kLanes;

const dss::SimdPath kLanePaths[] = {dss::SimdPath::kSse2, dss::SimdPath::kAvx2};

// The batch kinematics of `kin` against the double ones on `states` (eight at a time): every
// entry of every updated link within the stated error. Returns the largest translation error
// over the stated bound.
double kinematicsAgainstDouble(const dss::Kinematics& kin, std::size_t links,
                               const std::vector<std::vector<double>>& states) {
  const KinematicsBatch batch(kin);
  BOOST_REQUIRE(batch.supported());
  const std::size_t nq = kin.numActiveJoints();
  std::vector<KinematicsBatch::Pose> X(links);
  std::vector<Eigen::Isometry3d> ref(links, Eigen::Isometry3d::Identity());
  double worst = 0.0;
  for (const dss::SimdPath path : kLanePaths) {
    if (!dss::simdPathAvailable(path)) {
      BOOST_TEST_MESSAGE("batch kinematics: path " << dss::simdPathName(path) << " skipped");
      continue;
    }
    for (std::size_t b = 0; b + kLanes <= states.size(); b += kLanes) {
      std::vector<double> qs(nq * kLanes);
      for (int l = 0; l < kLanes; ++l)
        for (std::size_t j = 0; j < nq; ++j) qs[j * kLanes + l] = states[b + l][j];
      batch.compute(qs.data(), X.data(), path);
      for (int l = 0; l < kLanes; ++l) {
        kin.computeLinkPoses(states[b + l].data(), ref.data());
        for (int link : batch.updatedLinks()) {
          const Eigen::Matrix4d& M = ref[std::size_t(link)].matrix();
          for (int k = 0; k < 4; ++k)
            for (int i = 0; i < 3; ++i) {
              const double err = std::fabs(X[std::size_t(link)].v[3 * k + i][l] - M(i, k));
              const double bound = k == 3 ? batch.positionError() : batch.rotationError();
              BOOST_TEST(err <= bound, "link " << link << " entry (" << i << ", " << k << ") lane "
                                               << l << ": " << err);
              if (k == 3) worst = std::max(worst, err / bound);
            }
        }
      }
    }
  }
  return worst;
}

std::vector<std::vector<double>> randomStates(const dss::CollisionModel& m, int n,
                                              std::mt19937_64& rng) {
  std::vector<std::vector<double>> s;
  for (int i = 0; i < n; ++i) s.push_back(dss_test::randomGroupState(m, rng));
  return s;
}

// The states of short random motions from random states (length up to a fifth of the group's
// extent, at 1 % of it), as a motion validator interpolates them.
std::vector<std::vector<double>> motionStates(const dss::CollisionModel& m, int motions,
                                              std::mt19937_64& rng) {
  double extent2 = 0.0;
  for (int a : m.groupActive()) {
    const auto [lo, hi] = dss_test::sampleRange(m.robot(), a);
    extent2 += (hi - lo) * (hi - lo);
  }
  const double extent = std::sqrt(extent2);
  std::vector<std::vector<double>> s;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < motions; ++i) {
    const std::vector<double> q0 = dss_test::randomGroupState(m, rng);
    const std::vector<double> far = dss_test::randomGroupState(m, rng);
    double d = 0.0;
    for (int a : m.groupActive()) d += (far[a] - q0[a]) * (far[a] - q0[a]);
    const double scale = 0.2 * extent * u(rng) / std::max(std::sqrt(d), 1e-9);
    const int n = std::max(1, static_cast<int>(std::ceil(scale * std::sqrt(d) / (0.01 * extent))));
    for (int j = 1; j <= n; ++j) {
      std::vector<double> q = q0;
      for (int a : m.groupActive()) q[a] = q0[a] + (far[a] - q0[a]) * scale * j / n;
      s.push_back(q);
    }
  }
  return s;
}

struct Proven {
  long free = 0, proven = 0;
};

// Every lane the batch proves free is free by check(), on each lane path; the scalar path
// proves none. Returns the counts on the best path.
Proven provenAgainstExact(const std::shared_ptr<const dss::CollisionModel>& model,
                          const std::vector<std::vector<double>>& states) {
  Proven out;
  for (const dss::SimdPath path :
       {dss::SimdPath::kScalar, dss::SimdPath::kSse2, dss::SimdPath::kAvx2}) {
    if (!dss::simdPathAvailable(path)) {
      BOOST_TEST_MESSAGE("state batch: path " << dss::simdPathName(path) << " skipped");
      continue;
    }
    auto checker = std::make_shared<dss::DssChecker>(model);
    checker->setBatchPath(path);
    Proven p;
    for (std::size_t b = 0; b < states.size(); b += kLanes) {
      const int n = static_cast<int>(std::min<std::size_t>(kLanes, states.size() - b));
      const double* qs[kLanes];
      for (int l = 0; l < n; ++l) qs[l] = states[b + std::size_t(l)].data();
      const unsigned free = checker->freeStates(qs, n);
      BOOST_TEST((free >> n) == 0u);
      for (int l = 0; l < n; ++l) {
        const bool exact_free = checker->check(qs[l]) == dss::StateVerdict::kFree;
        const bool proven = (free >> l) & 1u;
        BOOST_TEST((!proven || exact_free),
                   "state " << b + std::size_t(l) << " proven free on " << dss::simdPathName(path));
        p.free += exact_free;
        p.proven += proven;
      }
    }
    if (path == dss::SimdPath::kScalar)
      BOOST_TEST(p.proven == 0);
    else
      out = p;
    BOOST_TEST(checker->counters().batch_free == std::uint64_t(p.proven));
  }
  return out;
}

// A batched and a one-by-one discrete motion check agree on every motion, with and without
// the last valid fraction.
void batchedMotionsAgree(const std::shared_ptr<const dss::CollisionModel>& model, int motions,
                         std::mt19937_64& rng) {
  auto checker = std::make_shared<const dss::DssChecker>(model);
  const dss::DiscreteMotionChecker plain(checker), batched(checker, true);
  const dss::CollisionModel& m = *model;
  int clear = 0;
  for (int i = 0; i < motions; ++i) {
    const std::vector<double> q0 = dss_test::randomGroupState(m, rng);
    std::vector<double> q1 = dss_test::randomGroupState(m, rng);
    const double scale = i % 2 ? 0.1 : 0.4;
    for (int a : m.groupActive()) q1[a] = q0[a] + scale * (q1[a] - q0[a]);
    for (int segments : {3, 9, 20, 41}) {
      const bool a = plain.clear(q0.data(), q1.data(), segments);
      BOOST_TEST(batched.clear(q0.data(), q1.data(), segments) == a);
      BOOST_TEST(
          batched.clear(q0.data(), q1.data(), segments, nullptr, dss::MotionOrder::kEndLast) == a);
      double fa = -1.0, fb = -1.0;
      BOOST_TEST(plain.clear(q0.data(), q1.data(), segments, &fa) == a);
      BOOST_TEST(batched.clear(q0.data(), q1.data(), segments, &fb) == a);
      BOOST_TEST(fa == fb);
      clear += a;
    }
  }
  BOOST_TEST(clear > 0);
  BOOST_TEST(clear < motions * 4);
  BOOST_TEST(checker->counters().batch_free > 0u);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(state_batch)

BOOST_AUTO_TEST_CASE(float_kinematics_within_their_error_on_our_arm) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  std::mt19937_64 rng(71);
  std::vector<std::vector<double>> states = randomStates(*setup.model, 800, rng);
  // Continuous joints far beyond a turn (reduced in double first).
  for (std::size_t i = 0; i < 80; ++i)
    for (int a : setup.model->groupActive())
      if (!robot.model->joints[robot.model->active_joints[a]].limits.has_position_limits)
        states[i][a] += (i % 2 ? 1.0 : -1.0) * 1e4;
  const double worst =
      kinematicsAgainstDouble(setup.model->sweepKinematics(), robot.model->links.size(), states);
  BOOST_TEST_MESSAGE("arm: largest translation error " << worst << " of the bound");
  BOOST_TEST(worst < 0.25);  // the bound keeps a wide factor of safety
}

BOOST_AUTO_TEST_CASE(nan_lanes_and_unsupported_models_prove_nothing) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  auto checker = std::make_shared<const dss::DssChecker>(setup.model);
  BOOST_TEST(checker->batch().enabled());
  std::mt19937_64 rng(5);
  std::vector<std::vector<double>> s = randomStates(*setup.model, kLanes, rng);
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(), 1e9};
  for (int l = 0; l < 3; ++l)
    s[std::size_t(l)][std::size_t(setup.model->groupActive()[0])] = bad[l];
  const double* qs[kLanes];
  for (int l = 0; l < kLanes; ++l) qs[l] = s[std::size_t(l)].data();
  const unsigned free = checker->freeStates(qs, kLanes);
  BOOST_TEST((free & 7u) == 0u);
  BOOST_TEST(checker->freeStates(qs, 0) == 0u);
  // A mobile base and a free flyer: no batch, every state to the exact check.
  for (const char* name : {"dss_mobile_base", "dss_free_flyer"}) {
    const dss_test::MobileSetup mob =
        dss_test::mobileSetup(name, std::string(name) == "dss_mobile_base" ? "aisle" : "window");
    const dss::DssChecker c(mob.setup.model);
    BOOST_TEST(!c.batch().enabled(), name);
    std::vector<double> q = mob.setup.model->held();
    const double* one[1] = {q.data()};
    BOOST_TEST(c.freeStates(one, 1) == 0u);
  }
}

BOOST_AUTO_TEST_CASE(proven_free_states_are_free_on_our_arm) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  std::mt19937_64 rng(99);
  std::vector<std::vector<double>> states = randomStates(*setup.model, 2000, rng);
  const std::vector<std::vector<double>> along = motionStates(*setup.model, 300, rng);
  states.insert(states.end(), along.begin(), along.end());
  const Proven p = provenAgainstExact(setup.model, states);
  BOOST_TEST_MESSAGE("arm: " << p.proven << " of " << p.free << " free states proven");
  BOOST_TEST(p.proven > p.free / 4);
}

BOOST_AUTO_TEST_CASE(batched_motions_agree_on_our_arm) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  std::mt19937_64 rng(3);
  batchedMotionsAgree(setup.model, 150, rng);
}

BOOST_AUTO_TEST_CASE(shared_robots_float_kinematics_and_proven_states, DSS_NEEDS_SHARED) {
  struct Robot {
    const char* urdf;
    const char* srdf;
    const char* scene;  // empty: no scene
  };
  const Robot robots[] = {
      {"robots/panda/panda.urdf", "robots/panda/panda.srdf", "scenes/mbm_panda/box/scene0001.yaml"},
      {"robots/panda/panda.urdf", "robots/panda/panda.srdf",
       "scenes/mbm_panda/bookshelf_small/scene0001.yaml"},
      {"robots/ur5_robotiq85/ur5.urdf", "robots/ur5_robotiq85/ur5.srdf", ""},
      {"robots/iiwa_description/iiwa14_primitive_collision.urdf", "", ""}};
  std::mt19937_64 rng(2026);
  for (const Robot& r : robots) {
    const dss::LoadedRobot robot =
        dss::loadRobot(dss_test::sharedPath(r.urdf), *r.srdf ? dss_test::sharedPath(r.srdf) : "");
    dss::Scene scene;
    if (*r.scene) scene = dss::loadScene(dss_test::sharedPath(r.scene));
    const dss::ModelSetup setup = dss::setupModel(robot, std::move(scene), "", {});
    const double worst =
        kinematicsAgainstDouble(setup.model->sweepKinematics(), robot.model->links.size(),
                                randomStates(*setup.model, 400, rng));
    BOOST_TEST(worst < 0.25, r.urdf);
    std::vector<std::vector<double>> states = randomStates(*setup.model, 1000, rng);
    const std::vector<std::vector<double>> along = motionStates(*setup.model, 150, rng);
    states.insert(states.end(), along.begin(), along.end());
    const Proven p = provenAgainstExact(setup.model, states);
    BOOST_TEST_MESSAGE(r.urdf << " " << r.scene << ": " << p.proven << " of " << p.free
                              << " free states proven");
    BOOST_TEST(p.proven > p.free / 4, r.urdf << " " << r.scene);
    batchedMotionsAgree(setup.model, 40, rng);
  }
}

BOOST_AUTO_TEST_SUITE_END()
