// Support functions of the primitives against independent long-double formulas, the URDF
// conventions (cone apex at +z, cylinder and capsule along z), and curved shapes at gaps and
// depths from 1e-3 down to 1e-12 of their size against a box face, for every shape type.
#include <boost/test/unit_test.hpp>
#include <random>

#include "dss/core/any_shape_query.h"
#include "dss/core/dss.h"
#include "dss/core/padded.h"
#include "dss/core/posed.h"
#include "dss/core/spherical_polygon.h"

using namespace dss;

namespace {

using LD = long double;

// h(d) for |d| = 1 in the shape's frame: the analytic support value.
LD supportValue(const AnyShape& s, const Vec3d& d) {
  const LD dx = d.x(), dy = d.y(), dz = d.z();
  const LD rxy = std::sqrt(dx * dx + dy * dy);
  if (auto* x = std::get_if<Sphere>(&s)) return x->radius;
  if (auto* x = std::get_if<Box>(&s))
    return std::abs(dx) * x->half.x() + std::abs(dy) * x->half.y() + std::abs(dz) * x->half.z();
  if (auto* x = std::get_if<Capsule>(&s)) return x->radius + std::abs(dz) * x->half_length;
  if (auto* x = std::get_if<Cylinder>(&s)) return x->radius * rxy + std::abs(dz) * x->half_length;
  if (auto* x = std::get_if<Cone>(&s))
    return std::max<LD>(dz * x->half_length, x->radius * rxy - dz * x->half_length);
  if (auto* x = std::get_if<Ellipsoid>(&s)) {
    const LD a = x->radii.x() * dx, b = x->radii.y() * dy, c = x->radii.z() * dz;
    return std::sqrt(a * a + b * b + c * c);
  }
  return 0;
}

std::vector<AnyShape> primitives() {
  return {Sphere{0.7},
          Box::fromSize({0.4, 1.0, 0.6}),
          Capsule::fromLength(0.3, 0.8),
          Cylinder::fromLength(0.4, 1.2),
          Cone::fromLength(0.5, 1.0),
          Ellipsoid{Vec3d(0.3, 0.6, 0.9)}};
}

Mat3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(shapes)

BOOST_AUTO_TEST_CASE(support_matches_analytic_values) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g;
  for (const auto& s : primitives()) {
    for (int i = 0; i < 2000; ++i) {
      const Vec3d d = Vec3d(g(rng), g(rng), g(rng)).normalized();
      const Vec3d x =
          std::visit([&](const auto& sh) { return Vec3d(sh.support(d, Vec3d::Zero())); }, s);
      BOOST_TEST(std::abs(LD(d.dot(x)) - supportValue(s, d)) < 1e-14L, shapeTypeName(s));
    }
  }
}

BOOST_AUTO_TEST_CASE(urdf_conventions) {
  const Cone cone = Cone::fromLength(0.5, 2.0);
  BOOST_TEST(cone.support(Vec3d(0, 0, 1), Vec3d::Zero()).z() == 1.0);    // apex at +length/2
  BOOST_TEST(cone.support(Vec3d(0, 0, -1), Vec3d::Zero()).z() == -1.0);  // base at -length/2
  BOOST_TEST(cone.support(Vec3d(1, 0, -1), Vec3d::Zero()).x() == 0.5);
  const Cylinder cyl = Cylinder::fromLength(0.5, 2.0);
  BOOST_TEST(cyl.support(Vec3d(0, 0, 1), Vec3d::Zero()).z() == 1.0);
  const Capsule cap = Capsule::fromLength(0.5, 2.0);
  BOOST_TEST(cap.support(Vec3d(0, 0, 1), Vec3d::Zero()).z() == 1.5);  // length/2 + radius
  const Box box = Box::fromSize({1, 2, 3});
  BOOST_TEST((box.support(Vec3d(1, -1, 1), Vec3d::Zero()) == Vec3d(0.5, -1, 1.5)));
}

