// The convex hull of a finite point set, through its support function.
//
// One point, two points, coplanar sets and full 3-D sets all work: the support function of
// conv(V) is max over V, so no hull construction is needed for correctness. Few points are
// scanned linearly; for many points a caller that knows the hull's vertex adjacency (the
// robot loader computes it with qhull) can hand it over, and the support then looks its
// direction up in a cube map (6 faces of kSeedGrid x kSeedGrid cells) built once:
//  - a cell whose four corner directions all have the same support vertex, each beating every
//    other vertex by a relative margin far above rounding, is certified: every direction in
//    the cell is a non-negative combination of its corners, so that vertex is the unique
//    maximiser for all of them (normal cones are convex), and the support returns it without
//    a single dot product;
//  - any other cell keeps the short list of vertices that beat its centre's support vertex b
//    somewhere in the (slightly grown) cell, max over d in the cell of (x - b).d >= 0: the
//    maximiser of every direction in the cell is among them, and the support takes the best
//    of them (2-4 dot products, no branch per vertex). A list longer than kMaxCandidates
//    (a hull with very many vertices) climbs along hull edges from b instead.
// On hulls like the Panda's links (about a hundred vertices) a third to a half of the cells
// are certified and most others list 2-4 vertices, which beats climbing from the centre's
// vertex. `kHillClimbMinVertices` is where climbing starts to beat the linear scan (`dss_bench
// narrowphase --sweep` measures it; FCL, coal and CGAL switch near 32).
//
// Points given in world coordinates are returned bit for bit by `support` (with a zero
// shift), so the exact mode decides such pairs exactly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "dss/core/types.h"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif

namespace dss {
namespace detail {

#if defined(__SSE2__) || defined(_M_X64)
template <class T>
inline constexpr std::size_t kScanLanes = std::is_same<T, float>::value
                                              ? 4
                                              : (std::is_same<T, double>::value ? 2 : 1);
#else
template <class T>
inline constexpr std::size_t kScanLanes = 1;
#endif

/// Index of the first of the points (x[i], y[i], z[i]), i < n, maximising the dot product with
/// (dx, dy, dz). The arrays hold `stride` entries, padded with copies of point n - 1.
template <class T>
DSS_INLINE int scanSoa(const T* x, int stride, int n, T dx, T dy, T dz) {
  (void)stride;
  int best = 0;
  T best_value = x[0] * dx + x[stride] * dy + x[2 * stride] * dz;
  for (int i = 1; i < n; ++i) {
    const T v = x[i] * dx + x[stride + i] * dy + x[2 * stride + i] * dz;
    if (v > best_value) {
      best_value = v;
      best = i;
    }
  }
  return best;
}

#if defined(__SSE2__) || defined(_M_X64)
// Two points per step, each lane keeping its own best value and index; the lanes then agree
// on the first index of the largest value, as the linear scan would. max(v, best) is exactly
// "v > best ? v : best" (MAXPD returns its second operand for equal values, for zeros of either
// sign and for a NaN): one instruction, where a compare-and-blend takes three.
DSS_INLINE int scanSoa(const double* x, int stride, int n, double dx, double dy, double dz) {
  (void)n;
  const double* y = x + stride;
  const double* z = y + stride;
  const __m128d DX = _mm_set1_pd(dx), DY = _mm_set1_pd(dy), DZ = _mm_set1_pd(dz);
  __m128d best =
      _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_loadu_pd(x), DX), _mm_mul_pd(_mm_loadu_pd(y), DY)),
                 _mm_mul_pd(_mm_loadu_pd(z), DZ));
  __m128d index = _mm_set_pd(1.0, 0.0);
  __m128d best_index = index;
  const __m128d two = _mm_set1_pd(2.0);
  for (int i = 2; i < stride; i += 2) {
    index = _mm_add_pd(index, two);
    const __m128d v = _mm_add_pd(
        _mm_add_pd(_mm_mul_pd(_mm_loadu_pd(x + i), DX), _mm_mul_pd(_mm_loadu_pd(y + i), DY)),
        _mm_mul_pd(_mm_loadu_pd(z + i), DZ));
    const __m128d gt = _mm_cmpgt_pd(v, best);
    best = _mm_max_pd(v, best);
    best_index = _mm_or_pd(_mm_and_pd(gt, index), _mm_andnot_pd(gt, best_index));
  }
  // Lane 1 wins when larger, or equal with a smaller index: decided without a branch.
  const __m128d v1 = _mm_unpackhi_pd(best, best), i1 = _mm_unpackhi_pd(best_index, best_index);
  const __m128d take = _mm_or_pd(_mm_cmpgt_sd(v1, best),
                                 _mm_and_pd(_mm_cmpeq_sd(v1, best), _mm_cmplt_sd(i1, best_index)));
  return static_cast<int>(
      _mm_cvtsd_f64(_mm_or_pd(_mm_and_pd(take, i1), _mm_andnot_pd(take, best_index))));
}

