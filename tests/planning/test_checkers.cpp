// Validity checkers on real models: a seeded plan on our shelf scene checked state by state
// under DSS and fcl-hull; DSS against fcl-hull and fcl-mesh on random Panda states of the
// MotionBenchMaker scenes (near-contact band measured with fcl::distance, DSS "free" against
// fcl-mesh "colliding" shown to be a real gap from DSS's separating direction); NaN states;
// two threads giving the same answers as one.
#include <atomic>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <random>
#include <thread>

#include <boost/test/unit_test.hpp>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "dss/core/posed.h"
#include "dss/planning/fcl_validity_checker.h"
#include "dss/planning/planning_problem.h"
#include "dss/scene/scene_loader.h"

namespace fs = std::filesystem;
namespace ob = ompl::base;

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
const std::string kPanda = std::string(DSS_SHARED_DIR) + "/robots/panda";
const std::string kMbm = std::string(DSS_SHARED_DIR) + "/scenes/mbm_panda";


dss::Problem shelfProblem(const dss::LoadedRobot& r) {
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  return dss::makeProblem(r, dss::loadScene(kArm + "/scenes/shelf.yaml"), req.group_name, req.startState());
}

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
          const dss::Posed<dss::detail::Ref<S>> p(dss::detail::Ref<S>{x}, X.linear(), X.translation());
          return p.support(d, dss::Vec3d::Zero()).dot(d);
        },
        s);
  };
  return -(h(a, X_A, n) + h(b, X_B, -n)) / n.norm();
}

// OMPL's seed can be set once per process, before any sampling: a global fixture does it.
struct SeedOmpl {
  SeedOmpl() {
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    ompl::RNG::setSeed(7);
  }
};

// Uniform states within the group bounds from our own seeded generator (independent of OMPL's
// process-wide seed and of test order).
std::vector<ob::State*> randomStates(const dss::Problem& p, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<ob::State*> out;
  std::vector<double> g(p.map->dimension());
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t i = 0; i < g.size(); ++i)
      g[i] = std::uniform_real_distribution<double>(p.map->lower(i), p.map->upper(i))(rng);
    out.push_back(p.si->allocState());
    p.map->fromGroupValues(g.data(), out.back());
  }
  return out;
}

}  // namespace

BOOST_TEST_GLOBAL_FIXTURE(SeedOmpl);

BOOST_AUTO_TEST_CASE(shelf_plan_is_valid_under_dss_and_fcl_hull) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  dss::Problem p = shelfProblem(r);
  BOOST_TEST_MESSAGE(p.model->summary());
  auto dss_checker = dss::makeChecker(p, {"dss"});
  auto fcl_checker = dss::makeChecker(p, {"fcl-hull"});
  ompl::geometric::SimpleSetup ss(p.si);
  ss.setStateValidityChecker(dss_checker);
  ss.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(p.si));
  ob::ScopedState<> start(p.si->getStateSpace()), goal(p.si->getStateSpace());
  const auto g0 = p.map->groupValues(req.startState());
  std::map<std::string, double> goal_map;
  for (const auto& jc : req.goals.at(0).joint_constraints) goal_map[jc.joint_name] = jc.position;
  const auto g1 = p.map->groupValues(goal_map);
  p.map->fromGroupValues(g0.data(), start.get());
  p.map->fromGroupValues(g1.data(), goal.get());
  BOOST_TEST(dss_checker->isValid(start.get()));
  BOOST_TEST(dss_checker->isValid(goal.get()));
  ss.setStartAndGoalStates(start, goal);
  BOOST_REQUIRE(ss.solve(10.0) == ob::PlannerStatus::EXACT_SOLUTION);
  auto path = ss.getSolutionPath();
  path.interpolate();  // at the validity-checking resolution the motion validator used
  int invalid_dss = 0, invalid_fcl = 0;
  for (auto* s : path.getStates()) {
    invalid_dss += !dss_checker->isValid(s);
    invalid_fcl += !fcl_checker->isValid(s);
  }
  BOOST_TEST(path.getStateCount() >= 50u);
  BOOST_TEST(invalid_dss == 0);
  BOOST_TEST(invalid_fcl == 0);
  // The straight line start -> goal passes through the shelf: the problem is not trivial.
  BOOST_TEST(!p.si->checkMotion(start.get(), goal.get()));
}

BOOST_AUTO_TEST_CASE(nan_inf_and_out_of_bounds_states_are_invalid) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  dss::Problem p = shelfProblem(r);
  for (const char* name : {"dss", "fcl-hull"}) {
    auto c = dss::makeChecker(p, {name});
    ob::ScopedState<> s(p.si->getStateSpace());
    auto g = p.map->groupValues({});
    for (std::size_t i = 0; i < g.size(); ++i) g[i] = 0.5 * (p.map->lower(i) + p.map->upper(i));
    p.map->fromGroupValues(g.data(), s.get());
    const bool base = c->isValid(s.get());
    (void)base;
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity(), 1e6}) {
      auto h = g;
      h[3] = bad;
      p.map->fromGroupValues(h.data(), s.get());
      BOOST_TEST(!c->isValid(s.get()), name << " value " << bad);
    }
    BOOST_TEST(c->counters().invalid_input == 4u);
  }
}

