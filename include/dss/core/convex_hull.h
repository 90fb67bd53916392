// The convex hull of a finite point set, through its support function.
//
// One point, two points, coplanar sets and full 3-D sets all work: the support function of
// conv(V) is max over V, so no hull construction is needed for correctness. Few points are
// scanned linearly; for many points a caller that knows the hull's vertex adjacency (the
// robot loader computes it with qhull) can hand it over, and the support then hill-climbs
// along hull edges from a seed vertex looked up in a cube map of directions (6 faces of
// kSeedGrid x kSeedGrid cells, each holding the support vertex of its centre direction, so
// that a climb usually takes zero to two steps). `kHillClimbMinVertices` is where
// climbing starts to pay (measured by `dss_bench narrowphase --sweep`; FCL, coal and CGAL
// switch near 32; on our machines the scan still wins at 32 and they break even near 48).
//
// Points given in world coordinates are returned bit for bit by `support` (with a zero
// shift), so the exact mode decides such pairs exactly.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "dss/core/types.h"

namespace dss {

inline constexpr std::size_t kHillClimbMinVertices = 48;
inline constexpr int kSeedGrid = 8;

template <class T>
class ConvexHullT {
 public:
  static constexpr bool kExactVertices = std::is_same<T, double>::value;

  ConvexHullT() = default;

  /// A hull of the given points (at least one; all finite). Throws std::invalid_argument.
  explicit ConvexHullT(std::vector<Vec3<T>> points) : points_(std::move(points)) { finish(); }

  /// As above, with the vertex adjacency of the hull: neighbours[i] lists the vertices that
  /// share a hull edge with vertex i. Every point must be a hull vertex for climbing to be
  /// correct; the caller (a hull builder) guarantees it.
  ConvexHullT(std::vector<Vec3<T>> points, const std::vector<std::vector<int>>& neighbours)
      : points_(std::move(points)) {
    if (neighbours.size() != points_.size())
      throw std::invalid_argument("ConvexHull: adjacency size differs from vertex count");
    offsets_.reserve(points_.size() + 1);
    offsets_.push_back(0);
    for (const auto& nb : neighbours) {
      for (int j : nb) {
        if (j < 0 || static_cast<std::size_t>(j) >= points_.size())
          throw std::invalid_argument("ConvexHull: adjacency refers to a missing vertex");
        adjacency_.push_back(j);
      }
      offsets_.push_back(static_cast<int>(adjacency_.size()));
    }
    finish();
  }

  const std::vector<Vec3<T>>& points() const { return points_; }
  std::size_t size() const { return points_.size(); }
  bool climbs() const { return !offsets_.empty() && points_.size() >= kHillClimbMinVertices; }

  /// Index of a point maximising d·x (the first of equal values in a linear scan).
  int supportIndex(const Vec3<T>& d) const {
    return climbs() ? climb(d) : scan(d);
  }
  int scan(const Vec3<T>& d) const {
    // Coordinates are also kept as separate arrays: this loop is the hottest of the library.
    const int n = n_;
    const T* x = soa_.data();
    const T* y = x + n;
    const T* z = y + n;
    const T dx = d.x(), dy = d.y(), dz = d.z();
    int best = 0;
    T best_value = x[0] * dx + y[0] * dy + z[0] * dz;
    for (int i = 1; i < n; ++i) {
      const T v = x[i] * dx + y[i] * dy + z[i] * dz;
      if (v > best_value) {
        best_value = v;
        best = i;
      }
    }
    return best;
  }

  Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    return points_[supportIndex(d)] - shift;
  }
  Vec3<T> center() const { return center_; }
  Vec3<T> anchor() const { return Vec3<T>::Zero(); }
  T magnitude() const { return magnitude_; }

  template <class U>
  ConvexHullT<U> cast() const {
    ConvexHullT<U> out;
    out.points_.reserve(points_.size());
    for (const auto& p : points_) out.points_.push_back(p.template cast<U>());
    out.offsets_ = offsets_;
    out.adjacency_ = adjacency_;
    out.finish();
    return out;
  }

