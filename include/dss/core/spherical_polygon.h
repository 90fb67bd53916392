// The search region of DSS: a convex spherical polygon that still contains every
// separating direction (Hornus 2017, section 4).
//
// It is stored as its poles: the support points p_i of the Minkowski difference whose open
// hemispheres {w : w.p_i < 0} it is the intersection of, in cyclic order. The vertex between
// poles i and i+1 is v_i = p_i x p_{i+1}, so classifying it against a new pole q is the sign
// of det(p_i, p_{i+1}, q) -- the one decision of the update, computed exactly in the exact
// mode. Special shapes: one pole (a hemisphere), two poles (a lune, whose two vertices are
// antipodal; a new pole coplanar with both narrows it to another lune, decided by the signs
// of q = alpha p_0 + beta p_1). Capacity is fixed: no allocation.
//
// Three sign policies, by the template flags Exact and Filter:
//   plain    (false, false): the floating-point sign of every determinant;
//   filtered (false, true):  the same signs, each checked against its rounding-error bound;
//                            any sign the bound cannot certify makes clip() answer kUnsure
//                            (the caller then reruns the whole query exactly). Poles carry
//                            hi only and the bounds use one scale M >= |p|_1 for every pole;
//   exact    (true, true):   poles carry their rounding error; a sign the filter cannot
//                            certify is computed exactly.
// A filtered search that never answers kUnsure took exactly the decisions of the exact one.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "dss/core/exact_predicates.h"
#include "dss/core/types.h"

#if (defined(__SSE__) || defined(_M_X64)) && !defined(DSS_NO_RSQRT)
#include <emmintrin.h>
#define DSS_HAVE_RSQRT 1
#endif

namespace dss::detail {

/// A point of the Minkowski difference: hi is its floating-point value; in the exact mode lo
/// holds the rounding error of hi = fl(a - b), so that hi + lo = a - b exactly. norm is an
/// upper bound of |hi| (its 1-norm: no square root on the hot path).
template <class W, bool Exact = true>
struct Pole {
  Vec3<W> hi;
  Vec3<W> lo;
  W norm;
};

/// The plain modes decide every sign from hi alone: their poles carry nothing else, so that
/// the polygon moves three values per pole instead of seven.
template <class W>
struct Pole<W, false> {
  Vec3<W> hi;
};

/// An approximation of 1/sqrt(x) for x > 0, to about 12 bits where the hardware has a
/// reciprocal square-root estimate (and x is in float range), else exact. It only scales
/// vertices and steering directions: every sign the search decides on is independent of the
/// (positive) scale, and the filter bounds are written in terms of the scale actually used.
template <class W>
DSS_INLINE W approxInvSqrt(W x) {
#ifdef DSS_HAVE_RSQRT
  if (x > W(1e-30) && x < W(1e30)) {
    if constexpr (std::is_same<W, double>::value) {
      // Packed conversions write whole registers: the scalar forms merge into a register's
      // old contents (a false dependency) and GCC routes _mm_set_ss through a general
      // register, both on the search's critical path.
      return _mm_cvtsd_f64(_mm_cvtps_pd(_mm_rsqrt_ps(_mm_cvtpd_ps(_mm_set1_pd(x)))));
    } else {
      return W(_mm_cvtss_f32(_mm_rsqrt_ps(_mm_set1_ps(static_cast<float>(x)))));
    }
  }
#endif
  return W(1) / std::sqrt(x);
}

enum class ClipResult { kChanged, kUnchanged, kEmpty, kOverflow, kUnsure };

// The polygon is aligned to a cache line and its poles start 48 bytes into one (lead_): the
// speed of the search depends on where the poles sit relative to a cache line, and without
// the alignment it would depend on where the stack happens to land.
template <class W, bool Exact, bool Filter = Exact>
class alignas(64) SphericalPolygon {
  static_assert(Filter || !Exact, "the exact policy filters its signs");
  static constexpr bool kOnlyFilter = Filter && !Exact;

 public:
  using PoleT = Pole<W, Exact>;
  static constexpr int kCapacity = 32;
  static constexpr W kUnit = std::numeric_limits<W>::epsilon() / W(2);

  void init(const PoleT& p0) {
    poles_[0] = p0;
    count_ = 1;
  }

