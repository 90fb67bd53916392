// A voxel grid over the region the robot's link spheres can reach, holding for every voxel a
// lower bound on the distance from any point of the voxel to every obstacle box of the scene,
// in whole multiples of a quantum (2^-7 m), one byte per voxel.
//
// The sweep (CollisionModel::anyCollision) asks it first for each moving link's sphere: when
// the bound at the sphere's centre exceeds the sphere's radius plus the padding, the link is
// clear of every obstacle and its per-obstacle tests are skipped. On random Panda states in
// the MotionBenchMaker scenes about three quarters of the link spheres are settled this way
// (one lookup instead of one sphere-box test per obstacle). A centre outside the grid, or NaN,
// gets no bound, and the per-obstacle tests run as before: the grid never changes an answer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "dss/scene/obstacle.h"

namespace dss {

class ClearanceGrid {
 public:
  static constexpr double kQuantum = 1.0 / 128;  ///< metres per step of the stored bound
  ClearanceGrid() = default;
  /// Covers `region` with at most about `max_voxels` cubic voxels (never smaller than
  /// `min_voxel` m). An empty or non-finite region, or no boxes, gives an empty grid.
  ClearanceGrid(const Aabb& region, const std::vector<Aabb>& boxes, std::size_t max_voxels = std::size_t(1) << 16,
                double min_voxel = 0.02);

  /// True when every box is farther than r from c (proven; false when unknown).
  bool clear(const Eigen::Vector3d& c, double r) const {
    const std::uint8_t* v = voxel(c);
    return v && *v * kQuantum > r;
  }
  /// The lower bound (metres) stored for the voxel of c, 0 outside the grid.
  double bound(const Eigen::Vector3d& c) const {
    const std::uint8_t* v = voxel(c);
    return v ? *v * kQuantum : 0.0;
  }

  bool empty() const { return bound_.empty(); }
  std::size_t voxels() const { return bound_.size(); }
  double voxelSize() const { return size_; }
  const Eigen::Vector3d& origin() const { return origin_; }

 private:
  /// The voxel holding c, or null outside the grid (and for NaN).
  const std::uint8_t* voxel(const Eigen::Vector3d& c) const {
    const double fx = (c.x() - origin_.x()) * inv_size_;
    const double fy = (c.y() - origin_.y()) * inv_size_;
    const double fz = (c.z() - origin_.z()) * inv_size_;
    if (!(fx >= 0.0 && fx < n_[0] && fy >= 0.0 && fy < n_[1] && fz >= 0.0 && fz < n_[2])) return nullptr;
    // Converted through int (the counts are far below 2^31): a double to size_t conversion
    // costs a comparison and a branch per axis on x86-64 without AVX-512.
    const auto index = [](double f) { return static_cast<std::size_t>(static_cast<int>(f)); };
    return &bound_[index(fz) * stride_z_ + index(fy) * stride_y_ + index(fx)];
  }

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double size_ = 0.0;
  double inv_size_ = 0.0;
  // An empty grid: no point is inside (fx < 0 fails for every finite point, NaN fails too).
  double n_[3] = {0.0, 0.0, 0.0};  // voxel counts per axis
  std::size_t stride_y_ = 0, stride_z_ = 0;
  std::vector<std::uint8_t> bound_;
};

}  // namespace dss
