// The decomposition's geometric vocabulary: points, boxes, half-spaces and the nearest point of
// a triangle.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dss::mesh::decomposition {

using Vec3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

inline bool lexLess(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

inline void sortUnique(std::vector<Vec3>& pts) {
  std::sort(pts.begin(), pts.end(), lexLess);
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
}

struct Box {
  Vec3 lo = Vec3::Constant(kInf);
  Vec3 hi = Vec3::Constant(-kInf);
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void add(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool empty() const { return !(lo.array() <= hi.array()).all(); }
  double diagonal() const { return empty() ? 0.0 : (hi - lo).norm(); }
  double distanceSq(const Vec3& p) const {
    return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
  }
  bool overlaps(const Box& b) const {
    return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all();
  }
};

/// The half-space n·x <= o.
struct Plane {
  Vec3 n;
  double o;
};

inline Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0.0)) return a;
  return a + std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) * ab;
}

// The projection onto the plane is used only when the triangle has an area well above rounding
// compared with its edges; slivers and repeated vertices take the nearest of the edges, which
// is then the exact answer up to the sliver's width.
inline Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 n = ab.cross(ac);
  const double n2 = n.squaredNorm();
  if (n2 > 1e-24 * ab.squaredNorm() * ac.squaredNorm()) {
    const Vec3 q = p - ((p - a).dot(n) / n2) * n;
    if (ab.cross(q - a).dot(n) >= 0.0 && (c - b).cross(q - b).dot(n) >= 0.0 &&
        (a - c).cross(q - c).dot(n) >= 0.0)
      return q;
  }
  Vec3 best = closestOnSegment(p, a, b);
  double best_d = (best - p).squaredNorm();
  for (const Vec3& q : {closestOnSegment(p, b, c), closestOnSegment(p, c, a)}) {
    const double d = (q - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = q;
    }
  }
  return best;
}

// Signed solid angle of triangle (a, b, c) seen from the origin (Van Oosterom and Strackee).
inline double solidAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double det = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(det, den);
}

}  // namespace dss::mesh::decomposition
