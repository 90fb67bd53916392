// Building the clearance grid (see dss/checker/clearance_grid.h).
#include "dss/checker/clearance_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dss {

ClearanceGrid::ClearanceGrid(const Aabb& region, const std::vector<Aabb>& boxes,
                             std::size_t max_voxels, double min_voxel) {
  const Eigen::Vector3d extent = region.upper - region.lower;
  if (boxes.empty() || !extent.allFinite() || !(extent.minCoeff() >= 0.0) || max_voxels == 0)
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
  // the rounding of these few operations is taken off before rounding down to the quantum.
  const double half_diagonal = 0.5 * std::sqrt(3.0) * size;
  std::size_t i = 0;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x, ++i) {
        const Eigen::Vector3d c = origin_ + size * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
        double d2 = std::numeric_limits<double>::infinity();
        for (const Aabb& b : boxes) d2 = std::min(d2, detail::sqDistPointAabb(c, b));
        const double margin = 1e-9 * (1.0 + c.cwiseAbs().maxCoeff() + half_diagonal);
        const double lower = std::sqrt(d2) - half_diagonal - margin;
        if (!(lower > 0.0)) continue;  // also NaN
        bound_[i] = static_cast<std::uint8_t>(std::min(255.0, std::floor(lower / kQuantum)));
      }
}

void ClearanceGrid::buildCandidates(const std::vector<Aabb>& boxes, double radius,
                                    std::size_t max_bytes) {
  words_ = 0;
  candidates_.clear();
  if (bound_.empty() || boxes.empty() || !(radius >= 0.0) || !std::isfinite(radius)) return;
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
          const double r = reach + margin;
          if (!(detail::sqDistPointAabb(c, b) <= r * r)) continue;
          candidates_[(z * stride_z_ + y * stride_y_ + x) * words + k / 64] |= bit;
        }
  }
  words_ = words;
  candidate_radius_ = radius;
}

}  // namespace dss
