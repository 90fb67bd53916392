// PointBlocks: the scans, four points at a time, on the instruction set picked at run time.
#include "dss/planning/point_blocks.h"

#include <algorithm>
#include <cmath>
#include <cstring>

// (Every function here that passes a 32-byte vector is inlined: see block_distances.h.)
#pragma GCC diagnostic ignored "-Wpsabi"
#include "block_distances.h"

namespace dss {

namespace {

using detail::blockQuad;
using detail::Quad;

__attribute__((always_inline)) inline std::size_t nearestQuad(const double* data,
                                                              std::size_t blocks, unsigned dim,
                                                              const double* q, double& best) {
  std::size_t best_i = PointBlocks::kNone;
  for (std::size_t b = 0; b < blocks; ++b, data += std::size_t(dim) * 4) {
    const Quad dist = blockQuad(data, q, dim);
    const auto below = dist < best;  // false for NaN
    if (!(below[0] | below[1] | below[2] | below[3])) continue;
    for (int l = 0; l < 4; ++l)
      if (dist[l] < best) {
        best = dist[l];
        best_i = 4 * b + std::size_t(l);
      }
  }
  return best_i;
}

__attribute__((always_inline)) inline void distancesQuad(const double* data, std::size_t blocks,
                                                         unsigned dim, const double* q,
                                                         double* out) {
  for (std::size_t b = 0; b < blocks; ++b, data += std::size_t(dim) * 4) {
    const Quad dist = blockQuad(data, q, dim);
    std::memcpy(out + 4 * b, &dist, sizeof dist);
  }
}

DSS_TARGET_AVX2 std::size_t nearestAvx2(const double* data, std::size_t blocks, unsigned dim,
                                        const double* q, double& best) {
  return nearestQuad(data, blocks, dim, q, best);
}
DSS_TARGET_AVX2 void distancesAvx2(const double* data, std::size_t blocks, unsigned dim,
                                   const double* q, double* out) {
  distancesQuad(data, blocks, dim, q, out);
}

std::size_t nearestSse2(const double* data, std::size_t blocks, unsigned dim, const double* q,
                        double& best) {
  return nearestQuad(data, blocks, dim, q, best);
}
void distancesSse2(const double* data, std::size_t blocks, unsigned dim, const double* q,
                   double* out) {
  distancesQuad(data, blocks, dim, q, out);
}

// One point at a time, value by value.
void distancesScalar(const double* data, std::size_t blocks, unsigned dim, const double* q,
                     double* out) {
  for (std::size_t b = 0; b < blocks; ++b, data += std::size_t(dim) * 4)
    detail::blockScalar(data, q, dim, out + 4 * b);
}
std::size_t nearestScalar(const double* data, std::size_t blocks, unsigned dim, const double* q,
                          double& best) {
  std::size_t best_i = PointBlocks::kNone;
  double dist[4];
  for (std::size_t b = 0; b < blocks; ++b, data += std::size_t(dim) * 4) {
    distancesScalar(data, 1, dim, q, dist);
    for (int l = 0; l < 4; ++l)
      if (dist[l] < best) {
        best = dist[l];
        best_i = 4 * b + std::size_t(l);
      }
  }
  return best_i;
}

}  // namespace

PointBlocks::PointBlocks(unsigned dimension) : PointBlocks(dimension, activeSimdPath()) {}

PointBlocks::PointBlocks(unsigned dimension, SimdPath path, std::size_t tree_from)
    : dim_(dimension),
      path_(simdPathAvailable(path) ? path : bestSimdPath()),
      tree_from_(tree_from),
      tree_(dimension, path_) {}

void PointBlocks::push(const double* v) {
  if (n_ % 4 == 0)
    data_.resize(data_.size() + std::size_t(dim_) * 4, std::numeric_limits<double>::quiet_NaN());
  double* p = place(n_);
  for (unsigned d = 0; d < dim_; ++d) p[4 * d] = v[d];
  ++n_;
  if (tree_on_) {
    tree_.insert(n_ - 1, v);
  } else if (n_ >= tree_from_) {
    std::vector<double> w(dim_);
    for (std::size_t i = 0; i < n_; ++i) {
      get(i, w.data());
      tree_.insert(i, w.data());
    }
    tree_on_ = true;
  }
}

void PointBlocks::swapRemove(std::size_t i) {
  const std::size_t last = n_ - 1;
  if (tree_on_) tree_.swapRemove(i, last);
  double* to = place(i);
  double* from = place(last);
  for (unsigned d = 0; d < dim_; ++d) {
    to[4 * d] = from[4 * d];
    from[4 * d] = std::numeric_limits<double>::quiet_NaN();
  }
  --n_;
  if (n_ % 4 == 0) data_.resize(data_.size() - std::size_t(dim_) * 4);
}

void PointBlocks::get(std::size_t i, double* v) const {
  const double* p = place(i);
  for (unsigned d = 0; d < dim_; ++d) v[d] = p[4 * d];
}

std::size_t PointBlocks::nearest(const double* q) const {
  if (n_ == 0) return kNone;
  if (tree_on_) {
    const std::size_t i = tree_.nearest(q);
    return i == kNone ? 0 : i;
  }
  const std::size_t blocks = (n_ + 3) / 4;
  double best = std::numeric_limits<double>::infinity();
  std::size_t i = kNone;
  switch (path_) {
    case SimdPath::kAvx2:
      i = nearestAvx2(data_.data(), blocks, dim_, q, best);
      break;
    case SimdPath::kSse2:
      i = nearestSse2(data_.data(), blocks, dim_, q, best);
      break;
    case SimdPath::kScalar:
      i = nearestScalar(data_.data(), blocks, dim_, q, best);
      break;
  }
  return i == kNone ? 0 : i;
}

const double* PointBlocks::allDistances(const double* q) const {
  thread_local std::vector<double> out;
  const std::size_t blocks = (n_ + 3) / 4;
  if (out.size() < 4 * blocks) out.resize(4 * blocks);
  switch (path_) {
    case SimdPath::kAvx2:
      distancesAvx2(data_.data(), blocks, dim_, q, out.data());
      break;
    case SimdPath::kSse2:
      distancesSse2(data_.data(), blocks, dim_, q, out.data());
      break;
    case SimdPath::kScalar:
      distancesScalar(data_.data(), blocks, dim_, q, out.data());
      break;
  }
  return out.data();
}

void PointBlocks::nearestK(const double* q, std::size_t k, std::vector<Found>& out) const {
  out.clear();
  if (k == 0 || n_ == 0) return;
  if (tree_on_) return tree_.nearestK(q, k, out);
  const double* dist = allDistances(q);
  for (std::size_t i = 0; i < n_; ++i) detail::offerNearestK(out, k, dist[i], i);
  std::sort_heap(out.begin(), out.end());
}

void PointBlocks::withinRadius(const double* q, double radius, std::vector<Found>& out) const {
  out.clear();
  if (n_ == 0) return;
  if (tree_on_) return tree_.withinRadius(q, radius, out);
  const double* dist = allDistances(q);
  for (std::size_t i = 0; i < n_; ++i)
    if (std::sqrt(dist[i]) <= radius) out.emplace_back(dist[i], i);
  std::sort(out.begin(), out.end());
}

}  // namespace dss
