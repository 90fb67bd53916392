// The discrete motion check (dss/checker/discrete_motion.h) and its OMPL validator
// (discrete_motion_validator.h): each order visits every state of a motion once; the verdict
// and the first colliding state do not depend on the order, nor on batches proving states free
// (the first states of the order one by one, the end never in a batch); the joint-space
// interpolation is OMPL's to the bit; and on random motions of our robots (plain, continuous,
// planar and floating joints) and of the Panda and UR5 in MotionBenchMaker scenes, the validator
// gives OMPL's DiscreteMotionValidator's verdicts and lastValid (fraction and state), with and
// without the direct joint-value path, in both orders; the validity checker knows the last state
// it found free; a checker that forwards to ours is looked through (the same states asked); the
// counts per kind of motion take every motion once and every state of it at most once.
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "dss/checker/discrete_motion.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/multi_dof.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"
#include "support/thrown_message.h"

namespace ob = ompl::base;

namespace {

const std::string kRobots = std::string(DSS_SOURCE_DIR) + "/robots";

// A continuous joint about z under a revolute one, reaching a box: an SO(2) part in the space.
const char* kTurnerUrdf = R"(<robot name="turner">
  <link name="base"/>
  <link name="arm"><collision><origin xyz="0.5 0 0"/><geometry><box size="0.8 0.05 0.05"/></geometry></collision></link>
  <link name="tip"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.3 0.04 0.04"/></geometry></collision></link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
  <joint name="bend" type="revolute"><parent link="arm"/><child link="tip"/><origin xyz="0.9 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
</robot>)";

// A problem with its validity checker set.
struct Case {
  std::string name;
  dss::Problem p;
  std::shared_ptr<dss::ValidityChecker> checker;
};

Case finish(std::string name, dss::Problem p) {
  Case c{std::move(name), std::move(p), nullptr};
  c.checker = dss::makeValidityChecker(c.p, {"dss"});
  c.p.si->setStateValidityChecker(c.checker);
  c.p.si->setup();
  return c;
}

Case fromFiles(const std::string& name, const std::string& urdf, const std::string& srdf,
               const std::string& scene, const std::string& request) {
  const auto req = dss::loadPlanRequestYaml(request);
  dss::LoadedRobot robot = dss::loadRobot(urdf, srdf);
  std::map<std::string, double> start = req.startState();
  if (req.workspace) {
    robot = dss::withWorkspace(robot, req.workspace->first, req.workspace->second);
    for (const auto& [n, v] : dss::multiDofStateValues(*robot.model, req.start_multi_dof))
      start[n] = v;
  }
  return finish(name, dss::makeProblem(robot, dss::loadScene(scene), req.group_name, start));
}

Case ourCase(const std::string& robot, const std::string& scene) {
  const std::string dir = kRobots + "/" + robot;
  return fromFiles(robot, dir + "/" + robot + ".urdf", dir + "/" + robot + ".srdf",
                   dir + "/scenes/" + scene + ".yaml", dir + "/scenes/" + scene + "_request.yaml");
}

Case turnerCase() {
  dss::LoadedRobot r;
  r.model =
      std::make_shared<const dss::RobotModel>(dss::loadUrdfString(kTurnerUrdf, "turner.urdf", "."));
  dss::Scene scene;
  for (int k = 0; k < 3; ++k) {
    dss::Obstacle o;
    o.name = o.object_id = "post" + std::to_string(k);
    o.shape = dss::Box::fromSize(Eigen::Vector3d(0.1, 0.1, 0.5));
    const double a = 2.0 * M_PI * k / 3.0 + 0.4;
    o.X_WO = Eigen::Isometry3d(Eigen::Translation3d(1.1 * std::cos(a), 1.1 * std::sin(a), 0.0));
    o.X_FO = o.X_WO;
    scene.obstacles.push_back(o);
  }
  return finish("turner", dss::makeProblem(r, scene, "", {}));
}

// A seeded uniform state of the case's space: group values within their bounds (quaternions
// normalised by the map).
void randomState(const Case& c, std::mt19937_64& rng, ob::State* s) {
  const dss::GroupStateMap& map = *c.p.map;
  std::vector<double> g(map.dimension());
  for (std::size_t i = 0; i < g.size(); ++i)
    g[i] = std::uniform_real_distribution<double>(map.lower(i), map.upper(i))(rng);
  map.fromGroupValues(g.data(), s);
}

