// The exact mode's promise at every scale: for every pair of shape types, pairs that are
// robustly intersecting or apart (the answer is the same with the first shape 1e-3 larger and
// smaller) keep their answer when every length is scaled by 2^k. Never "disjoint" for an
// intersecting pair at any k in [-1000, 1000]; every answer right where the inputs and their
// squares stay normal doubles. Hulls given by world vertices are decided exactly, so their
// answers do not change under vertex permutation, argument swap or power-of-two scaling, near
// contact included.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>

#include "dss/core/any_shape_query.h"
#include "dss/core/dss.h"

using namespace dss;

namespace {

// A shape of the given type with lengths in [0.1, 1], its hull vertices around the origin.
AnyShape randomShape(int type, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> len(0.1, 1.0), u(-1, 1);
  switch (type) {
    case 0:
      return Sphere{len(rng)};
    case 1:
      return Box::fromSize({len(rng), len(rng), len(rng)});
    case 2:
      return Capsule::fromLength(0.5 * len(rng), len(rng));
    case 3:
      return Cylinder::fromLength(0.5 * len(rng), len(rng));
    case 4:
      return Cone::fromLength(0.5 * len(rng), len(rng));
    case 5:
      return Ellipsoid{{len(rng), len(rng), len(rng)}};
    default: {
      std::vector<Vec3d> pts;
      for (int k = 0; k < 8; ++k) pts.push_back(0.6 * Vec3d(u(rng), u(rng), u(rng)));
      return ConvexHull(pts);
    }
  }
}

// Every length of the shape times 2^k (exact: only exponents change).
AnyShape scaled(const AnyShape& s, int k) {
  auto f = [k](double x) { return std::ldexp(x, k); };
  if (auto* x = std::get_if<Sphere>(&s)) return Sphere{f(x->radius)};
  if (auto* x = std::get_if<Box>(&s)) return Box{x->half.unaryExpr(f)};
  if (auto* x = std::get_if<Capsule>(&s)) return Capsule{f(x->radius), f(x->half_length)};
  if (auto* x = std::get_if<Cylinder>(&s)) return Cylinder{f(x->radius), f(x->half_length)};
  if (auto* x = std::get_if<Cone>(&s)) return Cone{f(x->radius), f(x->half_length)};
  if (auto* x = std::get_if<Ellipsoid>(&s)) return Ellipsoid{x->radii.unaryExpr(f)};
  std::vector<Vec3d> pts;
  for (const Vec3d& p : std::get<ConvexHull>(s).points()) pts.push_back(p.unaryExpr(f));
  return ConvexHull(pts);
}

Eigen::Isometry3d scaled(const Eigen::Isometry3d& X, int k) {
  Eigen::Isometry3d Y = X;
  Y.translation() = X.translation().unaryExpr([k](double x) { return std::ldexp(x, k); });
  return Y;
}

Eigen::Isometry3d randomPose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  X.translation() = spread * Vec3d(u(rng), u(rng), u(rng));
  return X;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scales)

BOOST_AUTO_TEST_CASE(exact_mode_at_every_power_of_two) {
  std::mt19937_64 rng(2024);
  const Options exact;
  int pairs = 0, intersecting = 0, false_disjoint = 0, wrong_in_range = 0, queries = 0;
  for (int ta = 0; ta < 7; ++ta) {
    for (int tb = 0; tb < 7; ++tb) {
      int kept = 0;
      for (int attempt = 0; attempt < 400 && kept < 6; ++attempt) {
        const AnyShape a = randomShape(ta, rng), b = randomShape(tb, rng);
        const Eigen::Isometry3d XA = randomPose(rng, 0.1), XB = randomPose(rng, 0.9);
        const bool truth = intersect(a, XA, b, XB, exact).intersect;
        // Robust: the same answer with A padded by 1e-3 and with B at 1e-3 from the truth's
        // side (A shrunk is not a shape operation: B moved 1 % farther away instead).
        if (intersect(a, XA, b, XB, exact, 1e-3).intersect != truth) continue;
        Eigen::Isometry3d XB_out = XB;
        XB_out.translation() =
            XA.translation() + (XB.translation() - XA.translation()) * (1 + 1e-2);
        if (intersect(a, XA, b, XB_out, exact).intersect != truth) continue;
        ++kept;
        ++pairs;
        intersecting += truth;
        for (int k = -1000; k <= 1000; k += 40) {
          const AnyShape ak = scaled(a, k), bk = scaled(b, k);
          const Eigen::Isometry3d XAk = scaled(XA, k), XBk = scaled(XB, k);
          for (int swap = 0; swap < 2; ++swap) {
            const Result r =
                swap ? intersect(bk, XBk, ak, XAk, exact) : intersect(ak, XAk, bk, XBk, exact);
            ++queries;
            if (truth && !r.intersect) {
              ++false_disjoint;
              BOOST_ERROR("types " << ta << "," << tb << " k " << k << (swap ? " swapped" : "")
                                   << ": an intersecting pair called disjoint");
            }
            // Inputs up to about 4 * 2^k and down to 0.05 * 2^k: they and their squares are
            // normal doubles for |k| <= 500.
            if (std::abs(k) <= 500 && r.intersect != truth) {
              ++wrong_in_range;
              BOOST_ERROR("types " << ta << "," << tb << " k " << k << (swap ? " swapped" : "")
                                   << ": answer " << r.intersect << " (" << toString(r.status)
                                   << ", " << r.iterations << " iterations), truth " << truth);
            }
          }
        }
      }
      BOOST_TEST(kept >= 4, "types " << ta << "," << tb << ": only " << kept << " robust pairs");
    }
  }
  BOOST_TEST_MESSAGE(pairs << " pairs (" << intersecting << " intersecting), " << queries
                           << " queries");
  BOOST_TEST(false_disjoint == 0);
  BOOST_TEST(wrong_in_range == 0);
  BOOST_TEST(intersecting > pairs / 5);
  BOOST_TEST(intersecting < pairs * 4 / 5);
}

