// The exact signs against arbitrary-precision rationals (boost::multiprecision), on random
// and on constructed singular and nearly singular inputs with non-zero rounding parts.
#include <boost/multiprecision/cpp_int.hpp>
#include <boost/test/unit_test.hpp>
#include <random>

#include "dss/core/exact_predicates.h"

using boost::multiprecision::cpp_rational;
using namespace dss;

namespace {

// Every double is a dyadic rational: exact conversion.
cpp_rational rat(double x) {
  int e;
  const double m = std::frexp(x, &e);
  const long long mi = static_cast<long long>(std::ldexp(m, 53));
  cpp_rational r(mi);
  const int shift = e - 53;
  if (shift >= 0)
    r *= cpp_rational(boost::multiprecision::cpp_int(1) << shift);
  else
    r /= cpp_rational(boost::multiprecision::cpp_int(1) << -shift);
  return r;
}

int sgn(const cpp_rational& r) { return r > 0 ? 1 : (r < 0 ? -1 : 0); }

}  // namespace

BOOST_AUTO_TEST_SUITE(exact_predicates)

BOOST_AUTO_TEST_CASE(two_diff_is_exact) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 10000; ++i) {
    const double a = u(rng) * std::ldexp(1.0, int(u(rng) * 60)),
                 b = u(rng) * std::ldexp(1.0, int(u(rng) * 60));
    double h, l;
    exact::twoDiff(a, b, h, l);
    BOOST_TEST((rat(h) + rat(l) == rat(a) - rat(b)));
  }
}

BOOST_AUTO_TEST_CASE(det3_matches_rationals_near_singular) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  int zeros = 0, n = 0;
  for (int i = 0; i < 3000; ++i) {
    // Rows as differences a - b of doubles at different scales, then the third row made
    // (nearly) a combination of the first two so that the determinant is tiny or zero.
    double a[3][3], b[3][3], hi[3][3], lo[3][3];
    for (int r = 0; r < 2; ++r)
      for (int k = 0; k < 3; ++k) {
        a[r][k] = u(rng) * 1e3;
        b[r][k] = u(rng) * 1e-3;
      }
    const double s = double(int(u(rng) * 8)), t = double(int(u(rng) * 8));
    for (int k = 0; k < 3; ++k) {
      a[2][k] = s * a[0][k] + t * a[1][k];  // rounded: nearly singular
      b[2][k] = s * b[0][k] + t * b[1][k];
      if (i % 3 == 0) a[2][k] = a[0][k], b[2][k] = b[0][k];  // exactly singular
    }
    cpp_rational m[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) {
        exact::twoDiff(a[r][k], b[r][k], hi[r][k], lo[r][k]);
        m[r][k] = rat(a[r][k]) - rat(b[r][k]);
      }
    const cpp_rational det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                             m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    BOOST_TEST(exact::det3Sign(hi, lo) == sgn(det));
    zeros += sgn(det) == 0;
    ++n;
  }
  BOOST_TEST(zeros >= 1000);
}

BOOST_AUTO_TEST_CASE(minor_dot_and_dot_diff) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 3000; ++i) {
    double h[4], l[4];
    cpp_rational v[4];
    for (int k = 0; k < 4; ++k) {
      const double a = u(rng) * 1e5, b = u(rng) * 1e-7;
      exact::twoDiff(a, b, h[k], l[k]);
      v[k] = rat(a) - rat(b);
    }
    // a = (v0, v1), b = (v2, v3); every other case b is a multiple of a (zero).
    if (i % 2) h[2] = h[0], l[2] = l[0], h[3] = h[1], l[3] = l[1], v[2] = v[0], v[3] = v[1];
    BOOST_TEST(exact::cross2Sign(h[0], l[0], h[1], l[1], h[2], l[2], h[3], l[3]) ==
               sgn(v[0] * v[3] - v[1] * v[2]));
    const double n[3] = {u(rng), u(rng), u(rng)};
    double p[3] = {u(rng) * 1e8, u(rng), u(rng)}, q[3] = {p[0], p[1], p[2]};
    q[i % 3] = std::nextafter(p[i % 3], 1e300);
    const cpp_rational ref = rat(n[0]) * (rat(p[0]) - rat(q[0])) +
                             rat(n[1]) * (rat(p[1]) - rat(q[1])) +
                             rat(n[2]) * (rat(p[2]) - rat(q[2]));
    BOOST_TEST(exact::dotDiffSign(n, p, q) == sgn(ref));
  }
}

BOOST_AUTO_TEST_SUITE_END()