BOOST_AUTO_TEST_CASE(two_threads_give_the_same_answers) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  dss::Problem p = shelfProblem(r);
  auto c = dss::makeChecker(p, {"dss"});
  std::vector<ob::State*> states = randomStates(p, 4000, 3);
  std::vector<char> one(states.size()), two(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) one[i] = c->isValid(states[i]);
  auto work = [&](std::size_t begin) {
    for (std::size_t i = begin; i < states.size(); i += 2) two[i] = c->isValid(states[i]);
  };
  std::thread t0(work, 0), t1(work, 1);
  t0.join();
  t1.join();
  BOOST_TEST(one == two);
  std::size_t valid = std::count(one.begin(), one.end(), 1);
  BOOST_TEST(valid > 0u);
  BOOST_TEST(valid < states.size());
  BOOST_TEST(c->counters().checks == 2 * states.size());
  for (auto* s : states) p.si->freeState(s);
}

namespace {
void compareOnMbm(const std::string& robot_dir, const std::string& robot, const std::string& mbm) {
  if (!fs::exists(robot_dir + "/" + robot + ".urdf") || !fs::exists(mbm)) {
    BOOST_TEST_MESSAGE(mbm << " or " << robot_dir << " absent: skipped");
    return;
  }
  const auto r = dss::loadRobot(robot_dir + "/" + robot + ".urdf", robot_dir + "/" + robot + ".srdf");
  double max_band = 0.0;
  std::size_t total = 0, hull_disagree = 0, mesh_free_dss_collide = 0, dss_free_mesh_collide = 0;
  double min_gap = std::numeric_limits<double>::infinity();
  for (const char* folder : {"box", "bookshelf_small", "cage", "table_pick"}) {
    const std::string dir = mbm + "/" + folder;
    if (!fs::exists(dir + "/scene0001.yaml")) continue;
    const auto req = dss::loadPlanRequestYaml(dir + "/request0001.yaml");
    dss::Problem p = dss::makeProblem(r, dss::loadScene(dir + "/scene0001.yaml"), req.group_name, req.startState());
    auto d = dss::makeChecker(p, {"dss"});
    auto fh = std::dynamic_pointer_cast<dss::FclValidityChecker>(dss::makeChecker(p, {"fcl-hull"}));
    auto fm = dss::makeChecker(p, {"fcl-mesh"});
    const std::vector<ob::State*> states = randomStates(p, 2000, 11);
    std::vector<double> q(r.model->numActiveJoints());
    std::vector<Eigen::Isometry3d> X(r.model->links.size());
    const auto& m = *p.model;
    std::size_t valid = 0;
    for (ob::State* s : states) {
      const bool vd = d->isValid(s), vh = fh->isValid(s), vm = fm->isValid(s);
      ++total;
      valid += vd;
      if (!vd && vm) ++mesh_free_dss_collide;  // expected: hulls contain the meshes
      if (vd == vh && !(vd && !vm)) continue;
      // Distances / gaps of every checked pair at this state.
      BOOST_REQUIRE(p.map->toJoints(s, q.data()));
      m.kinematics().computeLinkPoses(q.data(), X.data());
      double dmin = std::numeric_limits<double>::infinity();
      double gmin = std::numeric_limits<double>::infinity();
      auto visit = [&](int e, const Eigen::Isometry3d& X_A, const fcl::CollisionGeometryd* gb,
                       const dss::AnyShape& sb, const Eigen::Isometry3d& X_B) {
        fcl::DistanceRequestd dreq;
        fcl::DistanceResultd dres;
        dmin = std::min(dmin, std::abs(fcl::distance(fh->elementGeometry(e), X_A, gb, X_B, dreq, dres)));
        gmin = std::min(gmin, dssGap(m.elements()[e].source->shape, X_A, sb, X_B));
        return false;
      };
      m.anyCollision(
          X.data(), 0.0, 0.0,
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
        BOOST_TEST_MESSAGE(folder << ": dss " << vd << " fcl-hull " << vh << ", min fcl distance " << dmin);
      }
      if (vd && !vm) {
        ++dss_free_mesh_collide;
        min_gap = std::min(min_gap, gmin);
        BOOST_TEST_MESSAGE(folder << ": dss free, fcl-mesh colliding; DSS gap " << gmin);
        BOOST_TEST(gmin > 0.0);  // certified by DSS's separating plane: really apart
      }
    }
    BOOST_TEST_MESSAGE(folder << ": " << valid << " of " << states.size() << " valid under dss; " << m.summary());
    for (auto* s : states) p.si->freeState(s);
  }
  std::cout << "planning tests: " << total << " random " << robot << " states; dss vs fcl-hull disagree on "
            << hull_disagree << " (max fcl distance among them " << max_band << " m); dss free where "
            << "fcl-mesh collides: " << dss_free_mesh_collide << " (smallest DSS gap " << min_gap
            << " m); dss colliding where fcl-mesh free (hull vs mesh): " << mesh_free_dss_collide << "\n";
  // Near-contact band: disagreements only where the shapes are within 1 mm.
  BOOST_TEST(max_band < 1e-3);
  BOOST_TEST(hull_disagree * 100 <= total);
}
}  // namespace

BOOST_AUTO_TEST_CASE(dss_against_fcl_on_mbm_panda_random_states) {
  compareOnMbm(kPanda, "panda", kMbm);
}

BOOST_AUTO_TEST_CASE(dss_against_fcl_on_mbm_ur5_random_states) {
  compareOnMbm(std::string(DSS_SHARED_DIR) + "/robots/ur5_robotiq85", "ur5",
               std::string(DSS_SHARED_DIR) + "/scenes/mbm_ur5");
}