  /// Filtered policy: m bounds |p|_1 for every pole that will enter (a point of the
  /// difference: the sum of the shapes' extents about the working frame's origin).
  void setScale(W m) {
    scale_ = m;
    scale2_ = W(8) * kUnit * m * m;
  }
  int size() const { return count_; }
  const PoleT& pole(int i) const { return poles_[i]; }

  /// The next test direction (not normalised): a point inside the polygon -- the sum of its
  /// unit vertices (the paper's renormalised average), or for a lune see directionLune.
  DSS_INLINE Vec3<W> center() const {
    if (count_ == 1) return neg3(poles_[0].hi);
    if (count_ == 2) return directionLune();
    Vec3<W> s = unit_[0];
    for (int i = 1; i < count_; ++i) s = sum3(s, unit_[i]);
    return s;
  }

  /// A direction inside the lune {w : w.p0 < 0, w.p1 < 0}, next to the middle of its boundary
  /// arc on p1's side (p1 is the newer pole when the lune comes from a hemisphere): b =
  /// (p0.p1) p1 - (p1.p1) p0 is that arc's midpoint (b.p1 = 0, b.p0 = -|p0 x p1|^2, |b| =
  /// |p1|^2 |p0| sin(theta), theta the angle between the poles), and -push p1 with push =
  /// |p0|_1 |p1|_1 / 64 moves it into the lune by an angle whose tangent is 1 to 3 times
  /// 1 / (64 sin(theta)) (1-norms: no square root, no division). The direction depends only on
  /// the poles' directions, not their lengths. When the hemisphere {w.c < 0} is cut by q, this
  /// is the previous direction -c turned just past the new plane {w.q = 0}, which takes fewer
  /// plane tests than GJK's direction (minus the point of [p0, p1] closest to the origin) or a
  /// larger push. In a lune thinner than the push (sin^2(theta) below 1/64 to 3/64 of |cos(theta)|:
  /// poles within 7 to 12 degrees of opposite) it leaves the lune; the floating-point check then
  /// hands over to centerLune.
  DSS_INLINE Vec3<W> directionLune() const {
    const Vec3<W>& p0 = poles_[0].hi;
    const Vec3<W>& p1 = poles_[1].hi;
    const W push = norm1_3(p0) * norm1_3(p1) * W(1.0 / 64);
    const Vec3<W> n = diff3(scaled3(p1, dot3(p0, p1) - push), scaled3(p0, dot3(p1, p1)));
    if (dot3(n, p0) < W(0) && dot3(n, p1) < W(0)) return n;
    return centerLune();
  }

  /// The middle of the lune {w : w.p0 < 0, w.p1 < 0}: a positive combination of two points of
  /// the closed lune, so that the approximate weights of approxInvSqrt cannot push it out.
  /// With p0.p1 >= 0 (a lune at least a quarter-sphere wide) -p0 and -p1 lie in it: the
  /// direction is -(p0/|p0| + p1/|p1|). Otherwise (a thin lune, poles nearly opposite, where
  /// that sum cancels) its two boundary arcs' midpoints p0 x v and v x p1 (v = p0 x p1) lie in
  /// it and do not cancel.
  DSS_INLINE Vec3<W> centerLune() const {
    const Vec3<W>& p0 = poles_[0].hi;
    const Vec3<W>& p1 = poles_[1].hi;
    const Vec3<W>& v = unit_[0];
    if (dot3(p0, p1) < W(0) && !isZero3(v)) {
      const Vec3<W> a = cross3(p0, v), b = cross3(v, p1);
      return sum3(scaled3(a, approxInvSqrt(dot3(a, a))), scaled3(b, approxInvSqrt(dot3(b, b))));
    }
    return neg3(
        sum3(scaled3(p0, approxInvSqrt(dot3(p0, p0))), scaled3(p1, approxInvSqrt(dot3(p1, p1)))));
  }

  /// An upper bound of |hi| without a square root.
  static DSS_INLINE W normBound(const Vec3<W>& v) { return norm1_3(v); }

  DSS_INLINE ClipResult clip(const PoleT& q) {
    const ClipResult r = count_ == 1   ? clipHemisphere(q)
                         : count_ == 2 ? clipLune(q)
                                       : clipPolygon(q);
    if constexpr (kOnlyFilter) {
      if (unsure_) return ClipResult::kUnsure;
    }
    return r;
  }

