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
#pragma once

#include <cmath>
#include <limits>

#include "dss/core/exact_predicates.h"
#include "dss/core/types.h"

namespace dss::detail {

/// A point of the Minkowski difference: hi is its floating-point value; in the exact mode lo
/// holds the rounding error of hi = fl(a - b), so that hi + lo = a - b exactly.
template <class W>
struct Pole {
  Vec3<W> hi;
  Vec3<W> lo;
  W norm;
};

enum class ClipResult { kChanged, kUnchanged, kEmpty, kOverflow };

template <class W, bool Exact>
class SphericalPolygon {
 public:
  static constexpr int kCapacity = 48;
  // Relative error bound of a sign computed from the cached vertex v_i = fl(p_i x p_{i+1}):
  // cross products and a dot product (about 10 u) plus the ignored lo parts (3 u); 16 u is
  // a safe margin. Below it the exact predicate decides.
  static constexpr W kFilter = W(16) * std::numeric_limits<W>::epsilon() / W(2);

  void init(const Pole<W>& p0) {
    poles_[0] = p0;
    count_ = 1;
  }
  int size() const { return count_; }
  const Pole<W>& pole(int i) const { return poles_[i]; }

  /// The next test direction (not normalised): a point inside the polygon.
  Vec3<W> center() const {
    if (count_ == 1) return -poles_[0].hi;
    if (count_ == 2) return -(poles_[0].hi / poles_[0].norm + poles_[1].hi / poles_[1].norm);
    Vec3<W> s = Vec3<W>::Zero();
    for (int i = 0; i < count_; ++i) s += unit_[i];
    return s;
  }

  ClipResult clip(const Pole<W>& q) {
    if (count_ == 1) return clipHemisphere(q);
    if (count_ == 2) return clipLune(q);
    return clipPolygon(q);
  }

