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

// The clearance grid's "clear" must be a proof: for random boxes and random balls (radii
// drawn around the true distance, so that many sit within a hair of it), clear(c, r) implies
// every box is farther than r from c; it must also settle a good share of the balls that are
// clear, say nothing outside its region or for NaN, and an empty grid says nothing at all.
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
  BOOST_TEST_MESSAGE("clearance grid settled " << settled << " balls; " << clear_balls << " inside with 0.1 m to spare");
  BOOST_TEST(settled >= clear_balls * 9 / 10);
  const dss::ClearanceGrid empty;
  BOOST_TEST(!empty.clear(Eigen::Vector3d::Zero(), 0.0));
  dss::Aabb region;
  region.lower = Eigen::Vector3d::Constant(-1.0);
  region.upper = Eigen::Vector3d::Constant(1.0);
  const dss::ClearanceGrid grid(region, {dss::Aabb{Eigen::Vector3d::Constant(5.0), Eigen::Vector3d::Constant(6.0)}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(grid.clear(Eigen::Vector3d::Zero(), 0.5));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(nan, 0.0, 0.0), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(0.0, 0.0, nan), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d::Zero(), nan));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(2.0, 0.0, 0.0), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity()));
}