 private:
  // Sign of det(a, b, q) = (a x b).q from the cached unit vertex u = fl((a x b)/|a x b|) and
  // its error bound e: |u.q - det/|a x b|| <= e |q|_1 (filtered policy: e already holds the
  // factor M >= |q|_1). Below it the exact predicate decides, or the filtered search gives up.
  DSS_INLINE int detSign(const Vec3<W>& u, W e, const PoleT& a, const PoleT& b, const PoleT& q) {
    const W d = dot3(u, q.hi);
    if constexpr (!Filter) {
      return (d > W(0)) - (d < W(0));
    } else if constexpr (kOnlyFilter) {
      unsure_ |= !(std::abs(d) > e);
      return (d > W(0)) - (d < W(0));
    } else {
      if (std::abs(d) > e * q.norm) return (d > W(0)) - (d < W(0));
      double hi[3][3], lo[3][3];
      for (int k = 0; k < 3; ++k) {
        hi[0][k] = a.hi[k], lo[0][k] = a.lo[k];
        hi[1][k] = b.hi[k], lo[1][k] = b.lo[k];
        hi[2][k] = q.hi[k], lo[2][k] = q.lo[k];
      }
      return exact::det3Sign(hi, lo);
    }
  }

  // Sign of the k-th component of a x b (k = 0: a_y b_z - a_z b_y, ...).
  static int crossSign(const PoleT& a, const PoleT& b, int k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const W m = a.hi[i] * b.hi[j] - a.hi[j] * b.hi[i];
    if constexpr (Exact) {
      if (!(std::abs(m) > W(8) * kUnit * a.norm * b.norm))
        return exact::cross2Sign(a.hi[i], a.lo[i], a.hi[j], a.lo[j], b.hi[i], b.lo[i], b.hi[j],
                                 b.lo[j]);
    }
    return (m > W(0)) - (m < W(0));
  }

  static int dotSign(const PoleT& a, const PoleT& b) {
    const W d = dot3(a.hi, b.hi);
    if constexpr (Exact) {
      if (!(std::abs(d) > W(8) * kUnit * a.norm * b.norm)) {
        const double ah[3] = {a.hi[0], a.hi[1], a.hi[2]}, al[3] = {a.lo[0], a.lo[1], a.lo[2]};
        const double bh[3] = {b.hi[0], b.hi[1], b.hi[2]}, bl[3] = {b.lo[0], b.lo[1], b.lo[2]};
        return exact::dotSign(ah, al, bh, bl);
      }
    }
    return (d > W(0)) - (d < W(0));
  }

  // Unit vertex a x b and the bound of detSign. The error of fl(a x b) is at most about
  // 3u |a|_1 |b|_1 per component; normalising divides it by |a x b| and adds a few u; the
  // dot with q adds 3u; the ignored lo parts add 3u |a||b|. 8u (|a|_1 |b|_1 / |a x b| + 1)
  // covers all of it with margin. The filtered policy bounds |a|_1 |b|_1 |q|_1 by M^3.
  DSS_INLINE void cacheVertex(int i, const PoleT& a, const PoleT& b) {
    setUnit(i, cross3(a.hi, b.hi), a, b);
  }

  DSS_INLINE void setUnit(int i, const Vec3<W>& v, const PoleT& a, const PoleT& b) {
    W e = W(0);
    unitVertex(v, a, b, unit_[i], e);
    if constexpr (Filter) err_[i] = e;
  }

  // The unit vertex u of v = a x b and (filtering policies) its filter bound e.
  DSS_INLINE void unitVertex(const Vec3<W>& v, const PoleT& a, const PoleT& b, Vec3<W>& u,
                             W& e) const {
    (void)a, (void)b, (void)e;
    const W n2 = dot3(v, v);
    if (n2 > W(0)) {
      const W inv = approxInvSqrt(n2);  // u has norm 1 within 1e-3: see detSign's bound
      u = scaled3(v, inv);
      if constexpr (Exact) e = W(8) * kUnit * (a.norm * b.norm * inv + W(1));
      if constexpr (kOnlyFilter) e = (scale2_ * inv + W(8) * kUnit) * scale_;
    } else {
      u = Vec3<W>(W(0), W(0), W(0));
      if constexpr (Filter) e = std::numeric_limits<W>::infinity();  // always exact / unsure
    }
  }

