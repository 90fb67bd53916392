// The oriented-box stage of the sweep must never call a touching pair apart: on random box
// pairs (many near contact), every "apart" from obbApart is confirmed disjoint by exact DSS.
#include <random>

#include <boost/test/unit_test.hpp>

#include "dss/core/any_shape_query.h"
#include "dss/planning/collision_model.h"

BOOST_AUTO_TEST_CASE(obb_apart_is_never_wrong) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0), s(0.05, 0.6);
  int apart = 0, dss_disjoint = 0;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Matrix3d Ra = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    const Eigen::Matrix3d Rb = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    const Eigen::Vector3d ha(s(rng), s(rng), s(rng)), hb(s(rng), s(rng), s(rng));
    const Eigen::Vector3d ca(u(rng), u(rng), u(rng)), cb(u(rng), u(rng), u(rng));
    const double pad = k % 3 == 0 ? 0.05 : 0.0;
    Eigen::Isometry3d Xa = Eigen::Isometry3d::Identity(), Xb = Xa;
    Xa.linear() = Ra;
    Xa.translation() = ca;
    Xb.linear() = Rb;
    Xb.translation() = cb;
    const dss::Result r = dss::intersect(dss::AnyShape(dss::Box{ha}), Xa, dss::AnyShape(dss::Box{hb}), Xb, {}, pad);
    dss_disjoint += !r.intersect;
    if (dss::detail::obbApart(Ra, ca, ha, Rb, cb, hb, pad)) {
      ++apart;
      BOOST_TEST(!r.intersect);
    }
  }
  BOOST_TEST_MESSAGE("obbApart " << apart << ", DSS disjoint " << dss_disjoint << " of 20000");
  BOOST_TEST(apart > 1000);
  // SAT on boxes is exact up to its margin: it finds nearly every disjoint pair.
  BOOST_TEST(apart >= dss_disjoint * 99 / 100);
}

// The sphere-box stage of the sweep tests a slot's boxes two at a time from six coordinate
// arrays: against the scalar distance for random boxes (many within a hair of the sphere),
// every length from 0 to 64 and every start, NaN centres (always "test further"), and the
// padding lanes (never a hit).
BOOST_AUTO_TEST_CASE(sphere_box_hits_match_the_scalar_distance) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.5);
  const std::size_t total = 67, stride = 68;
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<dss::Aabb> boxes(total);
    std::vector<double> soa(6 * stride);
    for (std::size_t i = 0; i < stride; ++i) {
      if (i < total) {
        const Eigen::Vector3d c(u(rng), u(rng), u(rng)), h(e(rng), e(rng), e(rng));
        boxes[i].lower = c - h;
        boxes[i].upper = c + h;
      }
      for (int a = 0; a < 3; ++a) {
        soa[a * stride + i] = i < total ? boxes[i].lower[a] : std::numeric_limits<double>::infinity();
        soa[(3 + a) * stride + i] = i < total ? boxes[i].upper[a] : -std::numeric_limits<double>::infinity();
      }
    }
    Eigen::Vector3d c(u(rng), u(rng), u(rng));
    if (trial % 50 == 7) c.y() = std::numeric_limits<double>::quiet_NaN();
    // a radius at the exact distance of one box: that box is a hit (distance <= radius)
    const double r2 = trial % 2 ? dss::detail::sqDistPointAabb(c, boxes[trial % total]) : 0.3 * (1 + u(rng));
    for (std::size_t begin = 0; begin + 1 < stride; begin += 2) {
      const std::size_t n = std::min<std::size_t>(64, total - std::min(total, begin));
      const std::uint64_t hits = dss::detail::sphereBoxHits(soa.data(), stride, begin, n, c, r2);
      for (std::size_t i = 0; i < 64; ++i) {
        const bool want = i < n && !(dss::detail::sqDistPointAabb(c, boxes[begin + i]) > r2);
        BOOST_TEST_REQUIRE(bool((hits >> i) & 1) == want, "trial " << trial << " begin " << begin << " box " << i);
      }
    }
  }
}
