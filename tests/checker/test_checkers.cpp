// State checkers (state_checker.h) on real models: DSS (dss_checker.h) against fcl-hull and
// fcl-mesh (fcl_checker.h) on random Panda and UR5 states of the MotionBenchMaker scenes
// (near-contact band measured with fcl::distance, DSS "free" against fcl-mesh "colliding" shown
// to be a real gap from DSS's separating direction); one checker asked from two threads giving
// the same answers as from one, with every check counted.
#include <algorithm>
#include <atomic>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <random>
#include <thread>

#include "dss/checker/checker_setup.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/fcl_checker.h"
#include "dss/checker/sweep.h"
#include "dss/core/any_shape_query.h"
#include "dss/core/posed.h"
#include "dss/core/ref.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;

namespace {

const std::string kPanda = dss_test::kPandaDir;
const std::string kMbm = dss_test::kMbmPanda;

// DSS's gap for a disjoint answer: -(h_A(n) + h_B(-n)) / |n| with the supports of the posed shapes.
double dssGap(const dss::AnyShape& a, const Eigen::Isometry3d& X_A, const dss::AnyShape& b,
              const Eigen::Isometry3d& X_B) {
  const dss::Result r = dss::intersect(a, X_A, b, X_B);
  if (r.intersect) return -1.0;
  const dss::Vec3d n = r.separating_direction;
  auto h = [](const dss::AnyShape& s, const Eigen::Isometry3d& X, const dss::Vec3d& d) {
    return std::visit(
        [&](const auto& x) {
          using S = std::decay_t<decltype(x)>;
          const dss::Posed<dss::detail::Ref<S>> p(dss::detail::Ref<S>{x}, X.linear(),
                                                  X.translation());
          return p.support(d, dss::Vec3d::Zero()).dot(d);
        },
        s);
  };
  return -(h(a, X_A, n) + h(b, X_B, -n)) / n.norm();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(state_checkers)

BOOST_AUTO_TEST_CASE(two_threads_give_the_same_answers) {
  const auto r = dss_test::loadArm();
  const dss::ModelSetup p = dss_test::shelfSetup(r);
  const dss::DssChecker c(p.model);
  std::mt19937_64 rng(3);
  std::vector<std::vector<double>> states;
  for (int k = 0; k < 4000; ++k) states.push_back(dss_test::randomGroupState(*p.model, rng));
  std::vector<char> one(states.size()), two(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) one[i] = !c.collides(states[i].data());
  auto work = [&](std::size_t begin) {
    for (std::size_t i = begin; i < states.size(); i += 2) two[i] = !c.collides(states[i].data());
  };
  std::thread t0(work, 0), t1(work, 1);
  t0.join();
  t1.join();
  BOOST_TEST(one == two);
  std::size_t valid = std::count(one.begin(), one.end(), 1);
  BOOST_TEST(valid > 0u);
  BOOST_TEST(valid < states.size());
  const dss::CheckerCounters counters = c.counters();
  BOOST_TEST(counters.checks == 2 * states.size());
  BOOST_TEST(counters.invalid_input == 0u);
  BOOST_TEST(counters.collisions == 2 * (states.size() - valid));
}

BOOST_AUTO_TEST_CASE(counts_add_up_beyond_the_owned_slots) {
  // More threads than there are owned counter slots: the later threads share the overflow
  // slot, whose additions are atomic, so that no count is lost. The threads run at once (the
  // first waits for the last to start) so that the overflow slot is written concurrently.
  const auto r = dss_test::loadArm();
  const dss::ModelSetup p = dss_test::shelfSetup(r);
  const dss::DssChecker c(p.model);
  std::mt19937_64 rng(11);
  std::vector<std::vector<double>> states;
  for (int k = 0; k < 300; ++k) states.push_back(dss_test::randomGroupState(*p.model, rng));
  std::size_t colliding = 0;
  for (const auto& q : states) colliding += c.collides(q.data());
  const dss::CheckerCounters before = c.counters();
  const int threads = 2 * dss::kOwnedSlots + 3;
  std::atomic<int> started{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      ++started;
      while (started.load() < threads) std::this_thread::yield();
      for (const auto& q : states) c.collides(q.data());
    });
  for (auto& th : pool) th.join();
  const dss::CheckerCounters added = c.counters() - before;
  BOOST_TEST(added.checks == std::uint64_t(threads) * states.size());
  BOOST_TEST(added.collisions == std::uint64_t(threads) * colliding);
  BOOST_TEST(colliding > 0u);
  BOOST_TEST(dss::threadSlotIndex() >= 0);
  BOOST_TEST(dss::threadSlotIndex() <= dss::kOwnedSlots);
}

BOOST_AUTO_TEST_CASE(timed_checks_add_their_time_and_change_no_answer) {
  const auto r = dss_test::loadArm();
  const dss::ModelSetup p = dss_test::shelfSetup(r);
  for (const char* name : {"dss", "fcl-hull"}) {
    dss::CheckerConfig timed_config{name};
    timed_config.time_checks = true;
    auto plain = dss::makeStateChecker(p.model, {name});
    auto timed = dss::makeStateChecker(p.model, timed_config);
    BOOST_TEST(!plain->timesChecks());
    BOOST_TEST(timed->timesChecks());
    std::mt19937_64 rng(5);
    std::size_t differ = 0;
    for (int k = 0; k < 500; ++k) {
      std::vector<double> q = dss_test::randomGroupState(*p.model, rng);
      if (k % 50 == 7) q[p.model->groupActive()[0]] = std::nan("");  // invalid input, timed too
      differ += plain->check(q.data()) != timed->check(q.data());
    }
    BOOST_TEST(differ == 0u, name);
    const dss::CheckerCounters a = plain->counters(), b = timed->counters();
    BOOST_TEST(a.checks == 500u);
    BOOST_TEST(b.checks == a.checks);
    BOOST_TEST(b.invalid_input == 10u);
    BOOST_TEST(b.collisions == a.collisions);
    BOOST_TEST(a.checking_ns == 0u, name);
    // 500 checks take far more than a nanosecond each on any machine, and far less than 10 s.
    BOOST_TEST(b.checking_ns > 500u, name);
    BOOST_TEST(b.checking_ns < 10'000'000'000u, name);
    BOOST_TEST((b - b).checking_ns == 0u);
  }
}

namespace {
void compareOnMbm(const std::string& robot_dir, const std::string& robot, const std::string& mbm) {
  BOOST_REQUIRE_MESSAGE(fs::exists(robot_dir + "/" + robot + ".urdf") && fs::exists(mbm),
                        mbm << " or " << robot_dir << " not found");
  const auto r =
      dss::loadRobot(robot_dir + "/" + robot + ".urdf", robot_dir + "/" + robot + ".srdf");
  double max_band = 0.0;
  std::size_t total = 0, hull_disagree = 0, mesh_free_dss_collide = 0, dss_free_mesh_collide = 0;
  double min_gap = std::numeric_limits<double>::infinity();
  for (const char* folder : {"box", "bookshelf_small", "cage", "table_pick"}) {
    const std::string dir = mbm + "/" + folder;
    if (!fs::exists(dir + "/scene0001.yaml")) continue;
    const auto req = dss::loadPlanRequestYaml(dir + "/request0001.yaml");
    const dss::ModelSetup p = dss::setupModel(r, dss::loadScene(dir + "/scene0001.yaml"),
                                              req.group_name, req.startState());
    auto d = dss::makeStateChecker(p.model, {"dss"});
    auto fh = std::dynamic_pointer_cast<const dss::FclChecker>(
        dss::makeStateChecker(p.model, {"fcl-hull"}));
    BOOST_REQUIRE(fh);
    auto fm = dss::makeStateChecker(p.model, {"fcl-mesh"});
    const auto& m = *p.model;
    std::mt19937_64 rng(11);
    std::vector<Eigen::Isometry3d> X(r.model->links.size());
    const std::vector<unsigned char> no_skip(m.selfTables().size(), 0);
    std::size_t valid = 0;
    const std::size_t num_states = 2000;
    for (std::size_t k = 0; k < num_states; ++k) {
      const std::vector<double> q = dss_test::randomGroupState(m, rng);
      const dss::StateVerdict verdict_d = d->check(q.data()), verdict_h = fh->check(q.data()),
                              verdict_m = fm->check(q.data());
      BOOST_TEST_REQUIRE((verdict_d != dss::StateVerdict::kInvalidInput &&
                          verdict_h != dss::StateVerdict::kInvalidInput &&
                          verdict_m != dss::StateVerdict::kInvalidInput),
                         folder << " state " << k);
      const bool vd = verdict_d == dss::StateVerdict::kFree,
                 vh = verdict_h == dss::StateVerdict::kFree,
                 vm = verdict_m == dss::StateVerdict::kFree;
      ++total;
      valid += vd;
      if (!vd && vm) ++mesh_free_dss_collide;  // expected: hulls contain the meshes
      if (vd == vh && !(vd && !vm)) continue;
      // Distances / gaps of every checked pair at this state.
      m.kinematics().computeLinkPoses(q.data(), X.data());
      double dmin = std::numeric_limits<double>::infinity();
      double gmin = std::numeric_limits<double>::infinity();
      auto visit = [&](int e, const Eigen::Isometry3d& X_A, const fcl::CollisionGeometryd* gb,
                       const dss::AnyShape& sb, const Eigen::Isometry3d& X_B) {
        fcl::DistanceRequestd dreq;
        fcl::DistanceResultd dres;
        dmin = std::min(dmin,
                        std::abs(fcl::distance(fh->elementGeometry(e), X_A, gb, X_B, dreq, dres)));
        gmin = std::min(gmin, dssGap(m.elements()[e].source->shape, X_A, sb, X_B));
        return false;
      };
      // Every pair the sweep's filters pass, from each link's own pose, with no table flag.
      dss::sweep<dss::SweepPoses::kOwnLinks>(
          m, X.data(), no_skip.data(), dss::SweepOptions{},
          [&](int e, const Eigen::Isometry3d& X_WS, int o) {
            const auto& ob = m.scene().obstacles[o];
            return visit(e, X_WS, fh->obstacleGeometry(o), ob.shape, ob.X_WO);
          },
          [&](int a, const Eigen::Isometry3d& X_A, int b, const Eigen::Isometry3d& X_B) {
            return visit(a, X_A, fh->elementGeometry(b), m.elements()[b].source->shape, X_B);
          });
      if (vd != vh) {
        ++hull_disagree;
        max_band = std::max(max_band, dmin);
        BOOST_TEST_MESSAGE(folder << ": dss " << vd << " fcl-hull " << vh << ", min fcl distance "
                                  << dmin);
      }
      if (vd && !vm) {
        ++dss_free_mesh_collide;
        min_gap = std::min(min_gap, gmin);
        BOOST_TEST_MESSAGE(folder << ": dss free, fcl-mesh colliding; DSS gap " << gmin);
        BOOST_TEST(gmin > 0.0);  // certified by DSS's separating plane: really apart
      }
    }
    BOOST_TEST_MESSAGE(folder << ": " << valid << " of " << num_states << " valid under dss; "
                              << m.summary());
  }
  std::cout << "checker tests: " << total << " random " << robot
            << " states; dss vs fcl-hull disagree on " << hull_disagree
            << " (max fcl distance among them " << max_band << " m); dss free where "
            << "fcl-mesh collides: " << dss_free_mesh_collide << " (smallest DSS gap " << min_gap
            << " m); dss colliding where fcl-mesh free (hull vs mesh): " << mesh_free_dss_collide
            << "\n";
  // Near-contact band: disagreements only where the shapes are within 1 mm.
  BOOST_TEST(max_band < 1e-3);
  BOOST_TEST(hull_disagree * 100 <= total);
}
}  // namespace

// A chain of 70 links (more than one 64-bit word of slots) along x, a box each, nearly
// straight: only the last links reach the obstacle beyond x = 3.3 m, where they bend towards it.
// The sweep visits the slots of every word; DSS answers as fcl-hull (FCL's own broad phase).
BOOST_AUTO_TEST_CASE(a_chain_of_70_links_against_fcl) {
  constexpr int kLinks = 70;
  std::string urdf = "<?xml version=\"1.0\"?>\n<robot name=\"chain\">\n";
  auto link = [](int k) {
    return "  <link name=\"l" + std::to_string(k) +
           "\"><collision><origin xyz=\"0.025 0 0\"/><geometry><box size=\"0.04 0.02 "
           "0.02\"/></geometry></collision></link>\n";
  };
  urdf += link(0);
  for (int k = 1; k <= kLinks; ++k) {
    urdf += link(k);
    urdf += "  <joint name=\"j" + std::to_string(k) + "\" type=\"revolute\"><parent link=\"l" +
            std::to_string(k - 1) + "\"/><child link=\"l" + std::to_string(k) +
            "\"/><origin xyz=\"0.05 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-0.04\" "
            "upper=\"0.04\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  urdf += "</robot>\n";
  const std::string path = dss_test::writeScratch("state_checkers", "chain70.urdf", urdf);
  const dss::LoadedRobot robot = dss::loadRobot(path, "");
  dss::Scene scene;
  dss::Obstacle wall;
  wall.name = wall.object_id = "wall";
  wall.shape = dss::Box{Eigen::Vector3d(0.15, 0.5, 0.1)};
  wall.X_FO.translation() = Eigen::Vector3d(3.45, 0.52, 0.0);
  wall.X_WO = wall.X_FO;
  scene.obstacles.push_back(wall);
  const dss::ModelSetup setup = dss::setupModel(robot, scene, "", {});
  BOOST_REQUIRE(setup.model->slots().size() == std::size_t(kLinks + 1));
  const auto dss_checker = dss::makeStateChecker(setup.model, dss::CheckerConfig{});
  dss::CheckerConfig fcl;
  fcl.checker = "fcl-hull";
  const auto fcl_checker = dss::makeStateChecker(setup.model, fcl);
  std::mt19937_64 rng(70);
  int colliding = 0;
  constexpr int kStates = 2000;
  for (int i = 0; i < kStates; ++i) {
    const std::vector<double> q = dss_test::randomGroupState(*setup.model, rng);
    const bool expected = fcl_checker->collides(q.data());
    BOOST_TEST(dss_checker->collides(q.data()) == expected, "state " << i);
    colliding += expected;
  }
  BOOST_TEST_MESSAGE("chain of 70 links: " << colliding << " of " << kStates << " colliding");
  BOOST_TEST(colliding > kStates / 10);
  BOOST_TEST(colliding < kStates * 9 / 10);
}

BOOST_AUTO_TEST_CASE(dss_against_fcl_on_mbm_panda_random_states, DSS_NEEDS_SHARED) {
  compareOnMbm(kPanda, "panda", kMbm);
}

BOOST_AUTO_TEST_CASE(dss_against_fcl_on_mbm_ur5_random_states, DSS_NEEDS_SHARED) {
  compareOnMbm(std::string(DSS_SHARED_DIR) + "/robots/ur5_robotiq85", "ur5",
               std::string(DSS_SHARED_DIR) + "/scenes/mbm_ur5");
}

BOOST_AUTO_TEST_SUITE_END()