  void setLune(const PoleT& a, const PoleT& b) {
    poles_[0] = a;
    poles_[1] = b;
    count_ = 2;
    cacheVertex(0, a, b);
  }

  DSS_INLINE ClipResult clipHemisphere(const PoleT& q) {
    const PoleT& p = poles_[0];
    const Vec3<W> v = cross3(p.hi, q.hi);
    // The floating-point cross product decides "not parallel" when a component clears its
    // rounding bound (3u |p|_1 |q|_1, doubled); otherwise the exact minors do.
    bool parallel;
    if constexpr (kOnlyFilter) {
      // Not parallel when a component clears the bound 8u M^2; otherwise give up.
      const W bound = scale2_;
      parallel = !(std::abs(v.x()) > bound || std::abs(v.y()) > bound || std::abs(v.z()) > bound);
      if (parallel) {
        unsure_ = true;
        return ClipResult::kUnchanged;
      }
    } else if constexpr (Exact) {
      const W bound = W(8) * kUnit * p.norm * q.norm;
      parallel = !(std::abs(v.x()) > bound || std::abs(v.y()) > bound || std::abs(v.z()) > bound) &&
                 crossSign(p, q, 0) == 0 && crossSign(p, q, 1) == 0 && crossSign(p, q, 2) == 0;
    } else {
      parallel = v.x() == W(0) && v.y() == W(0) && v.z() == W(0);
    }
    if (parallel) {
      // q = 0, or q opposite to p: the segment [p, q] in the difference holds the origin.
      if (dotSign(p, q) <= 0) return ClipResult::kEmpty;
      return ClipResult::kUnchanged;
    }
    poles_[1] = q;
    count_ = 2;
    setUnit(0, v, p, q);
    return ClipResult::kChanged;
  }

  DSS_INLINE ClipResult clipLune(const PoleT& q) {
    const PoleT p0 = poles_[0], p1 = poles_[1];
    const int s = detSign(unit_[0], err(0), p0, p1, q);
    if constexpr (kOnlyFilter) {
      if (s == 0) return ClipResult::kUnchanged;  // uncertified (unsure_ is set)
    }
    if (s != 0) {
      // Either triangle keeps the lune's vertex u01 = p0 x p1 (as itself or negated) and
      // gains two on the lines of c1 = p0 x q and c2 = q x p1 (fl(b x a) = -fl(a x b) bit for
      // bit, and so are their unit vectors and bounds):
      //   s > 0 (u01 cut off, q between p0 and p1): poles p0, q, p1; vertices c1, c2, -u01;
      //   s < 0 (-u01 cut off):                     poles p0, p1, q; vertices u01, -c2, -c1.
      // Both new vertices are computed before the side is known and the side only selects
      // (no branch on s: it is a coin toss for the predictor).
      Vec3<W> c1, c2;
      W e1 = W(0), e2 = W(0);
      unitVertex(cross3(p0.hi, q.hi), p0, q, c1, e1);
      unitVertex(cross3(q.hi, p1.hi), q, p1, c2, e2);
      const Vec3<W> u01 = unit_[0], n_u01 = neg3(u01), n_c1 = neg3(c1), n_c2 = neg3(c2);
      // Tables indexed by the side: loads, where a conditional would compile to a branch.
      const int cut = s > 0;
      const PoleT* const second[2] = {&p1, &q};
      const PoleT* const third[2] = {&q, &p1};
      const Vec3<W>* const v0[2] = {&u01, &c1};
      const Vec3<W>* const v1[2] = {&n_c2, &c2};
      const Vec3<W>* const v2[2] = {&n_c1, &n_u01};
      poles_[1] = *second[cut];
      poles_[2] = *third[cut];
      unit_[0] = *v0[cut];
      unit_[1] = *v1[cut];
      unit_[2] = *v2[cut];
      if constexpr (Filter) {
        const W e0[2] = {err_[0], e1}, e2s[2] = {e1, err_[0]};
        err_[0] = e0[cut];
        err_[1] = e2;
        err_[2] = e2s[cut];
      }
      count_ = 3;
      return ClipResult::kChanged;
    }
    // q in the plane of p0 and p1: q = alpha p0 + beta p1. Solve in the coordinate plane
    // where the minor a_k = (p0 x p1)_k is largest (and exactly non-zero).
    int k = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(unit_[0][c]) > std::abs(unit_[0][k])) k = c;
    int sk = crossSign(p0, p1, k);
    for (int c = 0; sk == 0 && c < 3; ++c) {
      k = c;
      sk = crossSign(p0, p1, k);
    }
    if (sk == 0) return ClipResult::kEmpty;   // cannot happen: a lune has independent poles
    const int sa = crossSign(q, p1, k) * sk;  // sign(alpha) = sign((q x p1)_k / (p0 x p1)_k)
    const int sb = crossSign(p0, q, k) * sk;  // sign(beta)  = sign((p0 x q)_k / (p0 x p1)_k)
    if (sa > 0 && sb > 0) return ClipResult::kUnchanged;
    if (sa <= 0 && sb <= 0) return ClipResult::kEmpty;
    if (sb > 0)
      setLune(p0, q);
    else
      setLune(q, p1);
    return ClipResult::kChanged;
  }

