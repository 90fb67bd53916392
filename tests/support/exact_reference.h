// Exact references for the core tests: separating-axis tests on integer coordinates in
// 128-bit arithmetic (no rounding at all), and long-double analytic support values.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "dss/core/types.h"

namespace dss::test {

using I128 = __int128;
struct IVec {
  I128 x, y, z;
};
inline IVec sub(const IVec& a, const IVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline IVec cross(const IVec& a, const IVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline I128 dot(const IVec& a, const IVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline bool isZero(const IVec& a) { return a.x == 0 && a.y == 0 && a.z == 0; }

/// Does axis n separate the point sets strictly (max_A n.x < min_B n.x or the reverse)?
inline bool separates(const IVec& n, const std::vector<IVec>& a, const std::vector<IVec>& b) {
  if (isZero(n)) return false;
  I128 amin = dot(n, a[0]), amax = amin, bmin = dot(n, b[0]), bmax = bmin;
  for (const auto& p : a) {
    const I128 v = dot(n, p);
    amin = v < amin ? v : amin;
    amax = v > amax ? v : amax;
  }
  for (const auto& p : b) {
    const I128 v = dot(n, p);
    bmin = v < bmin ? v : bmin;
    bmax = v > bmax ? v : bmax;
  }
  return amax < bmin || bmax < amin;
}

/// Exact intersection of conv(a) and conv(b) for integer points (|coord| <= 2^40 for full 3-D
/// sets of four or more points, 2^20 otherwise), touching
/// counts. Candidate axes: every cross product of two difference vectors within a set (face
/// normals of any hull, including flat ones) and every cross of a difference vector of a with
/// one of b (edge-edge), plus the differences themselves for points and segments.
inline bool intersectExact(const std::vector<IVec>& a, const std::vector<IVec>& b) {
  std::vector<IVec> ea, eb;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = i + 1; j < a.size(); ++j) ea.push_back(sub(a[j], a[i]));
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t j = i + 1; j < b.size(); ++j) eb.push_back(sub(b[j], b[i]));
  std::vector<IVec> axes;
  for (const auto* e : {&ea, &eb})
    for (std::size_t i = 0; i < e->size(); ++i)
      for (std::size_t j = i + 1; j < e->size(); ++j) axes.push_back(cross((*e)[i], (*e)[j]));
  for (const auto& u : ea)
    for (const auto& v : eb) axes.push_back(cross(u, v));
  // Lower-dimensional configurations (points, segments, triangles): the connecting
  // directions and their crosses with the edges cover the remaining separating axes.
  // Only used with small coordinates (|coord| <= 2^20) so that nothing overflows.
  if (a.size() >= 4 && b.size() >= 4) {
    for (const auto& n : axes)
      if (separates(n, a, b)) return false;
    return true;
  }
  for (const auto& p : a)
    for (const auto& q : b) {
      const IVec d = sub(q, p);
      axes.push_back(d);
      for (const auto* e : {&ea, &eb})
        for (const auto& u : *e) {
          const IVec c = cross(u, d);
          axes.push_back(c);
          axes.push_back(cross(c, u));
        }
    }
  for (const auto& n : axes)
    if (separates(n, a, b)) return false;
  return true;
}

inline Vec3d toVec(const IVec& p, double scale, const Vec3d& offset) {
  return Vec3d(double(p.x) * scale, double(p.y) * scale, double(p.z) * scale) + offset;
}

}  // namespace dss::test
