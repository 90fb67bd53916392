// Building the clearance grid (see dss/checker/clearance_grid.h).
#include "dss/checker/clearance_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dss {

namespace {
// The obstacles as the grid measures them: the squared distance to an obstacle's world box,
// raised to that of its oriented box when the obstacle is turned and that is larger; and one
// bound, at a point c, on the rounding of every oriented-box distance (sqDistPointObb's error
// for any box: |t|_1 <= 3 |c|_max + sqrt(3) |b.c|).
class Measure {
 public:
  explicit Measure(const std::vector<Obb>& obbs) : obbs_(obbs) {
    for (const Obb& b : obbs)
      if (!b.axis_aligned) reach_ = std::max(reach_, std::sqrt(3.0) * b.c.norm() + b.h.sum());
  }
  /// `b2`: the squared distance from c to obstacle k's world box.
  double sqDistance(const Eigen::Vector3d& c, std::size_t k, double b2) const {
    if (turned(k)) {
      double error;
      const double o2 = sqDistPointObb(c, obbs_[k], &error);
      if (o2 > b2) b2 = o2;  // NaN: the world box's
    }
    return b2;
  }
  /// Whether obstacle k's oriented box can raise its world box's distance.
  bool turned(std::size_t k) const { return reach_ >= 0.0 && !obbs_[k].axis_aligned; }
  double rounding(const Eigen::Vector3d& c) const {
    return reach_ < 0.0 ? 0.0 : 1e-9 * (3.0 * c.cwiseAbs().maxCoeff() + reach_) + 1e-12;
  }

 private:
  const std::vector<Obb>& obbs_;
  double reach_ = -1.0;  // negative: no turned obstacle
};
// One row of voxels (centres cx[0 .. n), half size `half`) against one box: d2[x] = min(d2[x],
// the squared distance from the voxel to the world box (lx, ux along x; dy2 + dz2, the voxel's
// squared distances along the other axes)), and for a turned box (kTurned) the larger of that
// and the square of the oriented box's distance from the centre less `half_diagonal` (0 at
// least), with the centre's frame coordinates t_a = rx[a] (cx + px0) + ryz[a]. Two voxels at
// a time with SSE2; max and min as the scalar tail forms them (b < a ? a : b is max(a, b) for
// these finite values; an oriented distance that is NaN leaves the world box's, a NaN distance
// leaves d2 as it is).
template <bool kTurned>
void row(const double* cx, double* d2, int n, double half, double lx, double ux, double dy2,
         double dz2, double half_diagonal = 0.0, double px0 = 0.0, const double* rx = nullptr,
         const double* ryz = nullptr, const double* h = nullptr) {
  int x = 0;
#if defined(__SSE2__)
  const __m128d vlx = _mm_set1_pd(lx - half), vux = _mm_set1_pd(ux + half), vdy2 = _mm_set1_pd(dy2),
                vdz2 = _mm_set1_pd(dz2), zero = _mm_setzero_pd(), vpx0 = _mm_set1_pd(px0),
                sign = _mm_set1_pd(-0.0), vhd = _mm_set1_pd(half_diagonal);
  __m128d vrx[3], vryz[3], vh[3];
  if constexpr (kTurned)
    for (int a = 0; a < 3; ++a) {
      vrx[a] = _mm_set1_pd(rx[a]);
      vryz[a] = _mm_set1_pd(ryz[a]);
      vh[a] = _mm_set1_pd(h[a]);
    }
  for (; x + 2 <= n; x += 2) {
    const __m128d c = _mm_loadu_pd(cx + x);
    const __m128d dx = _mm_max_pd(_mm_max_pd(_mm_sub_pd(vlx, c), _mm_sub_pd(c, vux)), zero);
    __m128d v = _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), vdy2), vdz2);
    if constexpr (kTurned) {
      const __m128d px = _mm_add_pd(c, vpx0);
      __m128d o[3];
      for (int a = 0; a < 3; ++a) {
        const __m128d t = _mm_add_pd(_mm_mul_pd(vrx[a], px), vryz[a]);
        o[a] = _mm_max_pd(_mm_sub_pd(_mm_andnot_pd(sign, t), vh[a]), zero);
      }
      const __m128d ob2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(o[0], o[0]), _mm_mul_pd(o[1], o[1])),
                                     _mm_mul_pd(o[2], o[2]));
      const __m128d ob = _mm_max_pd(_mm_sub_pd(_mm_sqrt_pd(ob2), vhd), zero);
      v = _mm_max_pd(_mm_mul_pd(ob, ob), v);  // v when ob is NaN
    }
    _mm_storeu_pd(d2 + x, _mm_min_pd(v, _mm_loadu_pd(d2 + x)));  // d2 when v is NaN
  }