  DSS_INLINE W err(int i) const {
    if constexpr (Filter) return err_[i];
    return W(0);
  }

  DSS_INLINE void moveEntry(int to, int from) {
    poles_[to] = poles_[from];
    unit_[to] = unit_[from];
    if constexpr (Filter) err_[to] = err_[from];
  }

  DSS_INLINE ClipResult clipPolygon(const PoleT& q) {
    bool keep[kCapacity];
    int kept = 0;
    for (int i = 0; i < count_; ++i) {
      const int j = i + 1 == count_ ? 0 : i + 1;
      keep[i] = detSign(unit_[i], err(i), poles_[i], poles_[j], q) < 0;
      kept += keep[i];
    }
    if (kept == 0) return ClipResult::kEmpty;
    if (kept == count_) return ClipResult::kUnchanged;
    // The removed vertices form one cyclic run [first, last]: poles first+1..last go away
    // and q joins poles first and last+1.
    int first = -1, last = -1, runs = 0;
    for (int i = 0; i < count_; ++i) {
      const int prev = i == 0 ? count_ - 1 : i - 1;
      const int next = i + 1 == count_ ? 0 : i + 1;
      if (!keep[i] && keep[prev]) first = i, ++runs;
      if (!keep[i] && keep[next]) last = i;
    }
    if (runs != 1) return ClipResult::kUnchanged;  // inconsistent float signs: no progress
    if (first <= last) {
      // ... first | q | last+1 ... : entry i holds pole i and the vertex (pole i, pole i+1).
      const int removed = last - first;  // poles first+1..last
      const int new_count = count_ - removed + 1;
      if (new_count > kCapacity) return ClipResult::kOverflow;
      const int shift = 1 - removed;
      if (shift > 0) {
        for (int i = count_ - 1; i > last; --i) moveEntry(i + shift, i);
      } else if (shift < 0) {
        for (int i = last + 1; i < count_; ++i) moveEntry(i + shift, i);
      }
      count_ = new_count;
      poles_[first + 1] = q;
      cacheVertex(first, poles_[first], q);
      cacheVertex(first + 1, q, poles_[(first + 2) % count_]);
    } else {
      // The run wraps: the kept poles last+1..first are contiguous; move them to the front
      // and append q.
      const int keep_count = first - last;
      for (int i = 0; i < keep_count; ++i) moveEntry(i, last + 1 + i);
      count_ = keep_count + 1;
      poles_[keep_count] = q;
      cacheVertex(keep_count - 1, poles_[keep_count - 1], q);
      cacheVertex(keep_count, q, poles_[0]);
    }
    return ClipResult::kChanged;
  }

  char lead_[48];  // see the top of the class
  PoleT poles_[kCapacity];
  Vec3<W> unit_[kCapacity];        // unit vertex between poles i and i+1 (zero if degenerate)
  W err_[Filter ? kCapacity : 1];  // filter bound of detSign (filtering policies only)
  int count_ = 0;
  W scale_ = W(0), scale2_ = W(0);  // filtered policy: M and 8u M^2
  bool unsure_ = false;             // filtered policy: a sign the filter could not certify
};

}  // namespace dss::detail
