// The squared distances of four points to a query at once: the kernel of PointBlocks' scans and
// of PointTree's buckets, which both keep points in blocks of four (block b, value d, lane l at
// (b * dim + d) * 4 + l); and the step both take to keep the k nearest.
//
// Quad is the compiler's vector of four doubles: one AVX register in a function compiled for
// AVX2, two SSE2 registers otherwise; the scalar path works lane by lane. Every path forms each
// difference, square and sum alone (no fused multiply-add), summed from the first value (0 + d0^2
// is d0^2 exactly, as OMPL's RealVectorStateSpace::distance sums from 0.0): the same distances
// to the bit.
//
// (GCC notes that a 32-byte vector is passed differently with AVX; every function here is
// inlined into its caller, and the callers compiled for AVX2 take and return only pointers,
// sizes and doubles. GCC reports the note at the end of a file, so including files silence it
// for the whole file with -Wpsabi.)
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

namespace dss {
namespace detail {

using Quad = double __attribute__((vector_size(32)));

__attribute__((always_inline)) inline Quad blockQuad(const double* block, const double* q,
                                                     unsigned dim) {
  Quad acc = {0.0, 0.0, 0.0, 0.0};
  for (unsigned d = 0; d < dim; ++d) {
    Quad v;
    std::memcpy(&v, block + 4 * d, sizeof v);
    const Quad diff = v - q[d];
    acc = acc + diff * diff;
  }
  return acc;
}

/// The same four squared distances, one point at a time, value by value.
inline void blockScalar(const double* block, const double* q, unsigned dim, double* out) {
  for (int l = 0; l < 4; ++l) {
    double acc = 0.0;
    for (unsigned d = 0; d < dim; ++d) {
      const double diff = block[4 * d + l] - q[d];
      acc += diff * diff;
    }
    out[l] = acc;
  }
}

/// One point offered to the k nearest so far, a max-heap in `out` of (squared distance, index)
/// pairs (ties ordered by index); a NaN distance counts as infinite. std::sort_heap gives them
/// nearest first.
inline void offerNearestK(std::vector<std::pair<double, std::size_t>>& out, std::size_t k, double d,
                          std::size_t i) {
  const std::pair<double, std::size_t> e{
      std::isnan(d) ? std::numeric_limits<double>::infinity() : d, i};
  if (out.size() < k) {
    out.push_back(e);
    std::push_heap(out.begin(), out.end());
  } else if (e < out.front()) {
    std::pop_heap(out.begin(), out.end());
    out.back() = e;
    std::push_heap(out.begin(), out.end());
  }
}

}  // namespace detail
}  // namespace dss