#endif
  for (; x < n; ++x) {
    const double dx = std::max(std::max((lx - half) - cx[x], cx[x] - (ux + half)), 0.0);
    double v = (dx * dx + dy2) + dz2;
    if constexpr (kTurned) {
      const double px = cx[x] + px0;
      const double o0 = std::max(std::abs(rx[0] * px + ryz[0]) - h[0], 0.0);
      const double o1 = std::max(std::abs(rx[1] * px + ryz[1]) - h[1], 0.0);
      const double o2 = std::max(std::abs(rx[2] * px + ryz[2]) - h[2], 0.0);
      const double ob = std::max(std::sqrt((o0 * o0 + o1 * o1) + o2 * o2) - half_diagonal, 0.0);
      v = ob * ob > v ? ob * ob : v;
    }
    d2[x] = v < d2[x] ? v : d2[x];
  }
}
}  // namespace

ClearanceGrid::ClearanceGrid(const Aabb& region, const std::vector<Aabb>& boxes,
                             const std::vector<Obb>& obbs, std::size_t max_voxels,
                             double min_voxel) {
  const Eigen::Vector3d extent = region.upper - region.lower;
  if (boxes.empty() || !extent.allFinite() || !(extent.minCoeff() >= 0.0) || max_voxels == 0 ||
      !(obbs.empty() || obbs.size() == boxes.size()))
    return;
  double size = std::max(min_voxel, std::cbrt(extent.prod() / static_cast<double>(max_voxels)));
  int n[3];
  for (;;) {  // round the counts up; grow the voxels until the total fits
    std::size_t total = 1;
    for (int a = 0; a < 3; ++a) {
      n[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / size)));
      total *= static_cast<std::size_t>(n[a]);
    }
    if (total <= max_voxels) break;
    size *= 1.05;
  }
  origin_ = region.lower;
  size_ = size;
  inv_size_ = 1.0 / size;
  for (int a = 0; a < 3; ++a) count_[a] = static_cast<unsigned>(n[a]);
  below_ = origin_ - Eigen::Vector3d::Constant(size);
  stride_y_ = static_cast<std::size_t>(n[0]);
  stride_z_ = stride_y_ * static_cast<std::size_t>(n[1]);
  bound_.assign(static_cast<std::size_t>(n[0]) * n[1] * n[2], 0);
  // The distance from the voxel (a cube) to a box's world box, exact for the two boxes; for a
  // turned obstacle also its oriented box's distance from the voxel's centre less half the
  // voxel's diagonal (every point of the voxel lies that close to the centre), when larger.
  // A margin far above the rounding of these few operations is taken off before rounding
  // down to the quantum, with that of the oriented-box distances.
  const double half = 0.5 * size;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * size;
  const Measure measure(obbs);
  // Row by row along x: each box's squared distance to the row's voxel centres in one pass
  // (the x part per voxel, the y and z parts once per row). A box whose distance to the row's
  // line already exceeds what a byte can hold (plus the half diagonal and every margin) cannot
  // lower any voxel of the row below the largest value, and is skipped.
  auto marginAt = [&](const Eigen::Vector3d& c) {
    return 1e-9 * (1.0 + c.cwiseAbs().maxCoeff() + half_diagonal) + measure.rounding(c);
  };
  std::vector<double> cx(static_cast<std::size_t>(n[0])), d2(static_cast<std::size_t>(n[0]));
  for (int x = 0; x < n[0]; ++x) cx[x] = origin_.x() + size * (x + 0.5);
  const double cx_max = std::max(std::abs(cx.front()), std::abs(cx.back()));
  std::size_t i = 0;
  for (int z = 0; z < n[2]; ++z) {
    const double cz = origin_.z() + size * (z + 0.5);
    for (int y = 0; y < n[1]; ++y, i += static_cast<std::size_t>(n[0])) {
      const double cy = origin_.y() + size * (y + 0.5);
      // The margins grow with |c|: the row's largest, at its farthest centre.
      const double saturated =
          256.0 * kQuantum + half_diagonal + 2.0 * marginAt(Eigen::Vector3d(cx_max, cy, cz));
      const double skip2 = saturated * saturated;
      std::fill(d2.begin(), d2.end(), std::numeric_limits<double>::infinity());
      for (std::size_t k = 0; k < boxes.size(); ++k) {
        const Aabb& b = boxes[k];
        const double dy =
            std::max(std::max((b.lower.y() - half) - cy, cy - (b.upper.y() + half)), 0.0);
        const double dz =
            std::max(std::max((b.lower.z() - half) - cz, cz - (b.upper.z() + half)), 0.0);
        const double dy2 = dy * dy, dz2 = dz * dz;
        if (dy2 + dz2 > skip2) continue;
        const double lx = b.lower.x(), ux = b.upper.x();
        if (measure.turned(k)) {
          // The larger of the distances to the world box and to the oriented box (a NaN of the
          // latter leaves the former). The oriented box's frame coordinates t_a = R(0, a) px +
          // (R(1, a) py + R(2, a) pz): only px varies along the row. Their rounding is far
          // below Measure::rounding's bound.
          const Obb& ob = obbs[k];
          const double py = cy - ob.c.y(), pz = cz - ob.c.z();
          double ryz[3], rx[3];
          for (int a = 0; a < 3; ++a) {
            ryz[a] = ob.R(1, a) * py + ob.R(2, a) * pz;
            rx[a] = ob.R(0, a);
          }
          row<true>(cx.data(), d2.data(), n[0], half, lx, ux, dy2, dz2, half_diagonal, -ob.c.x(),
                    rx, ryz, ob.h.data());
        } else {
          row<false>(cx.data(), d2.data(), n[0], half, lx, ux, dy2, dz2);
        }
      }
      for (int x = 0; x < n[0]; ++x) {
        const double lower = std::sqrt(d2[x]) - marginAt(Eigen::Vector3d(cx[x], cy, cz));
        if (!(lower > 0.0)) continue;  // also NaN
        bound_[i + static_cast<std::size_t>(x)] =
            static_cast<std::uint8_t>(std::min(255.0, std::floor(lower / kQuantum)));
      }
    }
  }
}

