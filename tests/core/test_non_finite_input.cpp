// A NaN or an infinity anywhere in a query on model shapes (any_shape_query.h,
// any_shape_sweep.h) answers "intersect" with status invalid_input, in every mode and at any
// iteration cap, including the numbers the search itself never meets: a ball's rotation, a
// cylinder's or cone's radius when every direction tried lies along its axis, the padding, the
// end pose of a sweep, and a zero iteration cap that stops before the first support. Found by
// fuzz/fuzz_core (a NaN sphere radius with a zero cap was answered iteration_limit).
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>

#include "dss/core/any_shape_query.h"
#include "dss/core/any_shape_sweep.h"

using namespace dss;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Vec3d(x, y, z);
  return X;
}

void expectInvalid(const Result& r, const char* what) {
  BOOST_TEST(r.intersect, what);
  BOOST_TEST((r.status == Status::kInvalidInput), what);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(non_finite_input)

BOOST_AUTO_TEST_CASE(every_number_of_a_query_is_checked) {
  for (const Mode mode : {Mode::kExact, Mode::kDouble, Mode::kFloat}) {
    for (const int cap : {0, 1, 64}) {
      Options opt;
      opt.mode = mode;
      opt.max_iterations = cap;
      // Far apart along z: without the check, the first direction would separate them.
      const Eigen::Isometry3d X_A = at(0, 0, 0), X_B = at(0, 0, 10);
      expectInvalid(intersect(Box::fromSize({1, 1, 1}), X_A, Sphere{kNan}, X_B, opt), "radius");
      Eigen::Isometry3d R_nan = X_B;
      R_nan.linear()(0, 1) = kNan;
      expectInvalid(intersect(Box::fromSize({1, 1, 1}), X_A, Sphere{1}, R_nan, opt),
                    "ball rotation");
      expectInvalid(intersect(Cylinder::fromLength(kInf, 1), X_A, Sphere{1}, X_B, opt),
                    "cylinder radius");
      expectInvalid(intersect(Cone::fromLength(kNan, 1), X_A, Sphere{1}, X_B, opt), "cone radius");
      expectInvalid(intersect(Capsule::fromLength(1, kNan), X_A, Sphere{1}, X_B, opt),
                    "capsule length");
      expectInvalid(intersect(Ellipsoid{{1, kInf, 1}}, X_A, Sphere{1}, X_B, opt), "ellipsoid");
      expectInvalid(intersect(Sphere{1}, X_A, Sphere{1}, at(0, kInf, 10), opt), "translation");
      expectInvalid(intersect(Sphere{1}, X_A, Sphere{1}, X_B, opt, kNan), "NaN padding");
      expectInvalid(intersect(Sphere{1}, X_A, Sphere{1}, X_B, opt, kInf), "infinite padding");
      expectInvalid(intersectSwept(Sphere{1}, X_A, at(0, kNan, 0), 0.0, Sphere{1}, X_B, opt),
                    "sweep end pose");
      expectInvalid(intersectSwept(Sphere{1}, X_A, X_A, kNan, Sphere{1}, X_B, opt),
                    "sweep padding");
      expectInvalid(intersectSwept(Sphere{1}, X_A, X_A, 0.0, Sphere{1}, X_B, R_nan, opt),
                    "second sweep end pose");
    }
  }
}

BOOST_AUTO_TEST_CASE(finite_queries_are_unchanged) {
  const Options opt;
  const Result apart = intersect(Sphere{1}, at(0, 0, 0), Sphere{1}, at(0, 0, 10), opt);
  BOOST_TEST(!apart.intersect);
  BOOST_TEST((apart.status == Status::kDecided));
  const Result padded = intersect(Sphere{1}, at(0, 0, 0), Sphere{1}, at(0, 0, 10), opt, 8.5);
  BOOST_TEST(padded.intersect);
  BOOST_TEST((padded.status == Status::kDecided));
}

BOOST_AUTO_TEST_SUITE_END()
