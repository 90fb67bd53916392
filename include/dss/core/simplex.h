// The point of a simplex (1 to 4 points) closest to the origin, with the simplex reduced to
// the smallest face that holds it: the inner step of GJK (Gilbert, Johnson and Keerthi 1988),
// written with Voronoi-region tests on the simplex's features. Used by decision GJK and by
// the first steps of the Hybrid.
#pragma once

#include "dss/core/types.h"

namespace dss::detail {

template <class W>
Vec3<W> closestOnSegment(Vec3<W>* s, int& n) {
  const Vec3<W> a = s[0], b = s[1];
  const Vec3<W> ab = b - a;
  const W t = -a.dot(ab);
  if (t <= W(0)) {
    n = 1;
    return a;
  }
  const W len2 = ab.dot(ab);
  if (t >= len2) {
    s[0] = b;
    n = 1;
    return b;
  }
  return a + ab * (t / len2);
}

template <class W>
Vec3<W> closestOnTriangle(Vec3<W>* s, int& n) {
  const Vec3<W> a = s[0], b = s[1], c = s[2];
  const Vec3<W> ab = b - a, ac = c - a;
  const W d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= W(0) && d2 <= W(0)) {
    n = 1;
    return a;
  }
  const W d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= W(0) && d4 <= d3) {
    s[0] = b;
    n = 1;
    return b;
  }
  const W vc = d1 * d4 - d3 * d2;
  if (vc <= W(0) && d1 >= W(0) && d3 <= W(0)) {
    n = 2;
    return a + ab * (d1 / (d1 - d3));
  }
  const W d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= W(0) && d5 <= d6) {
    s[0] = c;
    n = 1;
    return c;
  }
  const W vb = d5 * d2 - d1 * d6;
  if (vb <= W(0) && d2 >= W(0) && d6 <= W(0)) {
    s[1] = c;
    n = 2;
    return a + ac * (d2 / (d2 - d6));
  }
  const W va = d3 * d6 - d5 * d4;
  if (va <= W(0) && (d4 - d3) >= W(0) && (d5 - d6) >= W(0)) {
    s[0] = b;
    s[1] = c;
    n = 2;
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const W denom = W(1) / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

template <class W>
Vec3<W> closestOnTetrahedron(Vec3<W>* s, int& n) {
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  bool any_outside = false;
  W best_d2 = std::numeric_limits<W>::infinity();
  Vec3<W> best = Vec3<W>::Zero();
  Vec3<W> best_s[3];
  int best_n = 0;
  for (const auto& f : kFaces) {
    const Vec3<W>& a = s[f[0]];
    const Vec3<W> normal = (s[f[1]] - a).cross(s[f[2]] - a);
    const W side_origin = -normal.dot(a);
    const W side_other = normal.dot(s[f[3]] - a);
    if (side_origin * side_other >= W(0)) continue;  // origin on the inner side of this face
    any_outside = true;
    Vec3<W> tri[3] = {s[f[0]], s[f[1]], s[f[2]]};
    int m = 3;
    const Vec3<W> p = closestOnTriangle(tri, m);
    const W d2 = p.squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2, best = p, best_n = m;
      for (int i = 0; i < m; ++i) best_s[i] = tri[i];
    }
  }
  if (!any_outside) return Vec3<W>::Zero();  // origin inside: n stays 4
  for (int i = 0; i < best_n; ++i) s[i] = best_s[i];
  n = best_n;
  return best;
}

/// Closest point of conv(s[0..n)) to the origin; s and n are reduced to the supporting face.
template <class W>
Vec3<W> closestOnSimplex(Vec3<W>* s, int& n) {
  switch (n) {
    case 1:
      return s[0];
    case 2:
      return closestOnSegment(s, n);
    case 3:
      return closestOnTriangle(s, n);
    default:
      return closestOnTetrahedron(s, n);
  }
}

}  // namespace dss::detail
