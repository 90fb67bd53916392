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
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dss/checker/contacts.h"
#include "dss/checker/discrete_motion.h"
#include "dss/checker/dss_checker.h"
#include "dss/robot/kinematics_batch.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"
#include "support/temp_files.h"

namespace {

using dss::KinematicsBatch;
constexpr int kLanes = KinematicsBatch::kLanes;

const dss::SimdPath kLanePaths[] = {dss::SimdPath::kSse2, dss::SimdPath::kAvx2};

// The batch kinematics of `kin` against the double ones on `states` (eight at a time): every
// entry of every updated link within the stated error, and the same floats on every lane path.
// Returns the largest translation error over the stated bound.
double kinematicsAgainstDouble(const dss::Kinematics& kin, std::size_t links,
                               const std::vector<std::vector<double>>& states) {
  const KinematicsBatch batch(kin);
  BOOST_REQUIRE(batch.supported());
  const std::size_t nq = kin.numActiveJoints();
  std::vector<KinematicsBatch::Pose> X(links);
  std::vector<Eigen::Isometry3d> ref(links, Eigen::Isometry3d::Identity());
  double worst = 0.0;
  std::vector<float> first_path;  // the entries the first path computed, in order
  std::size_t entry = 0;
  for (const dss::SimdPath path : kLanePaths) {
    if (!dss::simdPathAvailable(path)) {
      BOOST_TEST_MESSAGE("batch kinematics: path " << dss::simdPathName(path) << " skipped");
      continue;
    }
    const bool first = first_path.empty();
    entry = 0;
    for (std::size_t b = 0; b + kLanes <= states.size(); b += kLanes) {
      std::vector<double> qs(nq * kLanes);
      for (int l = 0; l < kLanes; ++l)
        for (std::size_t j = 0; j < nq; ++j) qs[j * kLanes + l] = states[b + l][j];
      batch.compute(qs.data(), X.data(), path);
      for (int link : batch.updatedLinks())
        for (const auto& row : X[std::size_t(link)].v)
          for (float v : row) {
            if (first) {
              first_path.push_back(v);
            } else {
              BOOST_TEST((std::memcmp(&v, &first_path[entry], sizeof v) == 0),
                         "entry " << entry << " on " << dss::simdPathName(path));
            }
            ++entry;
          }
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

// Our arm with its last joint continuous: a copy of its URDF, joint7's type changed, written
// beside a link to the arm's meshes.
dss::LoadedRobot continuousArm() {
  std::ifstream in(dss_test::kArmDir + "/dss_arm7.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  const std::string from = "<joint name=\"joint7\" type=\"revolute\">";
  const std::size_t at = urdf.find(from);
  BOOST_REQUIRE(at != std::string::npos);
  urdf.replace(at, from.size(), "<joint name=\"joint7\" type=\"continuous\">");
  const std::string file = dss_test::writeScratch("state_batch", "arm_continuous.urdf", urdf);
  const std::filesystem::path meshes = dss_test::scratchDir("state_batch") / "meshes";
  if (!std::filesystem::exists(meshes))
    std::filesystem::create_directory_symlink(dss_test::kArmDir + "/meshes", meshes);
  return dss::loadRobot(file, dss_test::kArmDir + "/dss_arm7.srdf");
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

// Every lane the batch proves free is free by check(), on each lane path, and the lane paths
// prove the same lanes; the scalar path proves none. Returns the counts on the best path.
Proven provenAgainstExact(const std::shared_ptr<const dss::CollisionModel>& model,
                          const std::vector<std::vector<double>>& states) {
  Proven out;
  std::vector<unsigned> lane_bits;  // per batch, the first lane path's proven lanes
  for (const dss::SimdPath path :
       {dss::SimdPath::kScalar, dss::SimdPath::kSse2, dss::SimdPath::kAvx2}) {
    if (!dss::simdPathAvailable(path)) {
      BOOST_TEST_MESSAGE("state batch: path " << dss::simdPathName(path) << " skipped");
      continue;
    }
    auto checker = std::make_shared<dss::DssChecker>(model);
    checker->setBatchPath(path);
    const bool first_lanes = path != dss::SimdPath::kScalar && lane_bits.empty();
    std::size_t batch_index = 0;
    Proven p;
    for (std::size_t b = 0; b < states.size(); b += kLanes) {
      const int n = static_cast<int>(std::min<std::size_t>(kLanes, states.size() - b));
      const double* qs[kLanes];
      for (int l = 0; l < n; ++l) qs[l] = states[b + std::size_t(l)].data();
      const unsigned free = checker->freeStates(qs, n);
      BOOST_TEST((free >> n) == 0u);
      if (first_lanes)
        lane_bits.push_back(free);
      else if (path != dss::SimdPath::kScalar)
        BOOST_TEST(free == lane_bits[batch_index],
                   "batch " << batch_index << " on " << dss::simdPathName(path));
      ++batch_index;
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
  BOOST_REQUIRE(batched.batched());
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
  const dss::LoadedRobot robot = continuousArm();
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
  const dss::LoadedRobot robot = continuousArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  // A value the batch refuses (NaN, infinite, or an angle beyond 1e5 rad, where its reduction
  // is not certified, down to one ulp beyond) in each lane in turn, on each lane path: that
  // lane is never proven, and the others still are. An angle of exactly 1e5 rad is taken.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        kInf,
                        1e9,
                        2e5,
                        -2e5,
                        std::nextafter(1e5, kInf),
                        -std::nextafter(1e5, kInf)};
  // A continuous joint: the bounds take any finite value of it.
  std::size_t joint = 0;
  for (int a : setup.model->groupActive())
    if (!robot.model->joints[robot.model->active_joints[a]].limits.has_position_limits)
      joint = std::size_t(a);
  BOOST_REQUIRE(!robot.model->joints[robot.model->active_joints[joint]].limits.has_position_limits);
  std::mt19937_64 rng(5);
  for (const dss::SimdPath path : kLanePaths) {
    if (!dss::simdPathAvailable(path)) continue;
    auto checker = std::make_shared<dss::DssChecker>(setup.model);
    BOOST_TEST(checker->batch().enabled());
    checker->setBatchPath(path);
    int others_proven = 0, edge_proven = 0;
    for (int round = 0; round < 28; ++round) {
      std::vector<std::vector<double>> s = randomStates(*setup.model, kLanes, rng);
      const int lane = round % kLanes;
      s[std::size_t(lane)][joint] = bad[std::size_t(round) % std::size(bad)];
      const double* qs[kLanes];
      for (int l = 0; l < kLanes; ++l) qs[l] = s[std::size_t(l)].data();
      const unsigned free = checker->freeStates(qs, kLanes);
      BOOST_TEST(((free >> lane) & 1u) == 0u, "lane " << lane << " on " << dss::simdPathName(path));
      others_proven += __builtin_popcount(free & ~(1u << lane));
      BOOST_TEST(checker->freeStates(qs, 0) == 0u);
      // The same lane at exactly +-1e5 rad.
      s[std::size_t(lane)][joint] = round % 2 ? 1e5 : -1e5;
      edge_proven += (checker->freeStates(qs, kLanes) >> lane) & 1u;
    }
    BOOST_TEST(others_proven > 20);
    BOOST_TEST(edge_proven > 0);
  }
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

BOOST_AUTO_TEST_CASE(batched_motions_agree_on_our_arm, DSS_NEEDS_BATCHES) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetup(robot);
  std::mt19937_64 rng(3);
  batchedMotionsAgree(setup.model, 150, rng);
}

BOOST_AUTO_TEST_CASE(a_held_object_in_the_lanes_of_our_arm) {
  const dss::LoadedRobot robot = dss_test::loadArm();
  const dss::ModelSetup setup = dss_test::shelfSetupHoldingBar(robot);
  std::mt19937_64 rng(5);
  std::vector<std::vector<double>> states = randomStates(*setup.model, 1500, rng);
  const std::vector<std::vector<double>> along = motionStates(*setup.model, 300, rng);
  states.insert(states.end(), along.begin(), along.end());
  // The bar is in some of the collisions (against the shelf and against the arm).
  const dss::DssChecker exact(setup.model);
  int by_bar = 0;
  for (const auto& q : states)
    if (const auto contacts = dss::contactsAt(exact, q.data()))
      for (const dss::Contact& c : *contacts)
        by_bar += dss::describeContact(*setup.model, c).find("'bar'") != std::string::npos;
  BOOST_TEST(by_bar > 0);
  const Proven p = provenAgainstExact(setup.model, states);
  BOOST_TEST_MESSAGE("arm holding a bar: " << p.proven << " of " << p.free
                                           << " free states proven, " << by_bar
                                           << " contacts of the bar");
  if (dss::activeSimdPath() == dss::SimdPath::kAvx2) {
    BOOST_TEST(p.proven > p.free / 4);
    batchedMotionsAgree(setup.model, 100, rng);
  } else {
    BOOST_TEST_MESSAGE("arm holding a bar: not on the AVX2 path, batched motions not compared");
  }
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
    if (dss::activeSimdPath() == dss::SimdPath::kAvx2)
      batchedMotionsAgree(setup.model, 40, rng);
    else
      BOOST_TEST_MESSAGE(r.urdf << ": batched motions skipped (not on the AVX2 path)");
  }
}

BOOST_AUTO_TEST_SUITE_END()
