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
// One row of voxels (centres cx[0 .. n)) against one box: d2[x] = min(d2[x], the squared
// distance from the voxel's cube of half size `half` (0: its centre) to the world box (lx, ux
// along x; dy2 + dz2, the squared distances along the other axes)), and for a turned box
// (kTurned) the larger of that and the oriented box's squared distance from the centre, with
// the centre's frame coordinates t_a = rx[a] (cx + px0) + ryz[a]. Two voxels at a time with
// SSE2; max and min as the scalar tail forms them (b < a ? a : b is max(a, b) for these finite
// values; an oriented distance that is NaN leaves the world box's, a NaN distance leaves d2 as
// it is).
template <bool kTurned>
void row(const double* cx, double* d2, int n, double half, double lx, double ux, double dy2,
         double dz2, double px0 = 0.0, const double* rx = nullptr, const double* ryz = nullptr,
         const double* h = nullptr) {
  int x = 0;
#if defined(__SSE2__)
  const __m128d vlx = _mm_set1_pd(lx - half), vux = _mm_set1_pd(ux + half), vdy2 = _mm_set1_pd(dy2),
                vdz2 = _mm_set1_pd(dz2), zero = _mm_setzero_pd(), vpx0 = _mm_set1_pd(px0),
                sign = _mm_set1_pd(-0.0);
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
      v = _mm_max_pd(ob2, v);  // v when ob2 is NaN
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
      const double ob2 = (o0 * o0 + o1 * o1) + o2 * o2;
      v = ob2 > v ? ob2 : v;
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
  voxels_ = static_cast<std::size_t>(n[0]) * n[1] * n[2];
  bound_.assign(voxels_ + kReadPast, 0);
  // Two bounds per voxel, the smaller kept: for obstacles along the axes the exact distance
  // from the voxel's cube to their boxes; for turned obstacles the larger of the distances
  // from the voxel's centre to their world box and to their oriented box, less half the
  // voxel's diagonal (every point of the voxel lies that close to the centre). A margin far
  // above the rounding of these few operations is taken off before rounding down to the
  // quantum, with that of the oriented-box distances.
  const double half = 0.5 * size;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * size;
  const Measure measure(obbs);
  // Row by row along x: each box's squared distance to the row's voxels in one pass (the x
  // part per voxel, the y and z parts once per row). A box whose distance to the row's line
  // already exceeds what a byte can hold (plus the half diagonal and every margin) cannot lower
  // any voxel of the row below the largest value, and is skipped.
  auto marginAt = [&](const Eigen::Vector3d& c) {
    return 1e-9 * (1.0 + c.cwiseAbs().maxCoeff() + half_diagonal) + measure.rounding(c);
  };
  const std::size_t nx = static_cast<std::size_t>(n[0]);
  std::vector<double> cx(nx), d2(nx), d2_turned(nx);
  for (int x = 0; x < n[0]; ++x) cx[x] = origin_.x() + size * (x + 0.5);
  const double cx_max = std::max(std::abs(cx.front()), std::abs(cx.back()));
  std::size_t i = 0;
  for (int z = 0; z < n[2]; ++z) {
    const double cz = origin_.z() + size * (z + 0.5);
    for (int y = 0; y < n[1]; ++y, i += nx) {
      const double cy = origin_.y() + size * (y + 0.5);
      // The margins grow with |c|: the row's largest, at its farthest centre.
      const double saturated =
          256.0 * kQuantum + half_diagonal + 2.0 * marginAt(Eigen::Vector3d(cx_max, cy, cz));
      const double skip2 = saturated * saturated;
      std::fill(d2.begin(), d2.end(), std::numeric_limits<double>::infinity());
      std::fill(d2_turned.begin(), d2_turned.end(), std::numeric_limits<double>::infinity());
      bool any_turned = false;
      for (std::size_t k = 0; k < boxes.size(); ++k) {
        const Aabb& b = boxes[k];
        const bool turned = measure.turned(k);
        const double grow = turned ? 0.0 : half;  // the centre's distance, or the cube's
        const double dy =
            std::max(std::max((b.lower.y() - grow) - cy, cy - (b.upper.y() + grow)), 0.0);
        const double dz =
            std::max(std::max((b.lower.z() - grow) - cz, cz - (b.upper.z() + grow)), 0.0);
        const double dy2 = dy * dy, dz2 = dz * dz;
        if (dy2 + dz2 > skip2) continue;
        const double lx = b.lower.x(), ux = b.upper.x();
        if (turned) {
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
          row<true>(cx.data(), d2_turned.data(), n[0], 0.0, lx, ux, dy2, dz2, -ob.c.x(), rx, ryz,
                    ob.h.data());
          any_turned = true;
        } else {
          row<false>(cx.data(), d2.data(), n[0], half, lx, ux, dy2, dz2);
        }
      }
      for (int x = 0; x < n[0]; ++x) {
        double distance = std::sqrt(d2[x]);
        if (any_turned) distance = std::min(distance, std::sqrt(d2_turned[x]) - half_diagonal);
        const double lower = distance - marginAt(Eigen::Vector3d(cx[x], cy, cz));
        if (!(lower > 0.0)) continue;  // also NaN
        bound_[i + static_cast<std::size_t>(x)] =
            static_cast<std::uint8_t>(std::min(255.0, std::floor(lower / kQuantum)));
      }
    }
  }
}