// Random motions of the case's space: from a valid state (as OMPL assumes), to a uniform state
// (every other motion) or to a point at most a fifth of the way to one (short motions).
// Compares the validator with OMPL's, with and without lastValid; returns the motions found
// colliding.
int compareWithOmpl(const Case& c, const ob::MotionValidator& ours, int motions,
                    std::uint64_t seed) {
  const ob::SpaceInformationPtr& si = c.p.si;
  const ob::StateSpacePtr& space = si->getStateSpace();
  ob::DiscreteMotionValidator ompl(si);
  std::mt19937_64 rng(seed);
  ob::ScopedState<> a(space), b(space), far(space), la(space), lb(space);
  int colliding = 0;
  for (int m = 0; m < motions; ++m) {
    int tries = 0;
    do randomState(c, rng, a.get());
    while (!si->isValid(a.get()) && ++tries < 1000);
    randomState(c, rng, far.get());
    if (m % 2 == 0)
      space->copyState(b.get(), far.get());
    else
      space->interpolate(a.get(), far.get(), 0.2 * std::uniform_real_distribution<>()(rng),
                         b.get());
    // Ours right after the start was found valid (the end-last order, as from RRTConnect's goal
    // tree), then after OMPL's validator has checked other states (mostly the end-first order).
    const bool a_valid = si->isValid(a.get());
    const bool end_last = ours.checkMotion(a.get(), b.get());
    const bool expect = ompl.checkMotion(a.get(), b.get());
    BOOST_TEST(end_last == expect, c.name << " motion " << m << (a_valid ? "" : " (a invalid)"));
    BOOST_TEST(ours.checkMotion(a.get(), b.get()) == expect, c.name << " motion " << m);
    std::pair<ob::State*, double> lv_ompl{la.get(), -1.0}, lv_ours{lb.get(), -2.0};
    const bool expect_lv = ompl.checkMotion(a.get(), b.get(), lv_ompl);
    BOOST_TEST(expect_lv == expect);
    BOOST_TEST(ours.checkMotion(a.get(), b.get(), lv_ours) == expect_lv, c.name << " motion " << m);
    if (!expect_lv) {
      ++colliding;
      BOOST_TEST(lv_ours.second == lv_ompl.second, c.name << " motion " << m);
      BOOST_TEST(space->equalStates(la.get(), lb.get()), c.name << " motion " << m);
    }
  }
  return colliding;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(discrete_motion_validator)

BOOST_AUTO_TEST_CASE(each_order_takes_every_state_once) {
  using dss::MotionOrder;
  std::vector<int> order;
  for (MotionOrder kind : {MotionOrder::kEndFirst, MotionOrder::kEndLast}) {
    for (int n = 0; n <= 300; ++n) {
      dss::discreteCheckOrder(n, kind, order);
      BOOST_REQUIRE(order.size() == std::size_t(n));
      std::vector<int> sorted = order;
      std::sort(sorted.begin(), sorted.end());
      for (int j = 0; j < n; ++j) BOOST_REQUIRE(sorted[std::size_t(j)] == j + 1);
      if (n >= 20 && kind == MotionOrder::kEndFirst) {
        BOOST_TEST(order[0] == n);      // the end, then the middle of 1 .. n - 1
        BOOST_TEST(order[1] == n / 2);  // (OMPL's order)
      }
      if (n >= 20 && kind == MotionOrder::kEndLast) {
        BOOST_TEST(order[0] == static_cast<int>(std::lround(0.75 * n)), "n " << n);
        BOOST_TEST(order[1] == static_cast<int>(std::lround(0.9 * n)), "n " << n);
        BOOST_TEST(order[2] == n / 2);
        BOOST_TEST(order.back() == n);
      }
    }
    // The per-thread cache hands out the same orders, below and above its size.
    for (int n : {1, 2, 7, 100, 256, 257, 1000, 7}) {
      dss::discreteCheckOrder(n, kind, order);
      const int* cached = dss::cachedCheckOrder(n, kind);
      BOOST_TEST(std::vector<int>(cached, cached + n) == order, "n " << n);
    }
  }
  dss::discreteCheckOrder(1, MotionOrder::kEndLast, order);
  BOOST_TEST(order == std::vector<int>{1});
  dss::discreteCheckOrder(3, MotionOrder::kEndFirst, order);
  BOOST_TEST(order == (std::vector<int>{3, 1, 2}));
  dss::discreteCheckOrder(4, MotionOrder::kEndLast, order);
  BOOST_TEST(order == (std::vector<int>{3, 2, 1, 4}));
}

// The cursor the checks walk gives discreteCheckOrder's order, from the cache up to 256
// segments and generated level by level beyond; a motion of 2^30 segments starts at once (its
// order is not stored: it would take 4 GiB) and its end, then its middle, come first.
BOOST_AUTO_TEST_CASE(the_cursor_gives_the_order_without_storing_it) {
  using dss::MotionOrder;
  std::vector<int> order;
  for (MotionOrder kind : {MotionOrder::kEndFirst, MotionOrder::kEndLast}) {
    std::vector<int> sizes;
    for (int n = 0; n <= 1100; ++n) sizes.push_back(n);
    for (int n : {2047, 2048, 2049, 4095, 4096, 10007, 65536, 100003}) sizes.push_back(n);
    for (const int n : sizes) {
      dss::discreteCheckOrder(n, kind, order);
      dss::CheckOrderCursor cursor(n, kind);
      std::vector<int> walked;
      for (int j = cursor.next(); j != 0 && walked.size() <= order.size(); j = cursor.next())
        walked.push_back(j);
      BOOST_REQUIRE_MESSAGE(walked == order,
                            "n " << n << (kind == MotionOrder::kEndLast ? " end last" : ""));
      BOOST_TEST(cursor.next() == 0);
    }
    const int huge = 1 << 30;
    dss::CheckOrderCursor cursor(huge, kind);
    std::vector<int> head;
    for (int k = 0; k < 5; ++k) head.push_back(cursor.next());
    if (kind == MotionOrder::kEndFirst)
      BOOST_TEST(head == (std::vector<int>{huge, huge / 2, huge / 4, 3 * (huge / 4), huge / 8}));
    else
      BOOST_TEST(head ==
                 (std::vector<int>{int(std::lround(0.75 * huge)), int(std::lround(0.9 * huge)),
                                   huge / 2, huge / 4, huge / 8}));
  }
  // The checks themselves: a motion of 2^30 segments whose end collides ends at its first
  // state, one whose start is the only free state at its second (the middle).
  int asked = 0;
  BOOST_TEST(!dss::motionStatesFree(1 << 30, [&](int j) { return ++asked, j != (1 << 30); }));
  BOOST_TEST(asked == 1);
  asked = 0;
  BOOST_TEST(!dss::motionStatesFree(1 << 30, [&](int) { return ++asked == 1; }));
  BOOST_TEST(asked == 2);
}

BOOST_AUTO_TEST_CASE(the_verdict_and_first_colliding_state_do_not_depend_on_the_order) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + int(rng() % 60);
    std::set<int> colliding;  // empty, one state, a run, or scattered states
    const int kind = int(rng() % 4);
    if (kind == 1) colliding.insert(1 + int(rng() % unsigned(n)));
    if (kind == 2) {
      const int lo = 1 + int(rng() % unsigned(n)), len = 1 + int(rng() % 8);
      for (int j = lo; j <= std::min(n, lo + len - 1); ++j) colliding.insert(j);
    }
    if (kind == 3)
      for (int j = 1; j <= n; ++j)
        if (rng() % 5 == 0) colliding.insert(j);
    std::vector<int> asked;
    auto free = [&](int j) {
      asked.push_back(j);
      return colliding.count(j) == 0;
    };
    const bool verdict = colliding.empty();
    for (dss::MotionOrder kind : {dss::MotionOrder::kEndFirst, dss::MotionOrder::kEndLast}) {
      asked.clear();
      BOOST_REQUIRE(dss::motionStatesFree(n, free, nullptr, kind) == verdict);
      // Each state at most once; all of them for a free motion.
      std::set<int> once(asked.begin(), asked.end());
      BOOST_REQUIRE(once.size() == asked.size());
      if (verdict) BOOST_REQUIRE(int(asked.size()) == n);
    }
    asked.clear();
    int first = -1;
    BOOST_REQUIRE(dss::motionStatesFree(n, free, &first) == verdict);
    BOOST_REQUIRE(first == (verdict ? n + 1 : *colliding.begin()));
    // In order from the start, up to the first colliding state.
    BOOST_REQUIRE(int(asked.size()) == std::min(first, n));
    for (std::size_t k = 0; k < asked.size(); ++k) BOOST_REQUIRE(asked[k] == int(k) + 1);
  }
}

