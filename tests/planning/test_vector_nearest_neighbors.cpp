// The vector nearest-neighbour search against OMPL: PointBlocks against a brute-force search on
// OMPL's RealVectorStateSpace::distance (nearest, k nearest, within a radius; ties, the radius
// at a point's exact distance and one ulp below, NaN and infinite values, removal) on every
// instruction set; VectorNearestNeighbors against OMPL's GNAT on random additions, removals
// and queries, on both sides of its linear limit; and seeded plans with it against plans with
// the planners' default structure: the same checks, the same paths.
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <random>

#include "dss/planning/discrete_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/planning/validity_checker.h"
#include "dss/planning/vector_nearest_neighbors.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/simd_paths.h"
#include "support/thrown_message.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

struct Item {
  ob::State* state;
};

// Points of one dimension as OMPL states, with the reference searches.
struct Points {
  explicit Points(unsigned dim) : space(std::make_shared<ob::RealVectorStateSpace>(dim)) {}
  ~Points() {
    for (Item& it : items) space->freeState(it.state);
  }
  Points(const Points&) = delete;
  Points& operator=(const Points&) = delete;

  Item* add(const std::vector<double>& v) {
    items.push_back({space->allocState()});
    double* values = items.back().state->as<ob::RealVectorStateSpace::StateType>()->values;
    std::copy(v.begin(), v.end(), values);
    return &items.back();
  }
  const double* values(std::size_t i) const {
    return items[i].state->as<ob::RealVectorStateSpace::StateType>()->values;
  }
  double distance(const Item* a, const Item* b) const {
    return space->distance(a->state, b->state);
  }

  std::shared_ptr<ob::RealVectorStateSpace> space;
  std::deque<Item> items;  // stable addresses
};

std::vector<double> randomPoint(unsigned dim, std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  std::vector<double> v(dim);
  for (double& x : v) x = u(rng);
  return v;
}

// The squared distance OMPL's distance is the square root of (the same sums).
double squaredDistance(const double* a, const double* b, unsigned dim) {
  double s = 0.0;
  for (unsigned i = 0; i < dim; ++i) {
    const double d = a[i] - b[i];
    s += d * d;
  }
  return s;
}

using dss_test::availablePaths;

}  // namespace

BOOST_AUTO_TEST_SUITE(vector_nearest_neighbors)