// World-vertex hulls are decided exactly: near contact too, the answer cannot depend on the
// order of the vertices, on which hull comes first, or on a power-of-two scale.
BOOST_AUTO_TEST_CASE(world_hulls_invariant_under_permutation_swap_and_scale) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1, 1);
  const Options exact;
  int n = 0, hits = 0;
  for (int i = 0; i < 300; ++i) {
    std::vector<Vec3d> pa, pb;
    for (int k = 0; k < 6; ++k) pa.push_back(0.5 * Vec3d(u(rng), u(rng), u(rng)));
    for (int k = 0; k < 6; ++k) pb.push_back(0.5 * Vec3d(u(rng), u(rng), u(rng)));
    // Touching or nearly: B moved so that its lowest vertex along a random axis lands on A's
    // highest, then nudged by a few ulps either way.
    const Vec3d axis = Vec3d(u(rng), u(rng), u(rng)).normalized();
    const Vec3d top_a = *std::max_element(
        pa.begin(), pa.end(),
        [&](const Vec3d& x, const Vec3d& y) { return axis.dot(x) < axis.dot(y); });
    const Vec3d low_b = *std::min_element(
        pb.begin(), pb.end(),
        [&](const Vec3d& x, const Vec3d& y) { return axis.dot(x) < axis.dot(y); });
    const Vec3d shift = (top_a - low_b) + axis * ((i % 7 - 3) * 1e-15);
    for (auto& p : pb) p += shift;
    const ConvexHull A(pa), B(pb);
    const bool r = intersect(A, B, exact).intersect;
    ++n;
    hits += r;
    BOOST_TEST(intersect(B, A, exact).intersect == r, "swap, pair " << i);
    std::shuffle(pa.begin(), pa.end(), rng);
    std::shuffle(pb.begin(), pb.end(), rng);
    BOOST_TEST(intersect(ConvexHull(pa), ConvexHull(pb), exact).intersect == r,
               "permutation, pair " << i);
    for (int k : {-900, -300, -7, 11, 400, 950}) {
      std::vector<Vec3d> sa, sb;
      for (const auto& p : pa)
        sa.push_back(p.unaryExpr([k](double x) { return std::ldexp(x, k); }));
      for (const auto& p : pb)
        sb.push_back(p.unaryExpr([k](double x) { return std::ldexp(x, k); }));
      BOOST_TEST(intersect(ConvexHull(sa), ConvexHull(sb), exact).intersect == r,
                 "scale 2^" << k << ", pair " << i);
    }
  }
  BOOST_TEST(hits > n / 5);
  BOOST_TEST(hits < n * 4 / 5);
}

// The reported case: a sphere of radius 1e52 and a box whose centre is 0.71e52 from it.
BOOST_AUTO_TEST_CASE(large_sphere_and_box_intersect) {
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d XB = I;
  XB.translation() = Vec3d(-1e52, -1e52, 0);
  for (const Mode mode : {Mode::kExact, Mode::kDouble}) {
    Options opt;
    opt.mode = mode;
    BOOST_TEST(
        intersect(AnyShape(Sphere{1e52}), I, AnyShape(Box::fromSize({1e52, 1e52, 1e52})), XB, opt)
            .intersect,
        toString(mode));
  }
}

BOOST_AUTO_TEST_SUITE_END()