// A slab whose top face is z = 0; each primitive, randomly rotated, is lowered to a gap or
// depth of eps * size from it. The reference is the analytic support value in long double.
BOOST_AUTO_TEST_CASE(near_contact_every_shape_type) {
  std::mt19937_64 rng(2);
  const auto slab = posed(Box::fromSize({4, 4, 1}), Mat3d::Identity().eval(), Vec3d(0, 0, -0.5));
  const AnyShape slab_any = Box::fromSize({4, 4, 1});
  Eigen::Isometry3d X_slab = Eigen::Isometry3d::Identity();
  X_slab.translation() = Vec3d(0, 0, -0.5);
  int wrong_exact = 0, n = 0, wrong_double = 0, wrong_float = 0;
  for (const auto& s : primitives()) {
    for (double eps : {1e-3, 1e-6, 1e-9, 1e-12}) {
      for (int side : {+1, -1}) {
        for (int i = 0; i < 25; ++i) {
          const Mat3d R = randomRotation(rng);
          // lowest point of R*S: -h_S(R^T (0,0,-1))
          const LD low = supportValue(s, R.transpose() * Vec3d(0, 0, -1));
          const double size = 1.0;
          const double z = double(low + LD(side * eps * size));
          Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
          X.linear() = R;
          X.translation() = Vec3d(0.1 * i / 25.0, -0.05, z);
          const bool truth = side < 0;
          Options o;
          for (bool swap : {false, true}) {
            const Result r =
                swap ? intersect(slab_any, X_slab, s, X, o) : intersect(s, X, slab_any, X_slab, o);
            wrong_exact += r.intersect != truth;
            ++n;
          }
          o.mode = Mode::kDouble;
          wrong_double += intersect(s, X, slab_any, X_slab, o).intersect != truth;
          o.mode = Mode::kFloat;
          wrong_float += intersect(s, X, slab_any, X_slab, o).intersect != truth;
        }
      }
    }
  }
  (void)slab;
  BOOST_TEST_MESSAGE("curved near contact: " << n << " exact queries, wrong " << wrong_exact
                                             << "; double wrong " << wrong_double
                                             << "; float wrong " << wrong_float);
  BOOST_TEST(wrong_exact == 0);
}

BOOST_AUTO_TEST_CASE(sphere_pairs_against_distance) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, n = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3d ca(u(rng), u(rng), u(rng));
    const double ra = 0.2 + 0.5 * std::abs(u(rng)), rb = 0.2 + 0.5 * std::abs(u(rng));
    // Centre distances spread around contact: about half the pairs intersect.
    const Vec3d cb =
        ca + Vec3d(u(rng), u(rng), u(rng)).normalized() * (ra + rb) * (1.0 + 0.5 * u(rng));
    const LD gap = std::sqrt(LD((ca - cb).squaredNorm())) - ra - rb;
    if (std::abs(gap) < 1e-12L) continue;
    const auto a = posed(Sphere{ra}, Mat3d::Identity().eval(), ca);
    const auto b = posed(Sphere{rb}, Mat3d::Identity().eval(), cb);
    BOOST_TEST(intersect(a, b).intersect == (gap <= 0));
    hits += gap <= 0;
    ++n;
  }
  BOOST_TEST(hits > n * 0.3);
  BOOST_TEST(hits < n * 0.7);
}

// The double mode decides a posed ball B by h_A(n) + r |n| with poles scaled by |n| (dss.h,
// testBallDirection). Against the exact mode on hull-ball and ball-ball pairs that are not near
// contact (the exact answer is the same with the radius 1e-4 larger and smaller), double gives
// the same answers with the ball as B (that path) and as A (the general one); so does float.
BOOST_AUTO_TEST_CASE(ball_test_of_the_plain_modes) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  int n = 0, hits = 0, wrong = 0, wrong_float = 0, hull_pairs = 0, same_iterations = 0;
  Options exact, dbl, flt;
  dbl.mode = Mode::kDouble;
  flt.mode = Mode::kFloat;
  for (int i = 0; i < 4000; ++i) {
    std::vector<Vec3d> pts;
    const Vec3d c0(u(rng), u(rng), u(rng));
    const int m = 1 + i % 8;  // points, segments, triangles and solids
    for (int k = 0; k < m; ++k) pts.push_back(c0 + 0.5 * Vec3d(u(rng), u(rng), u(rng)));
    const ConvexHull hull(pts);
    const double r = 0.05 + 0.4 * std::abs(u(rng));
    const Vec3d cb = c0 + 0.4 * Vec3d(u(rng), u(rng), u(rng));
    const auto ball = posed(Sphere{r}, Mat3d::Identity().eval(), cb);
    const auto ball_small = posed(Sphere{r * (1 - 1e-4)}, Mat3d::Identity().eval(), cb);
    const auto ball_large = posed(Sphere{r * (1 + 1e-4)}, Mat3d::Identity().eval(), cb);
    const auto other = posed(Sphere{0.3 * std::abs(u(rng))}, Mat3d::Identity().eval(), c0);
    for (int kind = 0; kind < 2; ++kind) {
      auto check = [&](const auto& a) {
        const bool truth = intersect(a, ball, exact).intersect;
        if (intersect(a, ball_small, exact).intersect != truth ||
            intersect(a, ball_large, exact).intersect != truth)
          return;  // near contact: the plain modes may differ
        ++n;
        hits += truth;
        const Result d = intersect(a, ball, dbl);
        wrong += d.intersect != truth;
        if (kind == 0) {
          ++hull_pairs;
          same_iterations += d.iterations == intersect(a, ball, exact).iterations;
        }
        wrong += intersect(ball, a, dbl).intersect != truth;
        wrong_float += intersect(a, ball, flt).intersect != truth;
        wrong_float += intersect(ball, a, flt).intersect != truth;
      };
      if (kind == 0)
        check(hull);
      else
        check(other);
    }
  }
  BOOST_TEST_MESSAGE("ball pairs: " << n << ", intersecting " << hits << ", double wrong " << wrong
                                    << ", float wrong " << wrong_float << "; hull-ball pairs "
                                    << hull_pairs << ", double with the exact mode's iterations "
                                    << same_iterations);
  BOOST_TEST(n > 7000);
  BOOST_TEST(hits > n * 0.3);
  BOOST_TEST(hits < n * 0.7);
  BOOST_TEST(wrong == 0);
  BOOST_TEST(wrong_float == 0);
  // The scaled poles steer as the exact mode's unscaled ones (lune_direction_ignores_pole_lengths):
  // on hull-ball pairs the iterations differ only where rounding tips a sign (1.6 % here, most
  // of them segments and triangles; 6.1 % with GJK's lune direction, which weighs pole
  // lengths). Ball-ball pairs are left out: every intersecting one has a support point
  // parallel to the centres' difference in exact arithmetic, which rounding tips either way.
  BOOST_TEST(same_iterations > hull_pairs * 0.97);
}