BOOST_AUTO_TEST_CASE(point_blocks_find_what_a_brute_force_search_on_ompl_distances_finds) {
  std::mt19937_64 rng(7);
  int queries = 0;
  for (int round = 0; round < 300; ++round) {
    const unsigned dim = 1 + unsigned(round % 9);
    const std::size_t n = std::size_t(rng() % 90);
    Points pts(dim);
    // Clusters of near points and exact duplicates among spread ones: ties and near ties.
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0 && rng() % 6 == 0) {  // a copy of an earlier point
        const std::size_t j = std::size_t(rng() % i);
        pts.add(std::vector<double>(pts.values(j), pts.values(j) + dim));
      } else {
        pts.add(randomPoint(dim, rng, round % 3 == 0 ? 1e-6 : 3.0));
      }
    }
    const auto paths = availablePaths();
    std::vector<dss::PointBlocks> blocks;
    for (auto p : paths) {
      blocks.emplace_back(dim, p);
      for (std::size_t i = 0; i < n; ++i) blocks.back().push(pts.values(i));
    }
    for (int qi = 0; qi < 20; ++qi, ++queries) {
      std::vector<double> q = randomPoint(dim, rng, round % 3 == 0 ? 1e-6 : 3.0);
      if (qi == 0 && n > 0) q.assign(pts.values(n / 2), pts.values(n / 2) + dim);  // on a point
      Item* query = pts.add(q);  // (not in the blocks)
      // Reference: OMPL's distances, the first of the nearest; all, sorted with their index.
      std::vector<std::pair<double, std::size_t>> all;
      for (std::size_t i = 0; i < n; ++i)
        all.emplace_back(squaredDistance(pts.values(i), q.data(), dim), i);
      for (std::size_t i = 0; i < n; ++i)
        BOOST_REQUIRE_EQUAL(std::sqrt(all[i].first), pts.distance(&pts.items[i], query));
      std::vector<std::pair<double, std::size_t>> sorted = all;
      std::sort(sorted.begin(), sorted.end());
      const std::size_t k = std::size_t(rng() % 12);
      // A radius at a point's exact distance (included), and one just below it (excluded).
      const double r_at = n > 0 ? pts.distance(&pts.items[rng() % n], query) : 1.0;
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        const dss::PointBlocks& pb = blocks[b];
        const std::size_t got = pb.nearest(q.data());
        if (n == 0) {
          BOOST_CHECK(got == dss::PointBlocks::kNone);
          continue;
        }
        BOOST_CHECK_MESSAGE(got == sorted.front().second,
                            "path " << dss::simdPathName(paths[b]) << " dim " << dim << " n " << n
                                    << ": nearest " << got << ", expected "
                                    << sorted.front().second);
        std::vector<dss::PointBlocks::Found> found;
        pb.nearestK(q.data(), k, found);
        BOOST_REQUIRE_EQUAL(found.size(), std::min(k, n));
        for (std::size_t i = 0; i < found.size(); ++i) BOOST_CHECK(found[i] == sorted[i]);
        for (const double r : {r_at, std::nextafter(r_at, 0.0)}) {
          pb.withinRadius(q.data(), r, found);
          std::vector<dss::PointBlocks::Found> expected;
          for (const auto& e : sorted)
            if (pts.distance(&pts.items[e.second], query) <= r) expected.push_back(e);
          BOOST_CHECK_MESSAGE(found == expected,
                              "path " << dss::simdPathName(paths[b]) << ": within radius " << r);
        }
      }
      pts.items.pop_back();
      pts.space->freeState(query->state);
    }
  }
  BOOST_TEST_MESSAGE(queries << " queries");
}

BOOST_AUTO_TEST_CASE(point_blocks_non_finite_values_and_removal) {
  for (auto path : availablePaths()) {
    const unsigned dim = 3;
    dss::PointBlocks pb(dim, path);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const double a[3] = {nan, 0, 0}, b[3] = {5, 5, 5}, c[3] = {inf, 0, 0}, d[3] = {1, 1, 1};
    for (const double* p : {a, b, c, d}) pb.push(p);
    const double q[3] = {0, 0, 0};
    // A NaN point is never nearest, an infinite one only when nothing is finite.
    BOOST_CHECK_EQUAL(pb.nearest(q), 3u);
    std::vector<dss::PointBlocks::Found> found;
    pb.nearestK(q, 4, found);
    BOOST_REQUIRE_EQUAL(found.size(), 4u);
    BOOST_CHECK_EQUAL(found[0].second, 3u);
    BOOST_CHECK_EQUAL(found[1].second, 1u);
    BOOST_CHECK(std::isinf(found[2].first) && std::isinf(found[3].first));
    pb.withinRadius(q, 1e300, found);
    BOOST_CHECK_EQUAL(found.size(), 2u);
    // A NaN query finds no point below infinity: point 0, as documented.
    const double qn[3] = {0, nan, 0};
    BOOST_CHECK_EQUAL(pb.nearest(qn), 0u);
    // Removal moves the last point into the place.
    pb.swapRemove(1);  // b out, d at 1
    BOOST_CHECK_EQUAL(pb.size(), 3u);
    double v[3];
    pb.get(1, v);
    BOOST_CHECK(v[0] == 1 && v[1] == 1 && v[2] == 1);
    BOOST_CHECK_EQUAL(pb.nearest(q), 1u);
    pb.swapRemove(2);
    pb.swapRemove(1);
    pb.swapRemove(0);
    BOOST_CHECK_EQUAL(pb.size(), 0u);
    BOOST_CHECK(pb.nearest(q) == dss::PointBlocks::kNone);
    pb.push(b);
    BOOST_CHECK_EQUAL(pb.nearest(q), 0u);
  }
}

