// The decisions on model shapes compiled in the core library (any_shape_query.h,
// any_shape_sweep.h): they must take the same paths as the templates they instantiate. Two
// hulls at the exact identity pose are decided as world vertices (exactly, in the exact mode);
// a posed sphere held by reference takes the plain modes' ball test; swept pairs answer as the
// SweptHull template does.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>

#include "dss/core/any_shape_query.h"
#include "dss/core/any_shape_sweep.h"
#include "dss/core/dss.h"
#include "dss/core/padded.h"
#include "dss/core/posed.h"
#include "dss/core/ref.h"
#include "dss/core/swept.h"

using namespace dss;

namespace {
ConvexHull cube(const Vec3d& c) {
  std::vector<Vec3d> v;
  for (int k = 0; k < 8; ++k)
    v.push_back(c + Vec3d(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  return ConvexHull(v);
}
bool same(const Result& a, const Result& b) {
  return a.intersect == b.intersect && a.status == b.status && a.iterations == b.iterations &&
         a.separating_direction == b.separating_direction;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(any_shape_query)

// Cubes touching along a direction, then one ulp apart: at the identity pose the dispatch
// decides the world vertices exactly (one ulp is "disjoint"), as the ConvexHull template does;
// the same hulls behind any other pose are posed shapes, whose "intersect" answers are exact
// only up to the rounding of their supports.
BOOST_AUTO_TEST_CASE(world_hulls_at_the_identity_pose_are_exact) {
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  int posed_says_touching = 0;
  for (const Vec3d dir : {Vec3d(1, 0, 0), Vec3d(1, 1, 0), Vec3d(1, 1, 1), Vec3d(-1, 1, -1)}) {
    const Vec3d touch = 2.0 * dir;
    Vec3d apart = touch;
    for (int k = 0; k < 3; ++k)
      if (dir[k] != 0) apart[k] = std::nextafter(touch[k], dir[k] > 0 ? 10.0 : -10.0);
    const AnyShape a = cube(Vec3d::Zero()), b = cube(touch), c = cube(apart);
    BOOST_TEST(intersect(a, I, b, I).intersect, "touching along " << dir.transpose());
    BOOST_TEST(!intersect(a, I, c, I).intersect, "one ulp apart along " << dir.transpose());
    BOOST_TEST(!intersect(c, I, a, I).intersect);
    BOOST_TEST(
        same(intersect(a, I, c, I), intersect(std::get<ConvexHull>(a), std::get<ConvexHull>(c))));
    // A pose that is not exactly the identity: rotation by 2 pi (rounded), translation zero.
    Eigen::Isometry3d X = I;
    X.linear() = Eigen::AngleAxisd(2 * M_PI, Vec3d::UnitZ()).toRotationMatrix();
    BOOST_REQUIRE(!(X.matrix() == I.matrix()));
    posed_says_touching += intersect(a, X, c, X).intersect;
  }
  // Posed, the one-ulp gap is below what a posed support can certify.
  BOOST_TEST(posed_says_touching > 0);
}

// The plain double search tests a posed ball by h_A(n) + r|n| (dss.h, testBallDirection); the
// dispatch poses model shapes by reference, and the ball test must recognise those too.
BOOST_AUTO_TEST_CASE(posed_references_to_balls_take_the_ball_test) {
  static_assert(detail::IsPosedBall<Posed<detail::Ref<Sphere>>>::value);
  static_assert(detail::IsPosedBall<Posed<Sphere>>::value);
  static_assert(!detail::IsPosedBall<Posed<detail::Ref<Box>>>::value);
  static_assert(!detail::IsPosedBall<Posed<detail::Ref<ConvexHull>>>::value);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  Options dbl;
  dbl.mode = Mode::kDouble;
  int n = 0, hits = 0;
  for (int i = 0; i < 2000; ++i) {
    std::vector<Vec3d> pts;
    for (int k = 0; k < 6; ++k) pts.push_back(0.5 * Vec3d(u(rng), u(rng), u(rng)));
    const ConvexHull hull(pts);
    const Sphere ball{0.05 + 0.4 * std::abs(u(rng))};
    Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity(), X_WB = Eigen::Isometry3d::Identity();
    X_WA.linear() =
        Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    X_WA.translation() = Vec3d(u(rng), u(rng), u(rng));
    X_WB.translation() = X_WA.translation() + 0.6 * Vec3d(u(rng), u(rng), u(rng));
    const Result via_model = intersect(AnyShape(hull), X_WA, AnyShape(ball), X_WB, dbl);
    const Result direct =
        intersect(posed(hull, Mat3d(X_WA.linear()), Vec3d(X_WA.translation())),
                  posed(ball, Mat3d(X_WB.linear()), Vec3d(X_WB.translation())), dbl);
    BOOST_TEST(same(via_model, direct), "pair " << i);
    ++n;
    hits += direct.intersect;
  }
  BOOST_TEST(hits > n * 0.2);
  BOOST_TEST(hits < n * 0.8);
}

// intersectSwept answers exactly as the SweptHull template it instantiates, in every mode,
// against a posed shape and against another swept one.
BOOST_AUTO_TEST_CASE(swept_decisions_match_the_templates) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  auto pose = [&](double spread) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    X.translation() = spread * Vec3d(u(rng), u(rng), u(rng));
    return X;
  };
  auto swept = [](const auto& s, const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1) {
    SweptHull<std::decay_t<decltype(s)>> h{s};
    h.R0 = X0.linear();
    h.R1 = X1.linear();
    h.p0 = X0.translation();
    h.p1 = X1.translation();
    return h;
  };
  int hits = 0, n = 0;
  for (int i = 0; i < 600; ++i) {
    const Box box = Box::fromSize(Vec3d(0.3 + 0.2 * u(rng), 0.2, 0.4));
    const Capsule cap = Capsule::fromLength(0.1, 0.3);
    const Eigen::Isometry3d A0 = pose(1.0), A1 = pose(1.0), B0 = pose(1.0), B1 = pose(1.0);
    const double pad = 0.05 * std::abs(u(rng));
    Options opt;
    opt.mode = static_cast<Mode>(i % 3);
    const Result r1 = intersectSwept(AnyShape(box), A0, A1, pad, AnyShape(cap), B0, opt);
    const Result t1 = intersect(padded(swept(box, A0, A1), pad),
                                posed(cap, Mat3d(B0.linear()), Vec3d(B0.translation())), opt);
    BOOST_TEST(same(r1, t1), "pair " << i);
    const Result r2 = intersectSwept(AnyShape(box), A0, A1, pad, AnyShape(cap), B0, B1, opt);
    const Result t2 = intersect(padded(swept(box, A0, A1), pad), swept(cap, B0, B1), opt);
    BOOST_TEST(same(r2, t2), "pair " << i);
    hits += t1.intersect + t2.intersect;
    n += 2;
  }
  BOOST_TEST(hits > n * 0.2);
  BOOST_TEST(hits < n * 0.9);
}

BOOST_AUTO_TEST_SUITE_END()
