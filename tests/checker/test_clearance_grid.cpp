// The clearance grid (clearance_grid.h): its "clear" must be a proof. For random boxes and
// random balls (radii drawn around the true distance, so that many sit within a hair of it),
// clear(c, r) implies every box is farther than r from c; it must also settle a good share of
// the balls that are clear, say nothing outside its region or for NaN, and an empty grid says
// nothing at all.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "dss/checker/clearance_grid.h"

BOOST_AUTO_TEST_SUITE(clearance_grid)

BOOST_AUTO_TEST_CASE(clearance_grid_is_a_lower_bound) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.3), f(0.0, 1.0);
  int settled = 0, clear_balls = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<dss::Aabb> boxes(1 + trial % 7);
    for (auto& b : boxes) {
      const Eigen::Vector3d c(u(rng), u(rng), u(rng)), h(e(rng), e(rng), e(rng));
      b.lower = c - h;
      b.upper = c + h;
    }
    if (trial == 3) boxes[0].upper = boxes[0].lower;  // a point-sized box
    dss::Aabb region;
    region.lower = Eigen::Vector3d(-1.2, -1.1, -1.0);
    region.upper = Eigen::Vector3d(1.1, 1.2, 1.3);
    const dss::ClearanceGrid grid(region, boxes, trial % 2 ? 4096 : 65536);
    BOOST_TEST(!grid.empty());
    BOOST_TEST(grid.voxels() <= (trial % 2 ? 4096u : 65536u));
    for (int k = 0; k < 5000; ++k) {
      const Eigen::Vector3d c(1.3 * u(rng), 1.3 * u(rng), 1.3 * u(rng));
      double d = std::numeric_limits<double>::infinity();
      for (const auto& b : boxes) d = std::min(d, std::sqrt(dss::detail::sqDistPointAabb(c, b)));
      const double r = k % 4 == 0 ? d * (1.0 - 1e-12) : d * f(rng);
      // The grid covers the region in whole voxels: up to one voxel more on the upper sides.
      const bool inside = (c.array() >= region.lower.array()).all() &&
                          (c.array() < region.upper.array() + grid.voxelSize()).all();
      if (grid.clear(c, r)) {
        ++settled;
        BOOST_TEST(d > r);
        BOOST_TEST(inside);
        BOOST_TEST(grid.bound(c) > r);
        BOOST_TEST(grid.bound(c) <= d);
      }
      clear_balls += inside && d > r + 0.1;
    }
  }
  BOOST_TEST_MESSAGE("clearance grid settled " << settled << " balls; " << clear_balls
                                               << " inside with 0.1 m to spare");
  BOOST_TEST(settled >= clear_balls * 9 / 10);
  const dss::ClearanceGrid empty;
  BOOST_TEST(!empty.clear(Eigen::Vector3d::Zero(), 0.0));
  dss::Aabb region;
  region.lower = Eigen::Vector3d::Constant(-1.0);
  region.upper = Eigen::Vector3d::Constant(1.0);
  const dss::ClearanceGrid grid(
      region, {dss::Aabb{Eigen::Vector3d::Constant(5.0), Eigen::Vector3d::Constant(6.0)}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(grid.clear(Eigen::Vector3d::Zero(), 0.5));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(nan, 0.0, 0.0), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(0.0, 0.0, nan), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d::Zero(), nan));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(2.0, 0.0, 0.0), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity()));
}

BOOST_AUTO_TEST_SUITE_END()