BOOST_AUTO_TEST_CASE(answers_as_gnat_across_additions_removals_and_the_linear_limit) {
  std::mt19937_64 rng(11);
  for (const std::size_t limit : {std::size_t(0), std::size_t(40), std::size_t(1) << 30}) {
    for (unsigned dim : {2u, 7u}) {
      Points pts(dim);
      dss::VectorNearestNeighbors<Item*> vec(dim);
      vec.setLinearLimit(limit);
      ompl::NearestNeighborsGNATNoThreadSafety<Item*> gnat;
      gnat.setDistanceFunction([&](Item* const& a, Item* const& b) { return pts.distance(a, b); });
      std::vector<Item*> live;
      for (int step = 0; step < 600; ++step) {
        Item* it = pts.add(randomPoint(dim, rng, 2.0));
        if (step % 7 == 3 && !live.empty()) {  // remove one
          const std::size_t i = std::size_t(rng() % live.size());
          BOOST_CHECK(vec.remove(live[i]));
          BOOST_CHECK(gnat.remove(live[i]));
          BOOST_CHECK(!vec.remove(live[i]));
          live.erase(live.begin() + std::ptrdiff_t(i));
        }
        if (step % 3 != 0) {  // add it, else keep it as a query only
          vec.add(it);
          gnat.add(it);
          live.push_back(it);
        }
        BOOST_REQUIRE_EQUAL(vec.size(), gnat.size());
        if (live.empty()) continue;
        Item* q = pts.add(randomPoint(dim, rng, 2.0));
        BOOST_CHECK_EQUAL(vec.nearest(q), gnat.nearest(q));
        BOOST_CHECK_EQUAL(vec.distance(vec.nearest(q), q), pts.distance(gnat.nearest(q), q));
        std::vector<Item*> a, b;
        vec.nearestK(q, 5, a);
        gnat.nearestK(q, 5, b);
        BOOST_CHECK(a == b);
        const double r = pts.distance(b.back(), q);
        vec.nearestR(q, r, a);
        gnat.nearestR(q, r, b);
        BOOST_CHECK(a == b);
      }
      BOOST_CHECK_EQUAL(vec.usesTree(), limit <= live.size());
      std::vector<Item*> listed;
      vec.list(listed);
      std::sort(listed.begin(), listed.end());
      std::sort(live.begin(), live.end());
      BOOST_CHECK(listed == live);
      vec.clear();
      BOOST_CHECK_EQUAL(vec.size(), 0u);
      BOOST_CHECK(!vec.usesTree());
      Item* q = pts.add(randomPoint(dim, rng, 2.0));
      BOOST_CHECK_THROW(vec.nearest(q), ompl::Exception);
    }
  }
}

BOOST_AUTO_TEST_CASE(needs_a_dimension) {
  BOOST_CHECK_THROW(dss::VectorNearestNeighbors<Item*>(), std::logic_error);
  BOOST_CHECK_THROW(dss::VectorNearestNeighbors<Item*>(0), std::logic_error);
}

