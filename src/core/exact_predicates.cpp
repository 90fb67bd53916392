// Exact sign evaluation with floating-point expansions (Shewchuk 1997, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates"): an expansion is a sum of
// doubles with non-overlapping magnitudes, kept in increasing order; its sign is the sign of
// its largest component.
#include "dss/core/exact_predicates.h"

#include <cassert>
#include <cmath>

namespace dss::exact {
namespace {

constexpr int kCapacity = 256;  // det3 of two-term entries needs at most 6 * 32 = 192

struct Expansion {
  double c[kCapacity];
  int n = 0;
  Expansion() = default;
  // Copies only the live components: the arrays are large and mostly unused.
  Expansion(const Expansion& o) : n(o.n) {
    for (int i = 0; i < n; ++i) c[i] = o.c[i];
  }
  Expansion& operator=(const Expansion& o) {
    n = o.n;
    for (int i = 0; i < n; ++i) c[i] = o.c[i];
    return *this;
  }
};

inline void twoSum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

inline void twoProd(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}

// x + y = a + b exactly, given |a| >= |b| (or a == 0).
inline void fastTwoSum(double a, double b, double& x, double& y) {
  x = a + b;
  y = b - (x - a);
}

// h = e + f by merging the components of both in increasing magnitude and carrying the sum
// along (Shewchuk's fast expansion sum, with zero elimination): linear in the lengths. Both
// inputs are non-overlapping and increasing (as every routine here leaves them), and the
// arithmetic is IEEE round-to-nearest-even, which the algorithm requires.
void sum(const Expansion& e, const Expansion& f, Expansion& h) {
  if (e.n == 0) {
    h = f;
    return;
  }
  if (f.n == 0) {
    h = e;
    return;
  }
  int i = 0, j = 0;
  // Next component in increasing magnitude.
  auto next = [&]() {
    if (j >= f.n || (i < e.n && std::abs(e.c[i]) <= std::abs(f.c[j]))) return e.c[i++];
    return f.c[j++];
  };
  h.n = 0;
  double q = next();
  double hh, qn;
  fastTwoSum(next(), q, qn, hh);
  q = qn;
  if (hh != 0.0) h.c[h.n++] = hh;
  while (i < e.n || j < f.n) {
    twoSum(q, next(), qn, hh);
    q = qn;
    if (hh != 0.0) h.c[h.n++] = hh;
  }
  if (q != 0.0 || h.n == 0) h.c[h.n++] = q;
}

void scale(const Expansion& e, double s, Expansion& h) {
  h.n = 0;
  if (e.n == 0) return;
  double q, hh;
  twoProd(e.c[0], s, q, hh);
  if (hh != 0.0) h.c[h.n++] = hh;
  for (int i = 1; i < e.n; ++i) {
    double p1, p0, sum1;
    twoProd(e.c[i], s, p1, p0);
    twoSum(q, p0, sum1, hh);
    if (hh != 0.0) h.c[h.n++] = hh;
    twoSum(p1, sum1, q, hh);
    // p1 + sum1 is exact as q + hh and |hh| is tiny: Shewchuk uses FAST-TWO-SUM here.
    if (hh != 0.0) h.c[h.n++] = hh;
  }
  if (q != 0.0 || h.n == 0) h.c[h.n++] = q;
}

void mul(const Expansion& e, const Expansion& f, Expansion& h) {
  h.n = 1;
  h.c[0] = 0.0;
  Expansion t, acc;
  for (int j = 0; j < f.n; ++j) {
    scale(e, f.c[j], t);
    sum(h, t, acc);
    h = acc;
  }
}

void negate(Expansion& e) {
  for (int i = 0; i < e.n; ++i) e.c[i] = -e.c[i];
}

int sign(const Expansion& e) {
  for (int i = e.n - 1; i >= 0; --i) {
    if (e.c[i] > 0.0) return 1;
    if (e.c[i] < 0.0) return -1;
  }
  return 0;
}

Expansion two(double h, double l) {
  Expansion e;
  // Normalise: h + l may not be non-overlapping if the caller passed arbitrary values.
  double x, y;
  twoSum(h, l, x, y);
  e.n = 0;
  if (y != 0.0) e.c[e.n++] = y;
  e.c[e.n++] = x;
  return e;
}

}  // namespace

int det3Sign(const double hi[3][3], const double lo[3][3]) {
  static constexpr int kPerm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                      {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
  // A filter first, on the leading parts alone: each lo is the rounding error of its hi, so
  // |lo| <= u |hi|, and the lo terms move the determinant by at most ((1 + u)^3 - 1) P where
  // P is the permanent of |hi|; the floating-point evaluation of det(hi) by cofactors errs by
  // at most about 5u P. Beyond 16u P (with margin, and far from underflow) the sign is sure.
  {
    const double(*m)[3] = hi;
    const double m0 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double m1 = m[1][0] * m[2][2] - m[1][2] * m[2][0];
    const double m2 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * m0 - m[0][1] * m1 + m[0][2] * m2;
    const double p0 = std::abs(m[1][1] * m[2][2]) + std::abs(m[1][2] * m[2][1]);
    const double p1 = std::abs(m[1][0] * m[2][2]) + std::abs(m[1][2] * m[2][0]);
    const double p2 = std::abs(m[1][0] * m[2][1]) + std::abs(m[1][1] * m[2][0]);
    const double perm = std::abs(m[0][0]) * p0 + std::abs(m[0][1]) * p1 + std::abs(m[0][2]) * p2;
    const double u = 1.1102230246251565e-16;  // 2^-53
    if (perm > 1e-280 && perm < 1e280 && std::abs(det) > 16 * u * perm) return det > 0 ? 1 : -1;
  }
  Expansion total;
  total.n = 1;
  total.c[0] = 0.0;
  for (int k = 0; k < 6; ++k) {
    const Expansion a = two(hi[0][kPerm[k][0]], lo[0][kPerm[k][0]]);
    const Expansion b = two(hi[1][kPerm[k][1]], lo[1][kPerm[k][1]]);
    const Expansion c = two(hi[2][kPerm[k][2]], lo[2][kPerm[k][2]]);
    Expansion ab, abc, next;
    mul(a, b, ab);
    mul(ab, c, abc);
    if (k >= 3) negate(abc);
    sum(total, abc, next);
    total = next;
  }
  return sign(total);
}

int cross2Sign(double axh, double axl, double ayh, double ayl, double bxh, double bxl, double byh,
               double byl) {
  Expansion p, q, r;
  mul(two(axh, axl), two(byh, byl), p);
  mul(two(ayh, ayl), two(bxh, bxl), q);
  negate(q);
  sum(p, q, r);
  return sign(r);
}

int dotSign(const double ph[3], const double pl[3], const double qh[3], const double ql[3]) {
  Expansion total, t, next;
  total.n = 1;
  total.c[0] = 0.0;
  for (int i = 0; i < 3; ++i) {
    mul(two(ph[i], pl[i]), two(qh[i], ql[i]), t);
    sum(total, t, next);
    total = next;
  }
  return sign(total);
}

int dotDiffSign(const double n[3], const double a[3], const double b[3]) {
  Expansion total, t, next;
  total.n = 1;
  total.c[0] = 0.0;
  for (int i = 0; i < 3; ++i) {
    double h, l;
    twoDiff(a[i], b[i], h, l);
    Expansion d = two(h, l);
    scale(d, n[i], t);
    sum(total, t, next);
    total = next;
  }
  return sign(total);
}

}  // namespace dss::exact
