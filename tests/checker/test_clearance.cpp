// DssChecker::clearance is a lower bound on the distance over the checked pairs, within its
// tolerance: compared with FCL's distance on the same hull geometry on random states of our
// shelf scene, and 0 for colliding and NaN states.
#include <fcl/fcl.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "dss/checker/checker_setup.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/fcl_checker.h"
#include "support/checker_fixtures.h"

namespace {
double fclDistance(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& XA,
                   const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& XB) {
  fcl::DistanceRequestd req;
  req.gjk_solver_type = fcl::GST_INDEP;
  req.distance_tolerance = 1e-8;
  fcl::DistanceResultd res;
  return fcl::distance(a, XA, b, XB, req, res);
}
}  // namespace

BOOST_AUTO_TEST_SUITE(dss_clearance)

BOOST_AUTO_TEST_CASE(clearance_is_a_tight_lower_bound) {
  const auto robot = dss_test::loadArm();
  const dss::ModelSetup p = dss_test::shelfSetup(robot);
  dss::DssCheckerSettings settings;
  settings.clearance_tolerance = 1e-3;
  const dss::DssChecker dss_checker(p.model, settings);
  const dss::FclChecker fcl_checker(p.model, dss::FclCheckerSettings{dss::FclGeometry::kHull});
  const dss::CollisionModel& m = *p.model;
  std::mt19937_64 rng(5);
  std::vector<double> q;
  std::vector<Eigen::Isometry3d> X(m.robot().links.size(), Eigen::Isometry3d::Identity());
  int valid = 0, colliding = 0;
  double worst_gap = 0.0;
  for (int k = 0; k < 300; ++k) {
    q = dss_test::randomGroupState(m, rng);
    const double c = dss_checker.clearance(q.data());
    const dss::StateVerdict verdict = dss_checker.check(q.data());
    BOOST_TEST_REQUIRE((verdict != dss::StateVerdict::kInvalidInput), "state " << k);
    if (verdict == dss::StateVerdict::kColliding) {
      BOOST_TEST(c == 0.0);
      ++colliding;
      continue;
    }
    ++valid;
    // Reference: FCL distance over the pairs the model checks.
    m.kinematics().computeLinkPoses(q.data(), X.data());
    double d = std::numeric_limits<double>::infinity();
    for (const auto& slot : m.slots())
      for (int o : slot.obstacles)
        for (int e = slot.first_element; e < slot.first_element + slot.num_elements; ++e)
          d = std::min(d,
                       fclDistance(fcl_checker.elementGeometry(e),
                                   X[slot.link] * m.elements()[e].source->X_LS,
                                   fcl_checker.obstacleGeometry(o), m.scene().obstacles[o].X_WO));
    for (const auto& sp : m.selfPairs()) {
      const auto& sa = m.slots()[sp.a];
      const auto& sb = m.slots()[sp.b];
      for (int a = sa.first_element; a < sa.first_element + sa.num_elements; ++a)
        for (int b = sb.first_element; b < sb.first_element + sb.num_elements; ++b)
          d = std::min(d, fclDistance(fcl_checker.elementGeometry(a),
                                      X[sa.link] * m.elements()[a].source->X_LS,
                                      fcl_checker.elementGeometry(b),
                                      X[sb.link] * m.elements()[b].source->X_LS));
    }
    const double reference = std::min(d, m.prunedClearance());
    BOOST_TEST(c <= d + 1e-6, "clearance " << c << " above the distance " << d);
    BOOST_TEST(c >= reference - 1e-3 - 1e-6,
               "clearance " << c << " not within tolerance of " << reference);
    worst_gap = std::max(worst_gap, reference - c);
  }
  BOOST_TEST(valid > 30);
  BOOST_TEST(colliding > 30);
  BOOST_TEST_MESSAGE("clearance: " << valid << " valid, " << colliding
                                   << " colliding states; largest shortfall " << worst_gap
                                   << " m (tolerance 1e-3)");
  // NaN: invalid, clearance 0.
  q[m.groupActive()[0]] = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(dss_checker.clearance(q.data()) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