// Seeded plans of our arm in its shelf scene (RRTConnect, BiTRRT): the vector search gives the
// same validity checks and the same path as the planner's default structure.
BOOST_AUTO_TEST_CASE(seeded_plans_are_the_plans_with_the_default_structure) {
  const std::string arm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const auto robot = dss::loadRobot(arm + "/dss_arm7.urdf", arm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(arm + "/scenes/shelf_request.yaml");
  const auto scene = dss::loadScene(arm + "/scenes/shelf.yaml");
  struct Outcome {
    bool solved = false;
    std::uint64_t checks = 0;
    std::vector<std::vector<double>> path;
  };
  auto plan = [&](const std::string& planner, bool vector, unsigned seed) {
    ompl::RNG::setSeed(seed);
    dss::Problem p = dss::makeProblem(robot, scene, req.group_name, req.startState());
    auto checker = dss::makeValidityChecker(p, {"dss"});
    og::SimpleSetup ss(p.si);
    ss.setStateValidityChecker(checker);
    p.si->setMotionValidator(dss::makeDiscreteMotionValidator(p, *checker));
    if (planner == "RRTConnect")
      ss.setPlanner(std::make_shared<og::RRTConnect>(p.si));
    else
      ss.setPlanner(std::make_shared<og::BiTRRT>(p.si));
    BOOST_REQUIRE(!vector || dss::useVectorNearestNeighbors(ss.getPlanner()));
    ob::ScopedState<> start(p.si->getStateSpace()), goal(p.si->getStateSpace());
    const auto g0 = p.map->groupValues(req.startState());
    p.map->fromGroupValues(g0.data(), start.get());
    std::map<std::string, double> goal_by_name;
    for (const dss::JointConstraint& c : req.goals.front().joint_constraints)
      goal_by_name[c.joint_name] = c.position;
    const auto g1 = p.map->groupValues(goal_by_name);
    p.map->fromGroupValues(g1.data(), goal.get());
    ss.setStartAndGoalStates(start, goal);
    Outcome o;
    o.solved =
        ss.solve(ob::timedPlannerTerminationCondition(30.0)) == ob::PlannerStatus::EXACT_SOLUTION;
    o.checks = checker->counters().checks;
    if (o.solved)
      for (auto* s : ss.getSolutionPath().getStates()) {
        std::vector<double> g(p.map->dimension());
        p.map->toGroupValues(s, g.data());
        o.path.push_back(g);
      }
    return o;
  };
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  for (const std::string planner : {"RRTConnect", "BiTRRT"})
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const Outcome a = plan(planner, false, seed), b = plan(planner, true, seed);
      BOOST_REQUIRE_MESSAGE(a.solved && b.solved, planner << " seed " << seed);
      BOOST_CHECK_MESSAGE(a.checks == b.checks, planner << " seed " << seed << ": " << a.checks
                                                        << " checks against " << b.checks);
      BOOST_CHECK_MESSAGE(a.path == b.path, planner << " seed " << seed << ": paths differ");
      BOOST_CHECK_GT(a.checks, 10u);
    }
}

BOOST_AUTO_TEST_CASE(other_planners_and_spaces_keep_their_structure) {
  const std::string arm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
  const auto robot = dss::loadRobot(arm + "/dss_arm7.urdf", arm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(arm + "/scenes/shelf_request.yaml");
  dss::Problem p = dss::makeProblem(robot, dss::loadScene(arm + "/scenes/shelf.yaml"),
                                    req.group_name, req.startState());
  p.si->setStateValidityChecker(dss::makeValidityChecker(p, {"dss"}));
  p.si->setup();
  BOOST_CHECK(!dss::useVectorNearestNeighbors(std::make_shared<og::PRM>(p.si)));
  BOOST_CHECK(!dss::useVectorNearestNeighbors(nullptr));
  // A space with an SO(2) part: not a joint-value vector.
  auto compound = std::make_shared<ob::CompoundStateSpace>();
  compound->addSubspace(std::make_shared<ob::RealVectorStateSpace>(2), 1.0);
  compound->addSubspace(std::make_shared<ob::SO2StateSpace>(), 1.0);
  auto si = std::make_shared<ob::SpaceInformation>(compound);
  BOOST_CHECK(!dss::useVectorNearestNeighbors(std::make_shared<og::RRTConnect>(si)));
  BOOST_CHECK(dss::useVectorNearestNeighbors(std::make_shared<og::RRTConnect>(p.si)));
}

BOOST_AUTO_TEST_SUITE_END()