// After any sequence of clips, every cached vertex lies on the boundary of the region and
// inside every other hemisphere, and the centre lies strictly inside.
BOOST_AUTO_TEST_CASE(spherical_polygon_invariants) {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g;
  int polygons = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    detail::SphericalPolygon<double, true> poly;
    auto makePole = [&](const Vec3d& v) {
      detail::Pole<double> p;
      p.hi = v;
      p.lo.setZero();
      p.norm = v.norm();
      return p;
    };
    const Vec3d target = Vec3d(g(rng), g(rng), g(rng)).normalized();  // stays separating
    auto randomPole = [&]() {
      for (;;) {
        const Vec3d v(g(rng), g(rng), g(rng));
        if (v.dot(target) < -0.05 * v.norm()) return v;
      }
    };
    poly.init(makePole(randomPole()));
    for (int k = 0; k < 12; ++k) {
      const auto res = poly.clip(makePole(randomPole()));
      BOOST_TEST((res != detail::ClipResult::kEmpty));  // target is inside every hemisphere
      const Vec3d c = poly.center();
      for (int j = 0; j < poly.size(); ++j) BOOST_TEST(c.dot(poly.pole(j).hi) < 0);
      if (poly.size() >= 3) {
        ++polygons;
        for (int i = 0; i < poly.size(); ++i) {
          const Vec3d v = poly.pole(i).hi.cross(poly.pole((i + 1) % poly.size()).hi);
          for (int j = 0; j < poly.size(); ++j)
            BOOST_TEST(v.dot(poly.pole(j).hi) <= 1e-12 * v.norm() * poly.pole(j).norm);
        }
      }
    }
  }
  BOOST_TEST(polygons > 1000);
}

// A lune whose poles are nearly opposite is a thin wedge; its centre must stay strictly
// inside however thin it is (the sum -(p0/|p0| + p1/|p1|) cancels there, and with approximate
// normalisation it left the lune: DSS then stalled until its cap on one tetrahedron pair in
// 10^8). Poles at angles pi - eps from each other, eps from 1e-1 down to 1e-10 in double and
// 1e-5 in float (below that the poles are opposite within float rounding), random scales.
template <class W>
void checkThinLunes(double min_log_eps) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> scale(-3, 3);
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3d a = Vec3d(g(rng), g(rng), g(rng)).normalized();
    Vec3d perp = a.cross(Vec3d(g(rng), g(rng), g(rng))).normalized();
    const double eps = std::pow(10.0, -1.0 - (min_log_eps - 1.0) * (trial % 100) / 99.0);
    const Vec3d b = -(std::cos(eps) * a + std::sin(eps) * perp);
    auto pole = [&](const Vec3d& v) {
      detail::Pole<W, false> p;  // the plain modes' pole: hi only
      p.hi = (v * std::pow(10.0, scale(rng))).template cast<W>();
      return p;
    };
    detail::SphericalPolygon<W, false> poly;
    poly.init(pole(a));
    const auto q = pole(b);
    if (poly.clip(q) != detail::ClipResult::kChanged || poly.size() != 2) continue;
    const Vec3<W> c = poly.center();
    ++checked;
    BOOST_TEST_REQUIRE(c.dot(poly.pole(0).hi) < W(0), "eps " << eps);
    BOOST_TEST_REQUIRE(c.dot(poly.pole(1).hi) < W(0), "eps " << eps);
  }
  BOOST_TEST(checked > 2000);
}

