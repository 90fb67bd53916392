// Building the clearance grid (see dss/checker/clearance_grid.h).
#include "dss/checker/clearance_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
    if (reach_ >= 0.0 && !obbs_[k].axis_aligned) {
      double error;
      const double o2 = sqDistPointObb(c, obbs_[k], &error);
      if (o2 > b2) b2 = o2;  // NaN: the world box's
    }
    return b2;
  }
  double rounding(const Eigen::Vector3d& c) const {
    return reach_ < 0.0 ? 0.0 : 1e-9 * (3.0 * c.cwiseAbs().maxCoeff() + reach_) + 1e-12;
  }

 private:
  const std::vector<Obb>& obbs_;
  double reach_ = -1.0;  // negative: no turned obstacle
};
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
  // Every point of a voxel lies within half its diagonal of the centre, so the centre's
  // distance to a box minus that is a lower bound for the whole voxel. A margin far above
  // the rounding of these few operations is taken off before rounding down to the quantum,
  // with that of the oriented-box distances.
  const double half_diagonal = 0.5 * std::sqrt(3.0) * size;
  const Measure measure(obbs);
  std::size_t i = 0;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x, ++i) {
        const Eigen::Vector3d c = origin_ + size * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
        // The nearest obstacle; a world box no nearer than the best so far cannot lower it, and
        // its oriented box is not needed.
        double d2 = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < boxes.size(); ++k) {
          const double b2 = detail::sqDistPointAabb(c, boxes[k]);
          if (!(b2 < d2)) continue;
          d2 = std::min(d2, measure.sqDistance(c, k, b2));
        }
        const double margin =
            1e-9 * (1.0 + c.cwiseAbs().maxCoeff() + half_diagonal) + measure.rounding(c);
        const double lower = std::sqrt(d2) - half_diagonal - margin;
        if (!(lower > 0.0)) continue;  // also NaN
        bound_[i] = static_cast<std::uint8_t>(std::min(255.0, std::floor(lower / kQuantum)));
      }
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