void ClearanceGrid::buildUpper(const std::vector<Obb>& boxes, double cap) {
  cells_.clear();
  if (bound_.empty()) return;
  std::vector<std::uint8_t> upper(bound_.size(), kUnknown);
  const auto store = [&] {
    cells_.resize(bound_.size());
    for (std::size_t i = 0; i < bound_.size(); ++i)
      cells_[i] = static_cast<std::uint16_t>(bound_[i] | (upper[i] << 8));
  };
  if (boxes.empty() || !(cap > 0.0) || !std::isfinite(cap)) return store();
  // The distance to a box is convex: over a voxel it is largest at a corner. A margin far
  // above the rounding of the corners, of the box frame and of voxel() (which may pick a
  // neighbour for a point within rounding of a face) is added before rounding up to the
  // quantum.
  const double half_diagonal = 0.5 * std::sqrt(3.0) * size_;
  const double stored = std::min(cap, (kUnknown - 1) * kQuantum);
  for (const Obb& b : boxes) {
    if (!b.R.allFinite() || !b.c.allFinite() || !b.h.allFinite() || !(b.h.minCoeff() >= 0.0))
      continue;
    // The voxels whose centres lie within `stored` plus the half diagonal of the box's world
    // box (a box at an angle reaches |R| h along each world axis).
    const Eigen::Vector3d reach = b.R.cwiseAbs() * b.h;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double grow = reach[a] + stored + half_diagonal + size_;
      const double l = std::floor((b.c[a] - grow - origin_[a]) * inv_size_);
      const double h = std::ceil((b.c[a] + grow - origin_[a]) * inv_size_);
      lo[a] = static_cast<int>(std::max(0.0, std::min(l, double(count_[a]))));
      hi[a] = static_cast<int>(std::max(0.0, std::min(h, double(count_[a]))));
    }
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int x = lo[0]; x < hi[0]; ++x) {
          const Eigen::Vector3d c = origin_ + size_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
          // The corners in the box's frame: its centre's coordinates plus or minus the half
          // voxel along each of the frame's axes.
          const Eigen::Vector3d t = b.R.transpose() * (c - b.c);
          const Eigen::Matrix3d half_voxel = 0.5 * size_ * b.R.transpose();
          double d2 = 0.0;
          for (int k = 0; k < 8; ++k) {
            const Eigen::Vector3d corner =
                t + half_voxel *
                        Eigen::Vector3d(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0);
            d2 = std::max(d2, (corner.cwiseAbs() - b.h).cwiseMax(0.0).squaredNorm());
          }
          const double margin = 1e-9 * (1.0 + 3.0 * c.cwiseAbs().maxCoeff() + 2.0 * b.c.norm() +
                                        b.h.sum() + half_diagonal) +
                                1e-12;
          const double bound = std::sqrt(d2) + margin;
          if (!(bound <= stored)) continue;
          std::uint8_t& u = upper[z * stride_z_ + y * stride_y_ + x];
          u = std::min(u, static_cast<std::uint8_t>(std::ceil(bound / kQuantum)));
        }
  }
  store();
}

