// The ball stage (ball_stage.h): a ball against a box, sphere, capsule or cylinder is called
// apart or touching only where exact DSS (the ball as a padded point) agrees, on random shapes,
// poses and paddings across twenty scales; at the contact boundary it answers nothing, and
// 1e-6 of the size either side it answers right; other shapes and NaN get no answer. The
// sweep with the stage answers as fcl-hull on the quadrotor among its trees
// (tests/planning/test_mobile_bases.cpp) and needs far fewer narrow-phase tests there.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "dss/checker/ball_stage.h"
#include "dss/checker/checker_setup.h"
#include "dss/checker/dss_checker.h"
#include "dss/core/any_shape_query.h"
#include "dss/robot/multi_dof.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/random_pose.h"

namespace {

using dss_test::randomPose;

// One of the four shapes the stage knows, of about `scale`.
dss::AnyShape randomPrimitive(std::mt19937_64& rng, int kind, double scale) {
  std::uniform_real_distribution<double> u(0.05, 1.0);
  switch (kind) {
    case 0:
      return dss::Box{scale * Eigen::Vector3d(u(rng), u(rng), u(rng))};
    case 1:
      return dss::Sphere{scale * u(rng)};
    case 2:
      return dss::Capsule{scale * u(rng), scale * u(rng)};
    default:
      return dss::Cylinder{scale * u(rng), scale * u(rng)};
  }
}

// Exact DSS on the same pair: the ball (c, r) as a sphere, the padding as DSS's.
bool exactTouch(const dss::AnyShape& shape, const Eigen::Isometry3d& X, const Eigen::Vector3d& c,
                double r, double pad) {
  Eigen::Isometry3d Xc = Eigen::Isometry3d::Identity();
  Xc.translation() = c;
  return dss::intersect(shape, X, dss::Sphere{r}, Xc, {}, pad).intersect;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(ball_stage)

BOOST_AUTO_TEST_CASE(answers_only_where_exact_dss_agrees) {
  std::mt19937_64 rng(71);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t decided[4] = {}, apart[4] = {}, touch[4] = {};
  const int kPairs = 40000;
  for (int i = 0; i < kPairs; ++i) {
    const int kind = i % 4;
    const double scale = std::ldexp(1.0, static_cast<int>(u(rng) * 20) - 10);
    const dss::AnyShape shape = randomPrimitive(rng, kind, scale);
    const Eigen::Isometry3d X = randomPose(rng, scale);
    const Eigen::Vector3d c = X.translation() + randomPose(rng, 0.8 * scale).translation();
    const double r = i % 5 == 0 ? 0.0 : scale * u(rng);
    const double pad = i % 3 == 0 ? 0.0 : 0.2 * scale * u(rng);
    const dss::BoxStage v = dss::ballStage(shape, X, c, r, pad);
    if (v == dss::BoxStage::kUnknown) continue;
    const bool exact = exactTouch(shape, X, c, r, pad);
    BOOST_TEST_REQUIRE((exact == (v == dss::BoxStage::kTouch)),
                       "pair " << i << " (" << dss::shapeTypeName(shape) << "): stage "
                               << (v == dss::BoxStage::kTouch ? "touch" : "apart") << ", exact DSS "
                               << exact);
    ++decided[kind];
    (v == dss::BoxStage::kTouch ? touch : apart)[kind] += 1;
  }
  for (int kind = 0; kind < 4; ++kind) {
    // Away from the boundary every pair is decided, both ways.
    BOOST_TEST(decided[kind] > std::size_t(kPairs / 4 * 99 / 100), "kind " << kind);
    BOOST_TEST(apart[kind] > 1000u, "kind " << kind);
    BOOST_TEST(touch[kind] > 1000u, "kind " << kind);
  }
}

// The ball slid along a random direction to the last place where exact DSS finds it apart
// (bisection): no answer there or just inside; 1e-6 of the size deeper, "touch"; 1e-6 farther
// out, "apart". For the box the ball comes face on, edge on and corner on.
BOOST_AUTO_TEST_CASE(at_the_contact_boundary) {
  std::mt19937_64 rng(73);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n;
  const int kPairs = 2000;
  std::size_t right = 0;
  for (int i = 0; i < kPairs; ++i) {
    const dss::AnyShape shape = randomPrimitive(rng, i % 4, 1.0);
    const Eigen::Isometry3d X = randomPose(rng, 0.5);
    const double r = i % 2 ? 0.3 * u(rng) : 0.0, pad = i % 3 ? 0.1 * u(rng) : 0.0;
    const Eigen::Vector3d dir = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
    auto at = [&](double d) { return Eigen::Vector3d(X.translation() + d * dir); };
    double lo = 0.0, hi = 10.0;  // lo: touching, hi: apart
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (exactTouch(shape, X, at(mid), r, pad) ? lo : hi) = mid;
    }
    BOOST_TEST_REQUIRE((dss::ballStage(shape, X, at(hi), r, pad) == dss::BoxStage::kUnknown),
                       "pair " << i << " (" << dss::shapeTypeName(shape) << ") at the boundary");
    BOOST_TEST_REQUIRE((dss::ballStage(shape, X, at(lo), r, pad) == dss::BoxStage::kUnknown),
                       "pair " << i << " just inside");
    const bool in = dss::ballStage(shape, X, at(hi - 1e-6), r, pad) == dss::BoxStage::kTouch;
    const bool out = dss::ballStage(shape, X, at(hi + 1e-6), r, pad) == dss::BoxStage::kApart;
    right += in && out;
  }
  BOOST_TEST(right == std::size_t(kPairs));
}

BOOST_AUTO_TEST_CASE(degenerate_and_unknown_inputs) {
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const dss::AnyShape box = dss::Box{Eigen::Vector3d(1, 1, 1)};
  // Face on: the ball's surface 0.1 from the face; a padding of 0.2 touches, 0.05 does not.
  BOOST_TEST((dss::ballStage(box, I, {1.6, 0, 0}, 0.5, 0.0) == dss::BoxStage::kApart));
  BOOST_TEST((dss::ballStage(box, I, {1.6, 0, 0}, 0.5, 0.2) == dss::BoxStage::kTouch));
  BOOST_TEST((dss::ballStage(box, I, {1.6, 0, 0}, 0.5, 0.05) == dss::BoxStage::kApart));
  // Corner on: distance sqrt(3) * 0.5 = 0.866 from the corner (1, 1, 1).
  BOOST_TEST((dss::ballStage(box, I, {1.5, 1.5, 1.5}, 0.86, 0.0) == dss::BoxStage::kApart));
  BOOST_TEST((dss::ballStage(box, I, {1.5, 1.5, 1.5}, 0.87, 0.0) == dss::BoxStage::kTouch));
  // A centre inside, and a point (r = 0) inside: touch; a point exactly on the face: no answer.
  BOOST_TEST((dss::ballStage(box, I, {0.3, 0, 0}, 0.1, 0.0) == dss::BoxStage::kTouch));
  BOOST_TEST((dss::ballStage(box, I, {0.3, 0, 0}, 0.0, 0.0) == dss::BoxStage::kTouch));
  BOOST_TEST((dss::ballStage(box, I, {1.0, 0, 0}, 0.0, 0.0) == dss::BoxStage::kUnknown));
  // A flat box (zero thickness) and a cylinder of zero length are still their sets.
  const dss::AnyShape plate = dss::Box{Eigen::Vector3d(1, 1, 0)};
  BOOST_TEST((dss::ballStage(plate, I, {0, 0, 0.3}, 0.2, 0.0) == dss::BoxStage::kApart));
  BOOST_TEST((dss::ballStage(plate, I, {0, 0, 0.3}, 0.4, 0.0) == dss::BoxStage::kTouch));
  const dss::AnyShape disc = dss::Cylinder{1.0, 0.0};
  BOOST_TEST((dss::ballStage(disc, I, {1.5, 0, 0.0}, 0.4, 0.0) == dss::BoxStage::kApart));
  BOOST_TEST((dss::ballStage(disc, I, {1.3, 0, 0.3}, 0.5, 0.0) == dss::BoxStage::kTouch));
  // The capsule's cap: the ball above its end.
  const dss::AnyShape capsule = dss::Capsule{0.5, 1.0};
  BOOST_TEST((dss::ballStage(capsule, I, {0, 0, 2.0}, 0.45, 0.0) == dss::BoxStage::kApart));
  BOOST_TEST((dss::ballStage(capsule, I, {0, 0, 2.0}, 0.55, 0.0) == dss::BoxStage::kTouch));
  // Shapes the stage does not know, and NaN anywhere: no answer.
  const dss::AnyShape hull = dss::ConvexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  BOOST_TEST((dss::ballStage(hull, I, {5, 5, 5}, 0.1, 0.0) == dss::BoxStage::kUnknown));
  const dss::AnyShape ellipsoid = dss::Ellipsoid{Eigen::Vector3d(1, 2, 3)};
  BOOST_TEST((dss::ballStage(ellipsoid, I, {9, 9, 9}, 0.1, 0.0) == dss::BoxStage::kUnknown));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST((dss::ballStage(box, I, {nan, 0, 0}, 0.1, 0.0) == dss::BoxStage::kUnknown));
  BOOST_TEST((dss::ballStage(box, I, {3, 0, 0}, nan, 0.0) == dss::BoxStage::kUnknown));
  BOOST_TEST((dss::ballStage(box, I, {3, 0, 0}, 0.1, nan) == dss::BoxStage::kUnknown));
  Eigen::Isometry3d Xnan = I;
  Xnan.translation().x() = nan;
  BOOST_TEST((dss::ballStage(box, Xnan, {3, 0, 0}, 0.1, 0.0) == dss::BoxStage::kUnknown));
  const double inf = std::numeric_limits<double>::infinity();
  BOOST_TEST((dss::ballStage(box, I, {inf, 0, 0}, 0.1, 0.0) == dss::BoxStage::kUnknown));
}

// The quadrotor among its trees: the sweep's answers with the stage are exact DSS's (the
// checker with and without the oriented-box and ball stages agree on every state), and the
// stage takes most of the narrow-phase tests away: the trees' crowns are spheres.
BOOST_AUTO_TEST_CASE(the_quadrotor_needs_few_narrow_phase_tests_among_round_crowns) {
  const std::string d = std::string(DSS_SOURCE_DIR) + "/robots/dss_quadrotor/";
  const dss::PlanRequest request = dss::loadPlanRequestYaml(d + "scenes/forest_request.yaml");
  BOOST_REQUIRE(request.workspace.has_value());
  const dss::LoadedRobot robot =
      dss::withWorkspace(dss::loadRobot(d + "dss_quadrotor.urdf", d + "dss_quadrotor.srdf"),
                         request.workspace->first, request.workspace->second);
  const dss::ModelSetup setup =
      dss::setupModel(robot, dss::loadScene(d + "scenes/forest.yaml"), "quadrotor", {});
  dss::DssChecker::Settings with_stages, without;
  without.obb_stage = false;
  const dss::DssChecker a(setup.model, with_stages), b(setup.model, without);
  const dss::CollisionModel& m = *setup.model;
  std::mt19937_64 rng(79);
  const int n = 4000;
  int colliding = 0;
  for (int k = 0; k < n; ++k) {
    std::vector<double> q(m.robot().numActiveJoints());
    for (std::size_t j = 0; j < q.size(); ++j) {
      const auto& lim = m.robot().joints[m.robot().active_joints[j]].limits;
      q[j] = std::uniform_real_distribution<double>(lim.lower, lim.upper)(rng);
    }
    const dss::StateVerdict va = a.check(q.data()), vb = b.check(q.data());
    BOOST_TEST_REQUIRE((va == vb), "state " << k);
    colliding += va == dss::StateVerdict::kColliding;
  }
  BOOST_TEST(colliding > n / 10);
  BOOST_TEST(colliding < n * 9 / 10);
  const double with_tests = double(a.counters().pair_tests) / n;
  const double without_tests = double(b.counters().pair_tests) / n;
  BOOST_TEST_MESSAGE("narrow-phase tests per state: " << with_tests << " with the stages, "
                                                      << without_tests << " without");
  BOOST_TEST(with_tests < 0.25 * without_tests);
}

BOOST_AUTO_TEST_SUITE_END()