namespace {
// An upper bound on the distance from any point of a voxel (a cube of half size `half`) to a
// box, in the box's frame axis by axis: a coordinate of the cube reaches at most
// |t_a| + half |R_a|_1 from the box's centre, t being the cube's centre in the box's frame
// (exactly |t_a| + half for a box along the axes, whose farthest corner attains the bound). A
// margin far above the rounding of the centre, of the box frame and of voxel() (which may
// pick a neighbour for a point within rounding of a face) is added.
class FarthestFromBox {
 public:
  FarthestFromBox(const Obb& b, double half)
      : Rt_(b.R.transpose()),
        c_(b.c),
        h_(b.h),
        reach_(half * b.R.cwiseAbs().colwise().sum().transpose()),
        margin_(1e-9 * (1.0 + 2.0 * b.c.norm() + b.h.sum() + 2.0 * half) + 1e-12) {}
  /// NaN for a box with a non-finite entry.
  double operator()(const Eigen::Vector3d& center) const {
    const Eigen::Vector3d t = (Rt_ * (center - c_)).cwiseAbs();
    return (t + reach_ - h_).cwiseMax(0.0).norm() + margin_ + 3e-9 * center.cwiseAbs().maxCoeff();
  }

 private:
  Eigen::Matrix3d Rt_;
  Eigen::Vector3d c_, h_, reach_;
  double margin_;
};
}  // namespace

std::uint8_t ClearanceGrid::upperAt(const Eigen::Vector3d& c, const std::vector<Obb>& boxes,
                                    double cap) const {
  const std::ptrdiff_t i = index((c - below_) * inv_size_);
  if (i < 0) return kUnknown;
  const std::size_t k = static_cast<std::size_t>(i);
  const std::size_t x = k % stride_y_, y = k % stride_z_ / stride_y_, z = k / stride_z_;
  const Eigen::Vector3d center = origin_ + size_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
  double best = std::numeric_limits<double>::infinity();
  for (const Obb& b : boxes) best = std::min(best, FarthestFromBox(b, 0.5 * size_)(center));
  const double stored = std::min(cap, (kUnknown - 1) * kQuantum);
  return best <= stored ? static_cast<std::uint8_t>(std::ceil(best / kQuantum)) : kUnknown;
}

void ClearanceGrid::buildUpper(const std::vector<Obb>& boxes, double cap) {
  cells_.clear();
  if (voxels_ == 0) return;
  std::vector<std::uint8_t> upper(voxels_, kUnknown);
  const double stored = std::min(cap, (kUnknown - 1) * kQuantum);
  for (const Obb& b : boxes) {
    if (!(stored > 0.0) || !b.R.allFinite() || !b.c.allFinite() || !b.h.allFinite() ||
        !(b.h.minCoeff() >= 0.0))
      continue;
    // The voxels whose centres lie within `stored` plus a voxel of the box's world box (a box
    // at an angle reaches |R| h along each world axis); beyond, no bound is kept.
    const Eigen::Vector3d extent = b.R.cwiseAbs() * b.h;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double grow = extent[a] + stored + size_;
      const double l = std::floor((b.c[a] - grow - origin_[a]) * inv_size_);
      const double h = std::ceil((b.c[a] + grow - origin_[a]) * inv_size_);
      lo[a] = static_cast<int>(std::max(0.0, std::min(l, double(count_[a]))));
      hi[a] = static_cast<int>(std::max(0.0, std::min(h, double(count_[a]))));
    }
    const FarthestFromBox farthest(b, 0.5 * size_);
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int x = lo[0]; x < hi[0]; ++x) {
          const double d = farthest(origin_ + size_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5));
          if (!(d <= stored)) continue;
          std::uint8_t& u = upper[z * stride_z_ + y * stride_y_ + x];
          u = std::min(u, static_cast<std::uint8_t>(std::ceil(d / kQuantum)));
        }
  }
  cells_.resize(voxels_);
  for (std::size_t i = 0; i < voxels_; ++i)
    cells_[i] = static_cast<std::uint16_t>(bound_[i] | (upper[i] << 8));
}

void ClearanceGrid::buildCandidates(const std::vector<Aabb>& boxes, double radius,
                                    std::size_t max_bytes, const std::vector<Obb>& obbs) {
  words_ = 0;
  candidates_.clear();
  if (voxels_ == 0 || boxes.empty() || !(radius >= 0.0) || !std::isfinite(radius) ||
      !(obbs.empty() || obbs.size() == boxes.size()))
    return;
  for (const Aabb& b : boxes)
    if (!b.lower.allFinite() || !b.upper.allFinite()) return;
  const std::size_t words = (boxes.size() + 63) / 64;
  if (voxels_ > max_bytes / (8 * words)) return;
  candidates_.assign(voxels_ * words, 0);
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