void ClearanceGrid::buildCandidates(const std::vector<Aabb>& boxes, double radius,
                                    std::size_t max_bytes, const std::vector<Obb>& obbs) {
  words_ = 0;
  candidates_.clear();
  if (bound_.empty() || boxes.empty() || !(radius >= 0.0) || !std::isfinite(radius) ||
      !(obbs.empty() || obbs.size() == boxes.size()))
    return;
  for (const Aabb& b : boxes)
    if (!b.lower.allFinite() || !b.upper.allFinite()) return;
  const std::size_t words = (boxes.size() + 63) / 64;
  if (bound_.size() > max_bytes / (8 * words)) return;
  candidates_.assign(bound_.size() * words, 0);
  // A ball centred in a voxel lies within half the diagonal plus the radius of the centre; a
  // margin covers the rounding of the centre and of voxel(), which may pick a neighbour for a
  // point within rounding of a face.
  const double half_diagonal = 0.5 * std::sqrt(3.0) * size_;
  const double reach = radius + half_diagonal + 1e-6 * size_;
  const Measure measure(obbs);
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const Aabb& b = boxes[k];
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double l = std::floor((b.lower[a] - reach - origin_[a]) * inv_size_) - 1;
      const double h = std::ceil((b.upper[a] + reach - origin_[a]) * inv_size_) + 1;
      lo[a] = static_cast<int>(std::max(0.0, std::min(l, double(count_[a]))));
      hi[a] = static_cast<int>(std::max(0.0, std::min(h, double(count_[a]))));
    }
    const std::uint64_t bit = std::uint64_t(1) << (k % 64);
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int x = lo[0]; x < hi[0]; ++x) {
          const Eigen::Vector3d c = origin_ + size_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
          const double margin = 1e-9 * (1.0 + c.cwiseAbs().maxCoeff() + reach);
          const double r = reach + margin, r_obb = r + measure.rounding(c);
          const double b2 = detail::sqDistPointAabb(c, b);
          if (!(b2 <= r * r) || !(measure.sqDistance(c, k, b2) <= r_obb * r_obb)) continue;
          candidates_[(z * stride_z_ + y * stride_y_ + x) * words + k / 64] |= bit;
        }
  }
  words_ = words;
  candidate_radius_ = radius;
}

}  // namespace dss