// The batched check (a batch proving a random part of the free states it is given): the
// verdict and first colliding state of the one-by-one check; the first states of the order one
// by one before any batch (the end of a motion towards a new state, the two states near the end
// of one towards a held state); the end state never in a batch; no batch of fewer than
// kMotionMinBatch or more than kMotionBatch states; every state at most once, and in the order.
BOOST_AUTO_TEST_CASE(batches_answer_as_the_states_one_by_one) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 1 + int(rng() % 60);
    std::set<int> colliding;
    const int shape = int(rng() % 4);
    if (shape == 1) colliding.insert(1 + int(rng() % unsigned(n)));
    if (shape == 2) {
      const int lo = 1 + int(rng() % unsigned(n)), len = 1 + int(rng() % 8);
      for (int j = lo; j <= std::min(n, lo + len - 1); ++j) colliding.insert(j);
    }
    if (shape == 3)
      for (int j = 1; j <= n; ++j)
        if (rng() % 5 == 0) colliding.insert(j);
    const bool verdict = colliding.empty();
    std::vector<int> seen;  // every state as first given to free or to a batch
    std::set<int> batched, proven_free;
    int singles_before_batch = -1, singles = 0;
    auto free = [&](int j) {
      BOOST_REQUIRE(proven_free.count(j) == 0);  // a proven state is never checked again
      if (batched.count(j) == 0) seen.push_back(j);
      ++singles;
      return colliding.count(j) == 0;
    };
    auto batch = [&](const int* js, int m) {
      BOOST_REQUIRE(m >= dss::kMotionMinBatch);
      BOOST_REQUIRE(m <= dss::kMotionBatch);
      if (singles_before_batch < 0) singles_before_batch = singles;
      unsigned proven = 0;
      for (int i = 0; i < m; ++i) {
        BOOST_REQUIRE(js[i] != n);
        seen.push_back(js[i]);
        batched.insert(js[i]);
        if (colliding.count(js[i]) == 0 && rng() % 4 != 0)
          proven |= 1u << i, proven_free.insert(js[i]);
      }
      return proven;
    };
    for (dss::MotionOrder kind : {dss::MotionOrder::kEndFirst, dss::MotionOrder::kEndLast}) {
      std::vector<int> order;
      dss::CheckOrderCursor cursor(n, kind);
      for (int j = cursor.next(); j != 0; j = cursor.next()) order.push_back(j);
      seen.clear(), batched.clear(), proven_free.clear();
      singles_before_batch = -1, singles = 0;
      BOOST_REQUIRE(dss::motionStatesFreeBatched(n, free, batch, nullptr, kind) == verdict);
      const int probes = kind == dss::MotionOrder::kEndFirst ? dss::kMotionProbesEndFirst
                                                             : dss::kMotionProbesEndLast;
      if (singles_before_batch >= 0) BOOST_REQUIRE(singles_before_batch >= probes);
      BOOST_REQUIRE(seen.size() <= order.size());
      if (verdict) BOOST_REQUIRE(seen.size() == order.size());
      for (std::size_t k = 0; k < seen.size(); ++k) BOOST_REQUIRE(seen[k] == order[k]);
      if (kind == dss::MotionOrder::kEndFirst) BOOST_REQUIRE(order.front() == n);
    }
    // From the start: the first colliding state, states in order.
    std::vector<int> asked_batched;
    auto free_in_order = [&](int j) {
      asked_batched.push_back(j);
      return colliding.count(j) == 0;
    };
    batched.clear(), proven_free.clear();
    int first = -1;
    BOOST_REQUIRE(dss::motionStatesFreeBatched(n, free_in_order, batch, &first) == verdict);
    BOOST_REQUIRE(first == (verdict ? n + 1 : *colliding.begin()));
    for (std::size_t k = 1; k < asked_batched.size(); ++k)
      BOOST_REQUIRE(asked_batched[k] > asked_batched[k - 1]);
  }
}

