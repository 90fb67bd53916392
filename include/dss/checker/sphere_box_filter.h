// The sphere-box filter of the sweep: a link's bounding sphere against the world boxes of the
// obstacles it is checked with, two boxes at a time. The boxes are stored as six arrays
// (lower x, y, z, upper x, y, z), padded to an even count with empty boxes.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "dss/scene/obstacle.h"

namespace dss {

class BoxSoa {
 public:
  BoxSoa() = default;
  explicit BoxSoa(const std::vector<Aabb>& boxes) {
    const std::size_t n = boxes.size();
    size_ = n;
    stride_ = n + (n & 1);  // the filter reads pairs
    // An empty box (lower +inf, upper -inf) is infinitely far from every point.
    const double inf = std::numeric_limits<double>::infinity();
    data_.assign(6 * stride_, 0.0);
    for (std::size_t i = 0; i < stride_; ++i)
      for (int a = 0; a < 3; ++a) {
        data_[a * stride_ + i] = i < n ? boxes[i].lower[a] : inf;
        data_[(3 + a) * stride_ + i] = i < n ? boxes[i].upper[a] : -inf;
      }
  }
  std::size_t size() const { return size_; }

  /// Bit i (i < n <= 64) set when box begin + i is not farther than sqrt(r2) from c, or when
  /// the distance is NaN: a set bit means "test further", so NaN is never a skip.
  std::uint64_t hits(std::size_t begin, std::size_t n, const Eigen::Vector3d& c, double r2) const {
    std::uint64_t hits = 0;
    const double* lx = data_.data() + begin;
    const double* ly = lx + stride_;
    const double* lz = ly + stride_;
    const double* ux = lz + stride_;
    const double* uy = ux + stride_;
    const double* uz = uy + stride_;
#if defined(__SSE2__)
    const __m128d cx = _mm_set1_pd(c.x()), cy = _mm_set1_pd(c.y()), cz = _mm_set1_pd(c.z());
    const __m128d zero = _mm_setzero_pd(), rr = _mm_set1_pd(r2);
    // max(0, t) keeps a NaN t (maxpd returns its second operand when one is NaN).
    auto axis = [&](const double* lo, const double* up, std::size_t i, __m128d ci) {
      const __m128d d = _mm_max_pd(_mm_sub_pd(ci, _mm_loadu_pd(up + i)),
                                   _mm_max_pd(zero, _mm_sub_pd(_mm_loadu_pd(lo + i), ci)));
      return _mm_mul_pd(d, d);
    };
    for (std::size_t i = 0; i < n; i += 2) {
      const __m128d d2 =
          _mm_add_pd(_mm_add_pd(axis(lx, ux, i, cx), axis(ly, uy, i, cy)), axis(lz, uz, i, cz));
      hits |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmpngt_pd(d2, rr))) << i;
    }
    return hits & (n == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << n) - 1);
#else
    for (std::size_t i = 0; i < n; ++i) {
      const double dx = std::max(0.0, std::max(lx[i] - c.x(), c.x() - ux[i]));
      const double dy = std::max(0.0, std::max(ly[i] - c.y(), c.y() - uy[i]));
      const double dz = std::max(0.0, std::max(lz[i] - c.z(), c.z() - uz[i]));
      if (!(dx * dx + dy * dy + dz * dz > r2)) hits |= std::uint64_t(1) << i;
    }
    return hits;
#endif
  }

 private:
  std::vector<double> data_;
  std::size_t size_ = 0;
  std::size_t stride_ = 0;
};

}  // namespace dss
