// The sphere-box filter of the sweep (sphere_box_filter.h) tests a slot's boxes two at a time
// from six coordinate arrays (BoxSoa): against the scalar distance for random boxes (many
// within a hair of the sphere), every length from 0 to 64 and every start, NaN centres (always
// "test further"), and the padding lane of an odd count (never a hit).
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "dss/checker/sphere_box_filter.h"

BOOST_AUTO_TEST_SUITE(sphere_box_filter)

BOOST_AUTO_TEST_CASE(sphere_box_hits_match_the_scalar_distance) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.5);
  const std::size_t total = 67;  // odd: the arrays end with one empty padding box
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<dss::Aabb> boxes(total);
    for (auto& b : boxes) {
      const Eigen::Vector3d c(u(rng), u(rng), u(rng)), h(e(rng), e(rng), e(rng));
      b.lower = c - h;
      b.upper = c + h;
    }
    const dss::BoxSoa soa(boxes);
    BOOST_TEST_REQUIRE(soa.size() == total);
    Eigen::Vector3d c(u(rng), u(rng), u(rng));
    if (trial % 50 == 7) c.y() = std::numeric_limits<double>::quiet_NaN();
    // a radius at the exact distance of one box: that box is a hit (distance <= radius)
    const double r2 =
        trial % 2 ? dss::detail::sqDistPointAabb(c, boxes[trial % total]) : 0.3 * (1 + u(rng));
    for (std::size_t begin = 0; begin < total; begin += 2) {
      const std::size_t n = std::min<std::size_t>(64, total - std::min(total, begin));
      const std::uint64_t hits = soa.hits(begin, n, c, r2);
      for (std::size_t i = 0; i < 64; ++i) {
        const bool want = i < n && !(dss::detail::sqDistPointAabb(c, boxes[begin + i]) > r2);
        BOOST_TEST_REQUIRE(bool((hits >> i) & 1) == want,
                           "trial " << trial << " begin " << begin << " box " << i);
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