BOOST_AUTO_TEST_CASE(joint_value_interpolation_is_omples_to_the_bit) {
  // OMPL's real vector interpolation against the formula the direct path uses.
  const Case c = ourCase("dss_arm7", "shelf");
  BOOST_REQUIRE(c.p.map->plain());
  const ob::StateSpacePtr& space = c.p.si->getStateSpace();
  ob::StateSamplerPtr sampler = space->allocStateSampler();
  ob::ScopedState<> a(space), b(space), s(space);
  const std::size_t nq = c.p.model->robot().numActiveJoints();
  std::vector<double> qa(nq), qb(nq), qs(nq), q(nq);
  int differing_from_naive = 0;
  for (int k = 0; k < 2000; ++k) {
    sampler->sampleUniform(a.get());
    sampler->sampleUniform(b.get());
    const int n = 1 + k % 97;
    const int j = k % n;
    const double t = double(j) / double(n);
    space->interpolate(a.get(), b.get(), t, s.get());
    c.p.map->toJoints(a.get(), qa.data());
    c.p.map->toJoints(b.get(), qb.data());
    c.p.map->toJoints(s.get(), qs.data());
    for (std::size_t i = 0; i < nq; ++i) {
      q[i] = qa[i] + (qb[i] - qa[i]) * t;
      BOOST_REQUIRE(q[i] == qs[i]);
      differing_from_naive += (1.0 - t) * qa[i] + t * qb[i] != qs[i];
    }
  }
  // The comparison can fail: another formula of the same line differs in the last bits.
  BOOST_TEST(differing_from_naive > 0);
}