BOOST_AUTO_TEST_CASE(thin_lune_centre_stays_inside) {
  checkThinLunes<double>(10);
  checkThinLunes<float>(5);
}

// A lune's next direction depends on its poles' directions only, not on their lengths: the
// double mode's ball test keeps |n| times the support point as a pole (dss.h), and the exact
// mode keeps the support point itself; both must steer alike. Random lunes up to 150 degrees
// wide (thinner ones may take the centerLune fallback, whose approximate normalisation is only
// good to 1e-3), poles rescaled by 10^-6 to 10^6: the directions agree to 1e-12.
BOOST_AUTO_TEST_CASE(lune_direction_ignores_pole_lengths) {
  std::mt19937_64 rng(12);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> scale(-6, 6);
  int checked = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const Vec3d a = Vec3d(g(rng), g(rng), g(rng)).normalized();
    const Vec3d b = Vec3d(g(rng), g(rng), g(rng)).normalized();
    if (a.dot(b) < std::cos(150.0 / 180.0 * std::acos(-1.0))) continue;
    auto direction = [&](double sa, double sb) {
      detail::Pole<double, false> p, q;
      p.hi = a * sa;
      q.hi = b * sb;
      detail::SphericalPolygon<double, false> poly;
      poly.init(p);
      BOOST_TEST_REQUIRE((poly.clip(q) == detail::ClipResult::kChanged));
      const Vec3d n = poly.center();
      BOOST_TEST_REQUIRE(n.dot(a) < 0);
      BOOST_TEST_REQUIRE(n.dot(b) < 0);
      return n.normalized();
    };
    const Vec3d n1 = direction(1, 1);
    const Vec3d n2 = direction(std::pow(10.0, scale(rng)), std::pow(10.0, scale(rng)));
    BOOST_TEST_REQUIRE(n1.cross(n2).norm() < 1e-12, "trial " << trial);
    ++checked;
  }
  BOOST_TEST(checked > 4000);
}

BOOST_AUTO_TEST_SUITE_END()

// The hull scan (SIMD lanes over coordinate arrays padded with copies of the last point)
// returns exactly what a plain linear scan returns: the first index of the largest d.x, for
// every size around the lane widths, ties included (duplicated points, integer grids), in
// double and float; NaN directions give index 0 as the plain scan does.
template <class T>
void checkScanAgainstLinear(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> coord(-3, 3);  // small integers: many exact ties
  std::normal_distribution<double> normal;
  for (int n = 1; n <= 37; ++n) {
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<Vec3<T>> pts;
      for (int i = 0; i < n; ++i) {
        if (trial % 2 == 0)
          pts.emplace_back(T(coord(rng)), T(coord(rng)), T(coord(rng)));
        else
          pts.emplace_back(T(normal(rng)), T(normal(rng)), T(normal(rng)));
      }
      if (n > 2 && trial % 5 == 0) pts[n - 1] = pts[0];  // duplicate of the first point
      const ConvexHullT<T> hull(pts);
      for (int k = 0; k < 12; ++k) {
        const Vec3<T> d = (k % 3 == 0) ? Vec3<T>(T(coord(rng)), T(coord(rng)), T(coord(rng)))
                                       : Vec3<T>(T(normal(rng)), T(normal(rng)), T(normal(rng)));
        int expect = 0;
        T best = pts[0].dot(d);
        for (int i = 1; i < n; ++i)
          if (pts[i].dot(d) > best) best = pts[i].dot(d), expect = i;
        BOOST_TEST_REQUIRE(hull.supportIndex(d) == expect, "n=" << n << " trial=" << trial);
        BOOST_TEST_REQUIRE((hull.support(d, Vec3<T>::Zero()) == pts[expect]));
      }
      const T nan = std::numeric_limits<T>::quiet_NaN();
      BOOST_TEST(hull.supportIndex(Vec3<T>(nan, T(1), T(0))) == 0);
    }
  }
}

BOOST_AUTO_TEST_CASE(hull_scan_matches_linear_scan) {
  std::mt19937_64 rng(20261124);
  checkScanAgainstLinear<double>(rng);
  checkScanAgainstLinear<float>(rng);
}