DSS_INLINE int scanSoa(const float* x, int stride, int n, float dx, float dy, float dz) {
  (void)n;
  const float* y = x + stride;
  const float* z = y + stride;
  const __m128 DX = _mm_set1_ps(dx), DY = _mm_set1_ps(dy), DZ = _mm_set1_ps(dz);
  __m128 best =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_loadu_ps(x), DX), _mm_mul_ps(_mm_loadu_ps(y), DY)),
                 _mm_mul_ps(_mm_loadu_ps(z), DZ));
  __m128 index = _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f);
  __m128 best_index = index;
  const __m128 four = _mm_set1_ps(4.0f);
  for (int i = 4; i < stride; i += 4) {
    index = _mm_add_ps(index, four);
    const __m128 v = _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(x + i), DX), _mm_mul_ps(_mm_loadu_ps(y + i), DY)),
        _mm_mul_ps(_mm_loadu_ps(z + i), DZ));
    const __m128 gt = _mm_cmpgt_ps(v, best);
    best = _mm_max_ps(v, best);
    best_index = _mm_or_ps(_mm_and_ps(gt, index), _mm_andnot_ps(gt, best_index));
  }
  // Pairwise reduction of the four lanes, without a branch: the larger value wins, and of
  // equal values the smaller index.
  auto reduce = [](__m128& v, __m128& i, __m128 v2, __m128 i2) {
    const __m128 take =
        _mm_or_ps(_mm_cmpgt_ps(v2, v), _mm_and_ps(_mm_cmpeq_ps(v2, v), _mm_cmplt_ps(i2, i)));
    v = _mm_or_ps(_mm_and_ps(take, v2), _mm_andnot_ps(take, v));
    i = _mm_or_ps(_mm_and_ps(take, i2), _mm_andnot_ps(take, i));
  };
  reduce(best, best_index, _mm_movehl_ps(best, best), _mm_movehl_ps(best_index, best_index));
  reduce(best, best_index, _mm_shuffle_ps(best, best, 1),
         _mm_shuffle_ps(best_index, best_index, 1));
  return static_cast<int>(_mm_cvtss_f32(best_index));
}
#endif

}  // namespace detail

