// Exact signs of the few expressions the exact mode decides on.
//
// Every number that enters is a double; a coordinate of a support point of the Minkowski
// difference is kept as a two-term expansion hi + lo (hi = fl(a - b), lo its exact rounding
// error), so p = a - b is represented without loss. The signs are computed with Shewchuk-style
// floating-point expansions (two-sum, two-product with std::fma, zero-eliminating sums),
// which are exact for any IEEE doubles barring overflow and underflow. Callers use these
// only when a cheap floating-point filter cannot decide (rare), so speed is secondary; no
// heap allocation is made.
#pragma once

#include <cmath>

namespace dss::exact {

/// a - b = hi + lo exactly.
inline void twoDiff(double a, double b, double& hi, double& lo) {
  hi = a - b;
  const double bv = a - hi;
  const double av = hi + bv;
  lo = (a - av) + (bv - b);
}

/// Sign (-1, 0, +1) of det[r0; r1; r2] where row i is (hi[i] + lo[i]) componentwise.
int det3Sign(const double hi[3][3], const double lo[3][3]);

/// Sign of ax*by - ay*bx (the 2-D cross product of a and b) where each argument is the
/// two-term value h + l.
int cross2Sign(double axh, double axl, double ayh, double ayl, double bxh, double bxl, double byh,
               double byl);

/// Sign of (ph + pl) . (qh + ql).
int dotSign(const double ph[3], const double pl[3], const double qh[3], const double ql[3]);

/// Sign of n . (a - b) for doubles n, a, b.
int dotDiffSign(const double n[3], const double a[3], const double b[3]);

}  // namespace dss::exact