BOOST_AUTO_TEST_CASE(the_joint_space_check_answers_as_its_states_one_by_one) {
  const Case c = ourCase("dss_arm7", "shelf");
  const auto checker = c.checker->checkerPtr();
  const dss::DiscreteMotionChecker motion(checker);
  const std::size_t nq = c.p.model->robot().numActiveJoints();
  std::mt19937_64 rng(11);
  int colliding = 0;
  for (int m = 0; m < 400; ++m) {
    const std::vector<double> q0 = dss_test::randomGroupState(*c.p.model, rng);
    const std::vector<double> q1 = dss_test::randomGroupState(*c.p.model, rng);
    const int n = 1 + int(rng() % 40);
    // The reference: every state in order.
    int first = n + 1;
    std::vector<double> q(nq);
    for (int j = 1; j <= n && first > n; ++j) {
      const double t = double(j) / double(n);
      for (std::size_t k = 0; k < nq; ++k) q[k] = q0[k] + (q1[k] - q0[k]) * t;
      if (checker->collides(j == n ? q1.data() : q.data())) first = j;
    }
    colliding += first <= n;
    BOOST_TEST(motion.clear(q0.data(), q1.data(), n) == (first > n));
    BOOST_TEST(motion.clear(q0.data(), q1.data(), n, nullptr, dss::MotionOrder::kEndLast) ==
               (first > n));
    double last = -1.0;
    BOOST_TEST(motion.clear(q0.data(), q1.data(), n, &last) == (first > n));
    if (first <= n) BOOST_TEST(last == double(first - 1) / double(n));
  }
  BOOST_TEST_MESSAGE("colliding motions: " << colliding << " of 400");
  BOOST_TEST(colliding > 40);
  BOOST_TEST(colliding < 360);
  BOOST_CHECK_THROW(dss::DiscreteMotionChecker(nullptr), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(same_verdicts_and_last_valid_as_ompl_on_our_robots) {
  std::vector<Case> cases;
  cases.push_back(ourCase("dss_arm7", "shelf"));         // plain: the direct path
  cases.push_back(turnerCase());                         // a continuous joint: SO(2)
  cases.push_back(ourCase("dss_mobile_base", "aisle"));  // SE(2)
  cases.push_back(ourCase("dss_free_flyer", "window"));  // SE(3)
  for (const Case& c : cases)
    for (const bool batched : {false, true}) {  // discrete, vector
      auto ours = dss::makeDiscreteMotionValidator(c.p, *c.checker, batched);
      const auto before = c.checker->checker().counters();
      const int colliding = compareWithOmpl(c, *ours, 400, 3);
      BOOST_TEST_MESSAGE(c.name << (batched ? " (vector)" : "") << ": " << colliding
                                << " of 400 motions colliding");
      BOOST_TEST(colliding > 20, c.name);
      BOOST_TEST(colliding < 380, c.name);
      BOOST_TEST(dss::motionChecks(*ours) == 3u * 400u, c.name);  // twice, and with lastValid
      // The vector validator decides states in batches on the arm (a plain joint space), where
      // the batches pay (an AVX2 CPU).
      const std::uint64_t batch_free = (c.checker->checker().counters() - before).batch_free;
      BOOST_TEST((batch_free > 0u) ==
                     (batched && c.name == "dss_arm7" && c.checker->checker().batchesPay()),
                 c.name);
    }
}

BOOST_AUTO_TEST_CASE(the_counts_take_every_motion_and_state_once) {
  std::vector<Case> cases;
  cases.push_back(ourCase("dss_arm7", "shelf"));         // the direct path (and batches)
  cases.push_back(ourCase("dss_free_flyer", "window"));  // the space's interpolation
  for (const Case& c : cases)
    for (const bool batched : {false, true}) {
      const auto ours = dss::makeDiscreteMotionValidator(c.p, *c.checker, batched);
      const ob::SpaceInformationPtr& si = c.p.si;
      const ob::StateSpacePtr& space = si->getStateSpace();
      std::mt19937_64 rng(17);
      ob::ScopedState<> a(space), b(space), far(space), other(space), lv(space);
      auto validState = [&](ob::State* s) {
        for (int tries = 0; tries < 1000; ++tries) {
          randomState(c, rng, s);
          if (si->isValid(s)) return true;
        }
        return false;
      };
      std::uint64_t batch_free = 0, colliding = 0;
      for (int m = 0; m < 300; ++m) {
        BOOST_TEST_REQUIRE(validState(a.get()));
        randomState(c, rng, far.get());
        space->interpolate(a.get(), far.get(), 0.3 * std::uniform_real_distribution<>()(rng),
                           b.get());
        // From the state just found free (a connection), or after another one (an extension).
        const dss::MotionOrder kind =
            m % 2 == 0 ? dss::MotionOrder::kEndLast : dss::MotionOrder::kEndFirst;
        const dss::MotionOrder other_kind =
            m % 2 == 0 ? dss::MotionOrder::kEndFirst : dss::MotionOrder::kEndLast;
        if (kind == dss::MotionOrder::kEndFirst) BOOST_TEST_REQUIRE(validState(other.get()));
        const dss::MotionCounts before = ours->counts(kind);
        const dss::MotionCounts other_before = ours->counts(other_kind);
        std::pair<ob::State*, double> last{lv.get(), 0.0};
        const bool ok = m % 3 == 0 ? ours->checkMotion(a.get(), b.get(), last)
                                   : ours->checkMotion(a.get(), b.get());
        const dss::MotionCounts after = ours->counts(kind);
        const std::uint64_t n = std::max(1u, space->validSegmentCount(a.get(), b.get()));
        const std::uint64_t exact = after.exact_states - before.exact_states;
        const std::uint64_t proven = after.batch_free_states - before.batch_free_states;
        BOOST_TEST(after.motions == before.motions + 1, c.name << " motion " << m);
        BOOST_TEST(after.colliding == before.colliding + (ok ? 0u : 1u), c.name << " motion " << m);
        // Every state of a free motion once, either way; a colliding motion ends on a state
        // decided one by one, and decides no state twice.
        if (ok)
          BOOST_TEST(exact + proven == n, c.name << " motion " << m);
        else
          BOOST_TEST((exact >= 1u && exact + proven <= n), c.name << " motion " << m);
        const dss::MotionCounts other_after = ours->counts(other_kind);
        BOOST_TEST(other_after.motions == other_before.motions, c.name << " motion " << m);
        BOOST_TEST(other_after.exact_states == other_before.exact_states);
        batch_free += proven;
        colliding += ok ? 0u : 1u;
      }
      const dss::MotionCounts first = ours->counts(dss::MotionOrder::kEndFirst);
      const dss::MotionCounts held = ours->counts(dss::MotionOrder::kEndLast);
      BOOST_TEST(first.motions == 150u);
      BOOST_TEST(held.motions == 150u);
      BOOST_TEST(first.motions + held.motions == dss::motionChecks(*ours));
      BOOST_TEST(first.colliding + held.colliding == colliding);
      BOOST_TEST(ours->invalidMotions() == colliding);
      BOOST_TEST(ours->validMotions() == 300u - colliding);
      BOOST_TEST(colliding > 10u, c.name);  // both verdicts occur
      BOOST_TEST(colliding < 290u, c.name);
      // Batches only in the vector validator on the arm, where they pay (an AVX2 CPU).
      BOOST_TEST((batch_free > 0u) ==
                     (batched && c.name == "dss_arm7" && c.checker->checker().batchesPay()),
                 c.name);
    }
}

BOOST_AUTO_TEST_CASE(the_validity_checker_knows_the_last_state_it_found_free) {
  const Case c = ourCase("dss_arm7", "shelf");
  const Case other = ourCase("dss_arm7", "shelf");
  std::mt19937_64 rng(13);
  const ob::StateSpacePtr& space = c.p.si->getStateSpace();
  ob::ScopedState<> s(space), t(space), u(space);
  // Two free states and a colliding one.
  do randomState(c, rng, s.get());
  while (!c.checker->isValid(s.get()));
  do randomState(c, rng, t.get());
  while (!c.checker->isValid(t.get()));
  do randomState(c, rng, u.get());
  while (c.checker->isValid(u.get()));
  BOOST_TEST(c.checker->lastFoundFree(t.get()));  // the colliding one changed nothing
  BOOST_TEST(!c.checker->lastFoundFree(s.get()));
  BOOST_TEST(!c.checker->lastFoundFree(u.get()));
  BOOST_TEST(!other.checker->lastFoundFree(t.get()));  // another adapter's record
  BOOST_REQUIRE(c.checker->isValid(s.get()));
  BOOST_TEST(c.checker->lastFoundFree(s.get()));
  BOOST_TEST(!c.checker->lastFoundFree(t.get()));
  ob::ScopedState<> s2(space);
  s2 = s;
  s2[0] = std::nextafter(s2[0], 10.0);  // one bit off: another state
  BOOST_TEST(!c.checker->lastFoundFree(s2.get()));
  // The same in an SE(3) space (group values: position and quaternion).
  const Case flyer = ourCase("dss_free_flyer", "window");
  ob::ScopedState<> f(flyer.p.si->getStateSpace()), f2(flyer.p.si->getStateSpace());
  do randomState(flyer, rng, f.get());
  while (!flyer.checker->isValid(f.get()));
  BOOST_TEST(flyer.checker->lastFoundFree(f.get()));
  do randomState(flyer, rng, f2.get());
  while (!flyer.checker->isValid(f2.get()));
  BOOST_TEST(!flyer.checker->lastFoundFree(f.get()));
  BOOST_TEST(flyer.checker->lastFoundFree(f2.get()));
}

BOOST_AUTO_TEST_CASE(another_validity_checker_decides_every_state) {
  // A validity checker that is not the motion checker's (here: FCL on the same model): the
  // validator asks it for every state, so the verdicts are FCL's, as OMPL's validator gives.
  Case c = ourCase("dss_arm7", "shelf");
  auto dss_checker = c.checker;
  auto fcl = dss::makeValidityChecker(c.p, {"fcl-hull"});
  c.p.si->setStateValidityChecker(fcl);
  auto ours = dss::makeDiscreteMotionValidator(c.p, *dss_checker);
  const std::uint64_t dss_checks = dss_checker->counters().checks;
  compareWithOmpl(c, *ours, 200, 5);
  BOOST_TEST(dss_checker->counters().checks == dss_checks);  // DSS never asked
  BOOST_TEST(fcl->counters().checks > 0u);
}

namespace {
// Passes every state on to one of our validity checkers (as dss_plan's benchmark switch does).
class Forwarding : public dss::ForwardingValidityChecker {
 public:
  Forwarding(const ob::SpaceInformationPtr& si, std::shared_ptr<dss::ValidityChecker> inner)
      : dss::ForwardingValidityChecker(si), inner_(std::move(inner)) {}
  bool isValid(const ob::State* s) const override { return inner_->isValid(s); }
  const dss::ValidityChecker* target() const override { return inner_.get(); }

 private:
  std::shared_ptr<dss::ValidityChecker> inner_;
};
}  // namespace

BOOST_AUTO_TEST_CASE(a_forwarding_checker_is_looked_through) {
  // The same motions checked under our validity checker and under a checker that forwards to
  // it: the same verdicts, and the same states asked (the same orders, the end-last one after
  // the start was found free), so the same number of checks.
  BOOST_TEST(dss::decidingChecker(nullptr) == nullptr);
  std::uint64_t checks[2] = {0, 0};
  int colliding[2] = {0, 0};
  for (int forward : {0, 1}) {
    Case c = ourCase("dss_arm7", "shelf");
    auto wrapper = std::make_shared<Forwarding>(c.p.si, c.checker);
    if (forward) c.p.si->setStateValidityChecker(wrapper);
    BOOST_TEST(dss::decidingChecker(wrapper.get()) == c.checker.get());
    BOOST_TEST(dss::decidingChecker(c.checker.get()) == c.checker.get());
    auto ours = dss::makeDiscreteMotionValidator(c.p, *c.checker);
    const std::uint64_t before = c.checker->counters().checks;
    colliding[forward] = compareWithOmpl(c, *ours, 300, 23);
    checks[forward] = c.checker->counters().checks - before;
  }
  BOOST_TEST(colliding[0] > 20);
  BOOST_TEST(colliding[1] == colliding[0]);
  BOOST_TEST(checks[1] == checks[0]);
  // A checker that is not ours and does not forward: none to look through.
  Case c = ourCase("dss_arm7", "shelf");
  auto other = std::make_shared<ob::AllValidStateValidityChecker>(c.p.si);
  BOOST_TEST(dss::decidingChecker(other.get()) == nullptr);
}

BOOST_AUTO_TEST_CASE(same_verdicts_and_last_valid_as_ompl_on_mbm_problems, DSS_NEEDS_SHARED) {
  const std::string robots = std::string(DSS_SHARED_DIR) + "/robots";
  for (const std::string type : {"bookshelf_small", "bookshelf_tall", "bookshelf_thin", "box",
                                 "cage", "table_pick", "table_under_pick"}) {
    for (const std::string robot : {"panda", "ur5"}) {
      const std::string dir = robot == "panda" ? robots + "/panda" : robots + "/ur5_robotiq85";
      const std::string folder = dss_test::sharedPath("scenes/mbm_" + robot + "/" + type);
      const Case c =
          fromFiles(robot + " " + type, dir + "/" + robot + ".urdf", dir + "/" + robot + ".srdf",
                    folder + "/scene0001.yaml", folder + "/request0001.yaml");
      BOOST_REQUIRE(c.p.map->plain());
      for (const bool batched : {false, true}) {  // discrete, vector
        auto ours = dss::makeDiscreteMotionValidator(c.p, *c.checker, batched);
        const int colliding = compareWithOmpl(c, *ours, 150, 17);
        BOOST_TEST_MESSAGE(c.name << (batched ? " (vector)" : "") << ": " << colliding
                                  << " of 150 motions colliding");
        BOOST_TEST(colliding > 5, c.name);
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()

// NaN and Inf are never free, nor a bounded value beyond its limits (1e300): a motion with one
// at either end collides under the discrete, vector and continuous validators, with and
// without lastValid (which then says no state of the motion is valid), on a plain space and on
// one with an SO(2) part. An SO(2) angle written beyond [-pi, pi] (OMPL's SO(2) distance
// asserts on it) is the same angle within it: the same verdicts.
BOOST_AUTO_TEST_SUITE(non_finite_ends)
BOOST_AUTO_TEST_CASE(a_motion_with_nan_inf_or_out_of_bounds_at_an_end_collides) {
  int bad_states = 0, wrapped_motions = 0;
  for (Case c : {ourCase("dss_arm7", "shelf"), turnerCase()}) {
    const ob::SpaceInformationPtr& si = c.p.si;
    const ob::StateSpacePtr& space = si->getStateSpace();
    std::vector<ob::MotionValidatorPtr> validators = {
        dss::makeDiscreteMotionValidator(c.p, *c.checker, false),
        dss::makeDiscreteMotionValidator(c.p, *c.checker, true),
        dss::makeContinuousMotionValidator(c.p, *c.checker)};
    std::mt19937_64 rng(5);
    ob::ScopedState<> free_state(space), bad(space), last(space);
    int tries = 0;
    do randomState(c, rng, free_state.get());
    while (!si->isValid(free_state.get()) && ++tries < 1000);
    BOOST_REQUIRE(si->isValid(free_state.get()));
    auto expectColliding = [&](const std::string& what) {
      ++bad_states;
      for (std::size_t k = 0; k < validators.size(); ++k) {
        const ob::MotionValidator& mv = *validators[k];
        const std::string at = c.name + " validator " + std::to_string(k) + ": " + what;
        BOOST_TEST(!mv.checkMotion(free_state.get(), bad.get()), at << " (end)");
        BOOST_TEST(!mv.checkMotion(bad.get(), free_state.get()), at << " (start)");
        std::pair<ob::State*, double> lv{last.get(), -1.0};
        BOOST_TEST(!mv.checkMotion(bad.get(), free_state.get(), lv), at << " (start, lastValid)");
        BOOST_TEST(lv.second == 0.0, at);
      }
    };
    const dss::GroupStateMap& map = *c.p.map;
    std::vector<double> g(map.dimension()), back(map.dimension());
    for (const double v :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity(), 1e300})
      for (std::size_t i = 0; i < g.size(); ++i) {
        map.toGroupValues(free_state.get(), g.data());
        g[i] = v;
        map.fromGroupValues(g.data(), bad.get());
        // (The map wraps a finite angle of SO(2) into its bounds: a valid angle.)
        map.toGroupValues(bad.get(), back.data());
        if (std::isfinite(v) && back[i] != v) continue;
        expectColliding("value " + std::to_string(i) + " = " + std::to_string(v));
      }
    // An angle of SO(2) outside [-pi, pi], written into the state (OMPL's SO(2) distance
    // asserts on it): the same angle within it, the same verdicts as the wrapped state's.
    if (const auto* cs = dynamic_cast<const ob::CompoundStateSpace*>(space.get()))
      for (unsigned k = 0; k < cs->getSubspaceCount(); ++k)
        if (cs->getSubspace(k)->getType() == ob::STATE_SPACE_SO2) {
          ob::ScopedState<> wrapped(space), far(space);
          for (int m = 0; m < 200; ++m) {
            randomState(c, rng, far.get());
            space->copyState(bad.get(), far.get());
            double& angle =
                bad->as<ob::CompoundState>()->as<ob::SO2StateSpace::StateType>(k)->value;
            angle += angle < 0 ? 2.0 * M_PI : -2.0 * M_PI;
            space->copyState(wrapped.get(), bad.get());
            space->enforceBounds(wrapped.get());
            BOOST_REQUIRE(!space->satisfiesBounds(bad.get()));
            for (std::size_t v = 0; v < validators.size(); ++v) {
              const ob::MotionValidator& mv = *validators[v];
              BOOST_TEST(mv.checkMotion(free_state.get(), bad.get()) ==
                             mv.checkMotion(free_state.get(), wrapped.get()),
                         c.name << " validator " << v << " motion " << m);
            }
            ++wrapped_motions;
          }
        }
  }
  // Four values into each of the arm's 7 and the turner's 2, less 1e300 into the turner's SO(2)
  // angle (wrapped by the map).
  BOOST_TEST(bad_states == 4 * 7 + 4 * 2 - 1);
  BOOST_TEST(wrapped_motions == 200);
}
BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(discrete_motion_validator)

// Before the space is set up it has no resolution (its longest valid segment is 0, and OMPL's
// segment count divides by it): a motion check then throws rather than check the end alone. On
// the shelf, a motion whose end is free and whose middle collides: refused once set up.
BOOST_AUTO_TEST_CASE(a_motion_checked_before_the_space_is_set_up_throws) {
  const std::string dir = kRobots + "/dss_arm7";
  const dss::LoadedRobot robot = dss::loadRobot(dir + "/dss_arm7.urdf", dir + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(dir + "/scenes/shelf_request.yaml");
  dss::Problem p = dss::makeProblem(robot, dss::loadScene(dir + "/scenes/shelf.yaml"),
                                    req.group_name, req.startState());
  auto checker = dss::makeValidityChecker(p, {"dss"});
  p.si->setStateValidityChecker(checker);
  const ob::SpaceInformationPtr& si = p.si;
  // The ends: valid states, found before the set-up through the validity checker alone.
  std::mt19937_64 rng(3);
  const auto& bounds = si->getStateSpace()->as<ob::RealVectorStateSpace>()->getBounds();
  ob::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace()), mid(si->getStateSpace());
  auto draw = [&](ob::ScopedState<>& s) {
    for (int tries = 0; tries < 10000; ++tries) {
      for (std::size_t j = 0; j < bounds.low.size(); ++j)
        s[j] = std::uniform_real_distribution<double>(bounds.low[j], bounds.high[j])(rng);
      if (si->isValid(s.get())) return;
    }
    BOOST_FAIL("no valid state in 10000 draws");
  };
  bool found = false;
  for (int k = 0; k < 2000 && !found; ++k) {
    draw(a), draw(b);
    si->getStateSpace()->interpolate(a.get(), b.get(), 0.5, mid.get());
    found = !si->isValid(mid.get());
  }
  BOOST_REQUIRE(found);
  for (const bool vector : {false, true}) {
    auto mv = dss::makeDiscreteMotionValidator(p, *checker, vector);
    std::pair<ob::State*, double> last{mid.get(), -1.0};
    const std::string m =
        dss_test::thrownMessage<std::logic_error>([&] { (void)mv->checkMotion(a.get(), b.get()); });
    BOOST_TEST(m.find("not set up") != std::string::npos, m);
    BOOST_TEST(m.find("call setup()") != std::string::npos, m);
    BOOST_CHECK_THROW((void)mv->checkMotion(a.get(), b.get(), last), std::logic_error);
  }
  si->setup();
  for (const bool vector : {false, true}) {
    auto mv = dss::makeDiscreteMotionValidator(p, *checker, vector);
    BOOST_TEST(!mv->checkMotion(a.get(), b.get()));
  }
}

BOOST_AUTO_TEST_SUITE_END()
