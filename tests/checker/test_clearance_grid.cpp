// The clearance grid (clearance_grid.h): its "clear" must be a proof. For random boxes and
// random balls (radii drawn around the true distance, so that many sit within a hair of it),
// clear(c, r) implies every box is farther than r from c; it must also settle a good share of
// the balls that are clear, say nothing outside its region or for NaN, and an empty grid says
// nothing at all. Its candidate lists must hold every box a ball of up to their radius can
// touch, from any point of any voxel (balls placed within a hair of a box, and of voxel faces).
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

BOOST_AUTO_TEST_CASE(candidate_lists_hold_every_box_a_ball_can_touch) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.2), f(0.0, 1.0);
  std::size_t listed = 0, total = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<dss::Aabb> boxes(20 + 11 * trial);  // more than one 64-bit word from trial 4
    for (auto& b : boxes) {
      const Eigen::Vector3d c(u(rng), u(rng), u(rng)), h(e(rng), e(rng), e(rng));
      b.lower = c - h;
      b.upper = c + h;
    }
    dss::Aabb region;
    region.lower = Eigen::Vector3d(-1.2, -1.1, -1.0);
    region.upper = Eigen::Vector3d(1.1, 1.2, 1.3);
    dss::ClearanceGrid grid(region, boxes, trial % 2 ? 4096 : 65536);
    const double radius = 0.05 + 0.1 * trial;
    grid.buildCandidates(boxes, radius, std::size_t(64) << 20);
    BOOST_REQUIRE(grid.candidateWords() == (boxes.size() + 63) / 64);
    BOOST_TEST(!grid.candidates(Eigen::Vector3d::Zero(), radius * 1.001));  // above the radius
    BOOST_TEST(!grid.candidates(Eigen::Vector3d(5, 0, 0), radius));         // outside the grid
    BOOST_TEST(!grid.candidates(Eigen::Vector3d(std::nan(""), 0, 0), radius));
    const double voxel = grid.voxelSize();
    for (int k = 0; k < 4000; ++k) {
      Eigen::Vector3d c(1.1 * u(rng), 1.1 * u(rng), 1.1 * u(rng));
      if (k % 3 == 0) {  // on a voxel face, within rounding
        const int a = k % 9 / 3;
        c[a] = grid.origin()[a] + voxel * std::round((c[a] - grid.origin()[a]) / voxel);
        c[a] = std::nextafter(c[a], k % 2 ? 10.0 : -10.0);
      }
      const std::uint64_t* cand = grid.candidates(c, radius);
      if (!cand) continue;
      for (std::size_t b = 0; b < boxes.size(); ++b) {
        const double d = std::sqrt(dss::detail::sqDistPointAabb(c, boxes[b]));
        // A ball of the full radius, and balls just reaching the box.
        if (d <= radius || (k % 5 == 0 && d <= radius * (1.0 + 1e-12))) {
          ++total;
          const bool in = (cand[b / 64] >> (b % 64)) & 1u;
          listed += in;
          BOOST_TEST(in, "trial " << trial << " point " << k << " box " << b);
        }
      }
    }
  }
  BOOST_TEST(total > 10000u);
  BOOST_TEST(listed == total);
  // Too large for the memory allowed: no lists.
  std::vector<dss::Aabb> boxes(70);
  for (auto& b : boxes) b.lower = b.upper = Eigen::Vector3d::Zero();
  dss::Aabb region;
  region.lower = Eigen::Vector3d::Constant(-1.0);
  region.upper = Eigen::Vector3d::Constant(1.0);
  dss::ClearanceGrid grid(region, boxes, 65536);
  grid.buildCandidates(boxes, 0.1, 1024);
  BOOST_TEST(grid.candidateWords() == 0u);
  BOOST_TEST(!grid.candidates(Eigen::Vector3d::Zero(), 0.1));
}

BOOST_AUTO_TEST_SUITE_END()
