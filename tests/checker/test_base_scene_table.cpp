// The base-scene table of a planar base (dss/checker/base_scene_table.h): every colliding cell
// holds a state whose tabled links really collide (exact DSS), every link certified free is
// apart from every obstacle (exact DSS), at random states and on the cells' borders (x and y
// on a border, on the bounds, theta at +-pi and whole turns away), and the checker answers
// exactly as without the table, at zero and at a larger scene padding.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <memory>
#include <random>

#include "dss/checker/base_scene_table.h"
#include "dss/checker/checker_setup.h"
#include "dss/checker/continuous_motion.h"
#include "dss/checker/dss_checker.h"
#include "dss/core/any_shape_query.h"
#include "dss/robot/multi_dof.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"

namespace {

struct Mobile {
  std::shared_ptr<const dss::CollisionModel> with, without;
};

// The robot `name` in `scene` with its request's workspace; the second model has no table.
Mobile load(const std::string& name, const std::string& scene) {
  const dss_test::MobileSetup m = dss_test::mobileSetup(name, scene);
  dss::CollisionModelOptions off;
  off.base_table_cells = 0;
  const dss::LoadedRobot& r = m.robot;
  auto without = std::make_shared<const dss::CollisionModel>(
      r.model, r.srdf ? &*r.srdf : nullptr, dss::loadScene(m.scene_file), m.setup.group_active,
      m.setup.held, off);
  return {m.setup.model, without};
}

// The active indices of the planar joint's x, y and theta.
std::array<int, 3> planarVars(const dss::RobotModel& robot) {
  for (const auto& md : robot.multi_dof_joints)
    if (md.type == dss::MultiDofType::kPlanar)
      return {robot.joints[md.joints[0]].active_index, robot.joints[md.joints[1]].active_index,
              robot.joints[md.joints[2]].active_index};
  BOOST_FAIL("no planar joint");
  return {-1, -1, -1};
}

// Random states of the group, half of them moved onto a cell border in x, y or theta (or onto
// the bounds), and theta sometimes whole turns away from [-pi, pi).
std::vector<double> sample(const dss::CollisionModel& m, std::mt19937_64& rng) {
  std::vector<double> q = dss_test::randomGroupState(m, rng);
  const dss::BaseSceneTable& t = m.baseTable();
  const auto v = planarVars(m.robot());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double tiny = std::ldexp(1.0, -40);
  for (int k = 0; k < 3; ++k) {
    if (u(rng) > 0.5) continue;
    const dss::RobotJoint& j = m.robot().joints[m.robot().active_joints[v[k]]];
    const double lo = k < 2 ? j.limits.lower : -M_PI, hi = k < 2 ? j.limits.upper : M_PI;
    const int n = t.cells(k);
    const int i = std::uniform_int_distribution<int>(0, n)(rng);
    double x = lo + (hi - lo) * i / n;
    const double r = u(rng);
    if (r < 1.0 / 3) x = std::nextafter(x, -INFINITY);
    if (r > 2.0 / 3) x = std::nextafter(x, INFINITY);
    if (k < 2) x = std::min(std::max(x, lo), hi);  // (within the bounds: tiny steps outside)
    q[v[k]] = x + (k < 2 ? 0.0 : tiny * (u(rng) - 0.5));
  }
  const double turns[] = {0.0, 0.0, 2.0, -2.0, 6.0, -40.0};
  q[v[2]] += M_PI * turns[std::uniform_int_distribution<int>(0, 5)(rng)];
  return q;
}

// Checks `n` states of `m` against exact DSS: a colliding cell holds a tabled link that
// touches an obstacle, a link certified free touches none. Returns the states in colliding
// cells and the links certified free.
std::pair<std::size_t, std::size_t> checkCells(const dss::CollisionModel& m, int n,
                                               std::uint64_t seed) {
  const dss::BaseSceneTable& t = m.baseTable();
  BOOST_TEST_REQUIRE(!t.empty());
  const auto& obstacles = m.scene().obstacles;
  std::vector<Eigen::Isometry3d> X(m.robot().links.size(), Eigen::Isometry3d::Identity());
  std::mt19937_64 rng(seed);
  std::size_t colliding = 0, free_links = 0;
  for (int k = 0; k < n; ++k) {
    const std::vector<double> q = sample(m, rng);
    BOOST_TEST_REQUIRE(m.withinBounds(q.data()));
    const std::uint8_t cell = t.read(q.data());
    if (cell == 0) continue;
    m.kinematics().computeLinkPoses(q.data(), X.data());
    // Exact DSS between an element of a tabled link and an obstacle.
    auto touches = [&](int e, int o) {
      const auto& el = m.elements()[e];
      return dss::intersect(el.source->shape, X[el.link] * el.source->X_LS, obstacles[o].shape,
                            obstacles[o].X_WO)
          .intersect;
    };
    if (cell == dss::BaseSceneTable::kColliding) {
      bool any = false;
      for (int s : t.slots()) {
        const auto& slot = m.slots()[s];
        for (int e = slot.first_element; e < slot.first_element + slot.num_elements && !any; ++e)
          for (int o : slot.obstacles) any = any || touches(e, o);
      }
      BOOST_TEST_REQUIRE(any, "state " << k << ": a colliding cell with its links apart");
      ++colliding;
      continue;
    }
    for (std::size_t i = 0; i < t.slots().size(); ++i) {
      if (!((cell >> i) & 1u)) continue;
      const auto& slot = m.slots()[t.slots()[i]];
      for (int e = slot.first_element; e < slot.first_element + slot.num_elements; ++e)
        for (std::size_t o = 0; o < obstacles.size(); ++o)
          BOOST_TEST_REQUIRE(!touches(e, int(o)),
                             "state " << k << ": link " << i << " certified free touches " << o);
      ++free_links;
    }
  }
  BOOST_TEST_MESSAGE(colliding << " states in colliding cells, " << free_links
                               << " links certified free");
  return {colliding, free_links};
}

// A body on a planar joint whose plane is tilted and moved (the joint's origin turned), with a
// deck fixed on it and an arm on a revolute joint below (not tabled), among boxes turned every
// way, a cylinder and a sphere.
std::shared_ptr<const dss::CollisionModel> tiltedPlane(std::uint64_t seed) {
  const std::string urdf = R"(<robot name="tilted"><link name="world"/>
<link name="body"><collision><geometry><box size="0.5 0.3 0.12"/></geometry></collision>
  <collision><origin xyz="0.25 0 0" rpy="1.5707963 0 0"/><geometry><cylinder radius="0.06" length="0.3"/></geometry></collision></link>
<link name="deck"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.3 0.2 0.08"/></geometry></collision></link>
<link name="arm"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.05 0.05"/></geometry></collision></link>
<joint name="base" type="planar"><parent link="world"/><child link="body"/>
  <origin xyz="0.3 -0.2 0.1" rpy="1.1 -0.6 0.7"/></joint>
<joint name="deck_mount" type="fixed"><parent link="body"/><child link="deck"/><origin xyz="-0.1 0 0.06"/></joint>
<joint name="elbow" type="revolute"><parent link="body"/><child link="arm"/>
  <origin xyz="0.25 0 0.1"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
</robot>)";
  auto robot = std::make_shared<dss::RobotModel>(dss::loadUrdfString(urdf, "tilted.urdf", "."));
  dss::setMultiDofTranslationBounds(*robot, Eigen::Vector3d(-2, -1.5, 0),
                                    Eigen::Vector3d(2, 1.5, 0));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  dss::Scene scene;
  for (int k = 0; k < 24; ++k) {
    dss::Obstacle o;
    o.name = o.object_id = "o" + std::to_string(k);
    if (k % 8 == 6)
      o.shape = dss::Cylinder{0.1 + 0.1 * std::abs(u(rng)), 0.2 + 0.3 * std::abs(u(rng))};
    else if (k % 8 == 7)
      o.shape = dss::Sphere{0.1 + 0.15 * std::abs(u(rng))};
    else
      o.shape =
          dss::Box{Eigen::Vector3d(0.05 + 0.4 * std::abs(u(rng)), 0.05 + 0.4 * std::abs(u(rng)),
                                   0.05 + 0.2 * std::abs(u(rng)))};
    o.X_WO.translation() = Eigen::Vector3d(2.2 * u(rng), 1.7 * u(rng), 0.4 * u(rng));
    if (k % 2 == 1)  // every other one turned
      o.X_WO.linear() =
          Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    scene.obstacles.push_back(o);
  }
  std::vector<double> held(robot->numActiveJoints(), 0.0);
  return std::make_shared<const dss::CollisionModel>(robot, nullptr, scene, std::vector<int>{},
                                                     held);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(base_scene_table)

BOOST_AUTO_TEST_CASE(cells_agree_with_the_exact_decision) {
  const Mobile mb = load("dss_mobile_base", "aisle");
  const auto [colliding, free_links] = checkCells(*mb.with, 30000, 41);
  BOOST_TEST(colliding > 3000u);
  BOOST_TEST(free_links > 3000u);
}

// The same on a tilted plane among turned boxes, cylinders and spheres: the plane's normal,
// the slides' directions and the shrink of the inner boxes come from the joint's frame.
BOOST_AUTO_TEST_CASE(cells_agree_with_the_exact_decision_on_a_tilted_plane) {
  for (std::uint64_t seed : {5u, 6u, 7u}) {
    const auto m = tiltedPlane(seed);
    BOOST_TEST_REQUIRE(m->baseTable().slots().size() == 2u);  // body and deck, not the arm
    const auto [colliding, free_links] = checkCells(*m, 8000, seed + 100);
    BOOST_TEST(colliding > 200u);
    BOOST_TEST(free_links > 1000u);
  }
}

BOOST_AUTO_TEST_CASE(built_for_the_planar_base_only) {
  const Mobile mb = load("dss_mobile_base", "aisle");
  const dss::BaseSceneTable& t = mb.with->baseTable();
  BOOST_TEST_REQUIRE(!t.empty());
  BOOST_TEST(mb.without->baseTable().empty());
  // The base (and the mast fixed on it) are tabled; the lift and the arm move by other joints.
  BOOST_TEST(t.slots().size() == 2u);
  for (int s : t.slots())
    BOOST_TEST((mb.with->robot().links[mb.with->slots()[s].link].name == "base_link" ||
                mb.with->robot().links[mb.with->slots()[s].link].name == "mast_link"));
  BOOST_TEST(t.numCells() <= 4u * dss::CollisionModelOptions().base_table_cells);
  BOOST_TEST(t.cells(2) >= 8);
  BOOST_TEST(t.numColliding() > t.numCells() / 20);
  BOOST_TEST(t.numFree(0) > t.numCells() / 20);
  BOOST_TEST(t.maxMove() > 0.0);
  BOOST_TEST(t.maxMove() < 0.2);
  // A floating base and a fixed arm get none.
  BOOST_TEST(load("dss_free_flyer", "window").with->baseTable().empty());
  BOOST_TEST(dss_test::shelfSetup(dss_test::loadArm()).model->baseTable().empty());
}

BOOST_AUTO_TEST_CASE(answers_match_without_the_table) {
  const Mobile mb = load("dss_mobile_base", "aisle");
  for (double padding : {0.0, 0.03}) {
    dss::DssCheckerSettings set;
    set.scene_padding = padding;
    const dss::DssChecker with(mb.with, set), without(mb.without, set);
    std::mt19937_64 rng(43);
    std::size_t hits = 0;
    std::vector<Eigen::Isometry3d> X(mb.with->robot().links.size(), Eigen::Isometry3d::Identity());
    for (int k = 0; k < 20000; ++k) {
      const std::vector<double> q = sample(*mb.with, rng);
      const bool a = with.collides(q.data()), b = without.collides(q.data());
      BOOST_TEST_REQUIRE(a == b, "state " << k << ", padding " << padding);
      hits += a;
      // The check with the poses given (the continuous check's midpoints) reads it too.
      if (k % 4 == 0) {
        mb.with->kinematics().computeLinkPoses(q.data(), X.data());
        BOOST_TEST_REQUIRE(with.collidesWithPoses(q.data(), X.data()) == a, "state " << k);
        BOOST_TEST_REQUIRE(without.collidesWithPoses(q.data(), X.data()) == a, "state " << k);
      }
    }
    BOOST_TEST(hits > 5000u);
    // The table saves narrow-phase and box work: fewer pair tests with it.
    BOOST_TEST(with.counters().pair_tests <= without.counters().pair_tests);
  }
  // Non-finite values stay invalid input.
  const dss::DssChecker with(mb.with);
  std::vector<double> q = mb.with->held();
  for (double bad : {NAN, INFINITY, -INFINITY}) {
    for (int v : planarVars(mb.with->robot())) {
      std::vector<double> x = q;
      x[v] = bad;
      BOOST_TEST((with.check(x.data()) == dss::StateVerdict::kInvalidInput));
    }
  }
}

// The continuous check clears a base link's units over a sub-motion whose table cells are
// all free for it. The table can only clear what the swept tests could not (never a
// collision): on these short and long random motions (theta crossing +-pi among them) the
// answers and last valid fractions are those without the table, with fewer swept tests.
BOOST_AUTO_TEST_CASE(continuous_answers_match_without_the_table) {
  const Mobile mb = load("dss_mobile_base", "aisle");
  const dss::ContinuousMotionChecker with(std::make_shared<const dss::DssChecker>(mb.with)),
      without(std::make_shared<const dss::DssChecker>(mb.without));
  const auto v = planarVars(mb.with->robot());
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int valid = 0, invalid = 0;
  for (int k = 0; k < 1500; ++k) {
    const std::vector<double> q0 = sample(*mb.with, rng);
    std::vector<double> q1 = sample(*mb.with, rng);
    const double f = k % 3 == 0 ? 1.0 : 0.05;  // long, or short
    for (std::size_t i = 0; i < q0.size(); ++i) q1[i] = q0[i] + f * (q1[i] - q0[i]);
    if (k % 5 == 0) q1[v[2]] = q0[v[2]] + (u(rng) - 0.5);  // a turn, sometimes across +-pi
    if (with.checker().collides(q0.data())) continue;
    double la = -1, lb = -1;
    const bool a = with.clear(q0.data(), q1.data(), &la);
    const bool b = without.clear(q0.data(), q1.data(), &lb);
    BOOST_TEST_REQUIRE(a == b, "motion " << k);
    BOOST_TEST_REQUIRE(la == lb, "motion " << k);
    (a ? valid : invalid)++;
  }
  BOOST_TEST_MESSAGE(valid << " motions clear, " << invalid << " not; swept tests "
                           << with.unitTests() << " with the table, " << without.unitTests()
                           << " without");
  BOOST_TEST(valid > 100);
  BOOST_TEST(invalid > 100);
  BOOST_TEST(with.unitTests() < without.unitTests());
}

BOOST_AUTO_TEST_SUITE_END()