 private:
  // Sign of det(a, b, q) given the cached fl cross product v = a x b and the bound |a||b|.
  static int detSign(const Vec3<W>& v, W bound, const Pole<W>& a, const Pole<W>& b,
                     const Pole<W>& q) {
    const W d = v.dot(q.hi);
    if constexpr (!Exact) {
      return (d > W(0)) - (d < W(0));
    } else {
      if (std::abs(d) > kFilter * bound * q.norm) return (d > W(0)) - (d < W(0));
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
  static int crossSign(const Pole<W>& a, const Pole<W>& b, int k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    if constexpr (!Exact) {
      const W m = a.hi[i] * b.hi[j] - a.hi[j] * b.hi[i];
      return (m > W(0)) - (m < W(0));
    } else {
      const W m = a.hi[i] * b.hi[j] - a.hi[j] * b.hi[i];
      if (std::abs(m) > kFilter * a.norm * b.norm) return (m > W(0)) - (m < W(0));
      return exact::cross2Sign(a.hi[i], a.lo[i], a.hi[j], a.lo[j], b.hi[i], b.lo[i], b.hi[j],
                               b.lo[j]);
    }
  }

  static int dotSign(const Pole<W>& a, const Pole<W>& b) {
    const W d = a.hi.dot(b.hi);
    if constexpr (!Exact) {
      return (d > W(0)) - (d < W(0));
    } else {
      if (std::abs(d) > kFilter * a.norm * b.norm) return (d > W(0)) - (d < W(0));
      const double ah[3] = {a.hi[0], a.hi[1], a.hi[2]}, al[3] = {a.lo[0], a.lo[1], a.lo[2]};
      const double bh[3] = {b.hi[0], b.hi[1], b.hi[2]}, bl[3] = {b.lo[0], b.lo[1], b.lo[2]};
      return exact::dotSign(ah, al, bh, bl);
    }
  }

  void setLune(const Pole<W>& a, const Pole<W>& b) {
    poles_[0] = a;
    poles_[1] = b;
    count_ = 2;
    vert_[0] = a.hi.cross(b.hi);
    bound_[0] = a.norm * b.norm;
  }

  ClipResult clipHemisphere(const Pole<W>& q) {
    const Pole<W>& p = poles_[0];
    const bool parallel = crossSign(p, q, 0) == 0 && crossSign(p, q, 1) == 0 &&
                          crossSign(p, q, 2) == 0;
    if (parallel) {
      // q = 0, or q opposite to p: the segment [p, q] in the difference holds the origin.
      if (dotSign(p, q) <= 0) return ClipResult::kEmpty;
      return ClipResult::kUnchanged;
    }
    setLune(p, q);
    return ClipResult::kChanged;
  }

  ClipResult clipLune(const Pole<W>& q) {
    const Pole<W> p0 = poles_[0], p1 = poles_[1];
    const int s = detSign(vert_[0], bound_[0], p0, p1, q);
    if (s > 0) {  // vertex p0 x p1 cut off: q goes between p0 and p1
      setPolygon3(p0, q, p1);
      return ClipResult::kChanged;
    }
    if (s < 0) {  // vertex p1 x p0 cut off
      setPolygon3(p0, p1, q);
      return ClipResult::kChanged;
    }
    // q in the plane of p0 and p1: q = alpha p0 + beta p1. Solve in the coordinate plane
    // where the minor a_k = (p0 x p1)_k is largest (and exactly non-zero).
    int k = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(vert_[0][c]) > std::abs(vert_[0][k])) k = c;
    int sk = crossSign(p0, p1, k);
    for (int c = 0; sk == 0 && c < 3; ++c) {
      k = c;
      sk = crossSign(p0, p1, k);
    }
    if (sk == 0) return ClipResult::kEmpty;  // cannot happen: a lune has independent poles
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

  void setPolygon3(const Pole<W>& a, const Pole<W>& b, const Pole<W>& c) {
    poles_[0] = a, poles_[1] = b, poles_[2] = c;
    count_ = 3;
    for (int i = 0; i < 3; ++i) cacheVertex(i, poles_[i], poles_[(i + 1) % 3]);
  }

  void cacheVertex(int i, const Pole<W>& a, const Pole<W>& b) {
    vert_[i] = a.hi.cross(b.hi);
    bound_[i] = a.norm * b.norm;
    const W n = vert_[i].norm();
    unit_[i] = n > W(0) ? Vec3<W>(vert_[i] / n) : Vec3<W>::Zero();
  }

  ClipResult clipPolygon(const Pole<W>& q) {
    bool keep[kCapacity];
    int kept = 0;
    for (int i = 0; i < count_; ++i) {
      const int j = i + 1 == count_ ? 0 : i + 1;
      keep[i] = detSign(vert_[i], bound_[i], poles_[i], poles_[j], q) < 0;
      kept += keep[i];
    }
    if (kept == 0) return ClipResult::kEmpty;
    if (kept == count_) return ClipResult::kUnchanged;
    // The removed vertices form one cyclic run [first, last]; poles first+1..last go away
    // and q joins poles first and last+1.
    int first = -1, last = -1, runs = 0;
    for (int i = 0; i < count_; ++i) {
      const int prev = i == 0 ? count_ - 1 : i - 1;
      const int next = i + 1 == count_ ? 0 : i + 1;
      if (!keep[i] && keep[prev]) first = i, ++runs;
      if (!keep[i] && keep[next]) last = i;
    }
    if (runs != 1) return ClipResult::kUnchanged;  // inconsistent float signs: no progress
    const int removed = last >= first ? last - first + 1 : last + count_ - first + 1;
    const int new_count = count_ - removed + 2;
    if (new_count > kCapacity) return ClipResult::kOverflow;
    // New cycle: q, poles last+1, ..., first (the kept chain, in order).
    Pole<W> poles[kCapacity];
    Vec3<W> vert[kCapacity], unit[kCapacity];
    W bound[kCapacity];
    poles[0] = q;
    int m = 1;
    for (int i = (last + 1) % count_;; i = (i + 1) % count_) {
      poles[m] = poles_[i];
      if (i != first) {  // vertex between old poles i and i+1 survives
        vert[m] = vert_[i], unit[m] = unit_[i], bound[m] = bound_[i];
      }
      ++m;
      if (i == first) break;
    }
    for (int i = 0; i < m; ++i) poles_[i] = poles[i];
    for (int i = 1; i < m - 1; ++i) vert_[i] = vert[i], unit_[i] = unit[i], bound_[i] = bound[i];
    count_ = m;
    cacheVertex(0, poles_[0], poles_[1]);        // q x p_{last+1}
    cacheVertex(m - 1, poles_[m - 1], poles_[0]);  // p_first x q
    return ClipResult::kChanged;
  }

  Pole<W> poles_[kCapacity];
  Vec3<W> vert_[kCapacity];  // vert_[i] = poles_[i] x poles_[i+1] (floating point)
  Vec3<W> unit_[kCapacity];  // vert_[i] normalised (zero if degenerate)
  W bound_[kCapacity];       // |poles_[i]| |poles_[i+1]|
  int count_ = 0;
};

}  // namespace dss::detail
