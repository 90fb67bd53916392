// The oriented-box stage of the sweep (obb.h) must never call a touching pair apart: on random
// box pairs (many near contact), every "apart" from obbApart is confirmed disjoint by exact DSS,
// and it finds nearly every disjoint pair.
#include <boost/test/unit_test.hpp>
#include <random>

#include "dss/checker/obb.h"
#include "dss/core/any_shape_query.h"

BOOST_AUTO_TEST_SUITE(obb_stage)

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
    const dss::Result r =
        dss::intersect(dss::AnyShape(dss::Box{ha}), Xa, dss::AnyShape(dss::Box{hb}), Xb, {}, pad);
    dss_disjoint += !r.intersect;
    if (dss::obbApart(Ra, ca, ha, Rb, cb, hb, pad)) {
      ++apart;
      BOOST_TEST(!r.intersect);
    }
  }
  BOOST_TEST_MESSAGE("obbApart " << apart << ", DSS disjoint " << dss_disjoint << " of 20000");
  BOOST_TEST(apart > 1000);
  // SAT on boxes is exact up to its margin: it finds nearly every disjoint pair.
  BOOST_TEST(apart >= dss_disjoint * 99 / 100);
}

BOOST_AUTO_TEST_SUITE_END()