inline constexpr std::size_t kHillClimbMinVertices = 48;
inline constexpr int kSeedGrid = 16;

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
  bool climbs() const { return climbs_; }
  /// Cube-map cells whose support vertex is certified (for tests and reports).
  std::size_t certifiedCells() const {
    return static_cast<std::size_t>(
        std::count_if(seeds_.begin(), seeds_.end(), [](int c) { return c < 0; }));
  }
  /// Cube-map cells with too many candidates, which climb (for tests and reports).
  std::size_t climbingCells() const {
    return static_cast<std::size_t>(std::count_if(seeds_.begin(), seeds_.end(),
                                                  [](int c) { return c >= 0 && (c & 0xff) == 0; }));
  }

  /// Index of a point maximising d·x (the first of equal values in a linear scan).
  DSS_INLINE int supportIndex(const Vec3<T>& d) const { return climbs() ? climb(d) : scan(d); }
  DSS_INLINE int scan(const Vec3<T>& d) const {
    // Coordinates are kept as separate arrays, padded to whole SIMD registers with copies of
    // the last point: this loop is the hottest of the library.
    return detail::scanSoa(soa_.data(), stride_, n_, d.x(), d.y(), d.z());
  }

  DSS_INLINE Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    // Climbing compares whole points: read the winner from there (one cache line, where the
    // three coordinate arrays would be three). The scan reads back from the coordinate arrays
    // it has just brought into cache.
    if (climbs()) return points_[climb(d)] - shift;
    const int i = scan(d);
    const T* x = soa_.data();
    return Vec3<T>(x[i], x[stride_ + i], x[2 * stride_ + i]) - shift;
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
      magnitude_ = std::max(magnitude_, p.stableNorm());  // no overflow at any scale
    }
    center_ = sum / T(points_.size());
    const std::size_t n = points_.size();
    n_ = static_cast<int>(n);
    constexpr std::size_t kLanes = detail::kScanLanes<T>;
    const std::size_t stride = (n + kLanes - 1) / kLanes * kLanes;
    stride_ = static_cast<int>(stride);
    soa_.resize(3 * stride);
    for (std::size_t i = 0; i < stride; ++i) {
      const Vec3<T>& p = points_[std::min(i, n - 1)];
      soa_[i] = p.x();
      soa_[stride + i] = p.y();
      soa_[2 * stride + i] = p.z();
    }
    climbs_ = !offsets_.empty() && n >= kHillClimbMinVertices;
    // Seeds for climbing: the support vertex of the centre direction of every cube-map cell,
    // or -1 - v for a cell certified to have support vertex v throughout (see the top).
    seeds_.clear();
    candidates_.clear();
    if (offsets_.empty()) return;
    seeds_.resize(6 * kSeedGrid * kSeedGrid);
    constexpr int G = kSeedGrid;
    auto direction = [](int face, T u, T w) {
      const int k = face / 2, a = (k + 1) % 3, b = (k + 2) % 3;
      Vec3<T> dir;
      dir[k] = (face % 2) ? T(-1) : T(1);
      dir[a] = u;
      dir[b] = w;
      return dir;
    };
    // Support vertex of each corner direction, or -1 when its margin over the runner-up is
    // not clearly above rounding.
    const T margin = T(std::is_same<T, float>::value ? 1e-4 : 1e-9) * (magnitude_ + T(1e-30));
    std::vector<int> corner(6 * (G + 1) * (G + 1), -1);
    for (int face = 0; face < 6; ++face)
      for (int i = 0; i <= G; ++i)
        for (int j = 0; j <= G; ++j) {
          const Vec3<T> dir = direction(face, T(-1) + T(2 * i) / T(G), T(-1) + T(2 * j) / T(G));
          int best = 0;
          T first = -std::numeric_limits<T>::infinity(), second = first;
          for (std::size_t v = 0; v < n; ++v) {
            const T h = points_[v].dot(dir);
            if (h > first) {
              second = first;
              first = h;
              best = static_cast<int>(v);
            } else if (h > second) {
              second = h;
            }
          }
          // |dir| <= sqrt(3): the margin is relative to the hull's size times |dir|
          if (first - second > T(2) * margin) corner[(face * (G + 1) + i) * (G + 1) + j] = best;
        }
    for (int face = 0; face < 6; ++face)
      for (int i = 0; i < G; ++i)
        for (int j = 0; j < G; ++j) {
          auto c = [&](int di, int dj) {
            return corner[(face * (G + 1) + i + di) * (G + 1) + j + dj];
          };
          const int v = c(0, 0);
          int& cell = seeds_[(face * G + i) * G + j];
          if (v >= 0 && c(1, 0) == v && c(0, 1) == v && c(1, 1) == v) {
            cell = -1 - v;
            continue;
          }
          // Candidates: every vertex that beats the centre's support vertex b for some
          // direction of the (slightly grown) cell; the maximiser of any direction in the cell
          // is among them. Over the cell d = c + (0, du, dw) in face coordinates with
          // |du|, |dw| <= 1/G, so max (x - b).d = (x - b).c + (|x_a - b_a| + |x_b - b_b|) / G.
          const Vec3<T> centre =
              direction(face, T(-1) + T(2 * i + 1) / T(G), T(-1) + T(2 * j + 1) / T(G));
          const int b = scan(centre);
          const int k = face / 2, a1 = (k + 1) % 3, a2 = (k + 2) % 3;
          const T half = T(1.000001) / T(G);
          const T tol = T(1e-9) * (magnitude_ + T(1e-30));
          std::vector<int> list{b};
          for (std::size_t x = 0; x < n; ++x) {
            if (static_cast<int>(x) == b) continue;
            const Vec3<T> diff = points_[x] - points_[b];
            if (diff.dot(centre) + half * (std::abs(diff[a1]) + std::abs(diff[a2])) >= -tol)
              list.push_back(static_cast<int>(x));
          }
          if (list.size() == 1) {  // b beats every other vertex throughout the cell
            cell = -1 - b;
            continue;
          }
          if (list.size() > kMaxCandidates) list.resize(1);  // rare: climb from b instead
          cell = (static_cast<int>(candidates_.size()) << 8) |
                 static_cast<int>(list.size() == 1 ? 0 : list.size());
          candidates_.insert(candidates_.end(), list.begin(), list.end());
        }
  }

  // The first maximiser of d.x among the count (>= 2) candidates of a cell.
  DSS_INLINE int bestCandidate(const int* list, int count, const Vec3<T>& d) const {
    int best = list[0];
    T best_value = points_[best].dot(d);
    for (int k = 1; k < count; ++k) {
      const int j = list[k];
      const T v = points_[j].dot(d);
      const bool up = v > best_value;
      best = up ? j : best;
      best_value = up ? v : best_value;
    }
    return best;
  }

  // The cube-map entry of d's cell: its largest coordinate picks the face, the two others
  // divided by it the cell. Zero and non-finite directions get vertex 0.
  int seed(const Vec3<T>& d) const {
    const T ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
    int k = 0;
    T m = ax;
    if (ay > m) k = 1, m = ay;
    if (az > m) k = 2, m = az;
    if (!(m > T(0)) || !(m < std::numeric_limits<T>::infinity())) return -1;
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
    const int entry = seed(d);
    if (entry < 0) return -1 - entry;  // certified cell
    const int count = entry & 0xff;
    const int* list = candidates_.data() + (entry >> 8);
    if (count > 0) return bestCandidate(list, count, d);
    int best = list[0];  // too many candidates: climb from the centre's vertex
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
  std::vector<T> soa_;  // x..., y..., z... of points_, each padded to stride_
  int n_ = 0;
  int stride_ = 0;
  bool climbs_ = false;
  std::vector<int> offsets_;  // CSR adjacency (empty: linear scan only)
  std::vector<int> adjacency_;
  Vec3<T> center_ = Vec3<T>::Zero();
  T magnitude_{0};
  std::vector<int> seeds_;  // cube map (with adjacency only): -1 - vertex, or candidates
  // Candidate vertex lists of the uncertified cells (seeds_ holds offset << 8 | count).
  static constexpr std::size_t kMaxCandidates = 16;
  std::vector<int> candidates_;
};

using ConvexHull = ConvexHullT<double>;

}  // namespace dss