 private:
  template <class U>
  friend class ConvexHullT;

  void finish() {
    if (points_.empty()) throw std::invalid_argument("ConvexHull: no points");
    Vec3<T> sum = Vec3<T>::Zero();
    magnitude_ = T(0);
    for (const auto& p : points_) {
      if (!p.allFinite()) throw std::invalid_argument("ConvexHull: non-finite point");
      sum += p;
      magnitude_ = std::max(magnitude_, p.norm());
    }
    center_ = sum / T(points_.size());
    const std::size_t n = points_.size();
    n_ = static_cast<int>(n);
    soa_.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      soa_[i] = points_[i].x();
      soa_[n + i] = points_[i].y();
      soa_[2 * n + i] = points_[i].z();
    }
    // Seeds for climbing: the support vertex of the centre direction of every cube-map cell.
    seeds_.clear();
    if (offsets_.empty()) return;
    seeds_.resize(6 * kSeedGrid * kSeedGrid);
    for (int face = 0; face < 6; ++face) {
      const int k = face / 2, a = (k + 1) % 3, b = (k + 2) % 3;
      for (int i = 0; i < kSeedGrid; ++i)
        for (int j = 0; j < kSeedGrid; ++j) {
          Vec3<T> dir;
          dir[k] = (face % 2) ? T(-1) : T(1);
          dir[a] = T(-1) + T(2 * i + 1) / T(kSeedGrid);
          dir[b] = T(-1) + T(2 * j + 1) / T(kSeedGrid);
          seeds_[(face * kSeedGrid + i) * kSeedGrid + j] = scan(dir);
        }
    }
  }

  // The cube-map cell of d: its largest coordinate picks the face, the two others divided by
  // it the cell. Any vertex is a correct start; this one is usually the answer or next to it.
  int seed(const Vec3<T>& d) const {
    const T ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
    int k = 0;
    T m = ax;
    if (ay > m) k = 1, m = ay;
    if (az > m) k = 2, m = az;
    if (!(m > T(0)) || !(m < std::numeric_limits<T>::infinity())) return 0;  // zero, NaN, Inf
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    const T scale = T(0.5 * kSeedGrid) / m;
    int i = static_cast<int>((d[a] + m) * scale);
    int j = static_cast<int>((d[b] + m) * scale);
    i = i < 0 ? 0 : (i >= kSeedGrid ? kSeedGrid - 1 : i);
    j = j < 0 ? 0 : (j >= kSeedGrid ? kSeedGrid - 1 : j);
    const int face = 2 * k + (d[k] < T(0) ? 1 : 0);
    return seeds_[(face * kSeedGrid + i) * kSeedGrid + j];
  }

  int climb(const Vec3<T>& d) const {
    int best = seed(d);
    T best_value = points_[best].dot(d);
    // Strict increase only: terminates, and on a convex polytope a vertex with no better
    // neighbour maximises d·x up to rounding.
    for (;;) {
      int next = best;
      for (int e = offsets_[best]; e < offsets_[best + 1]; ++e) {
        const int j = adjacency_[e];
        const T v = points_[j].dot(d);
        if (v > best_value) {
          best_value = v;
          next = j;
        }
      }
      if (next == best) return best;
      best = next;
    }
  }

  std::vector<Vec3<T>> points_;
  std::vector<T> soa_;          // x..., y..., z... of points_
  int n_ = 0;
  std::vector<int> offsets_;    // CSR adjacency (empty: linear scan only)
  std::vector<int> adjacency_;
  Vec3<T> center_ = Vec3<T>::Zero();
  T magnitude_{0};
  std::vector<int> seeds_;      // cube map of climbing seeds (with adjacency only)
};

using ConvexHull = ConvexHullT<double>;

}  // namespace dss
