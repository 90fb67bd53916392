// A voxel grid over the region the robot's link spheres can reach, holding for every voxel a
// lower bound on the distance from any point of the voxel to every obstacle box of the scene,
// in whole multiples of a quantum (2^-7 m), one byte per voxel.
//
// The sweep (sweep.h) asks it first for each moving link's sphere: when the bound at the
// sphere's centre exceeds the sphere's radius plus the padding, the link is clear of every
// obstacle and its per-obstacle tests are skipped (one lookup instead of one sphere-box test
// per obstacle: most link spheres of a free state are settled this way). A centre outside the
// grid, or NaN, gets no bound, and the per-obstacle tests run as before: the grid never
// changes an answer. In scenes with many obstacles it also lists, per voxel, the obstacles a
// link sphere centred there can touch, so that the per-obstacle tests run over those alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <Eigen/Geometry>

#include "dss/checker/obb.h"
#include "dss/scene/obstacle.h"

namespace dss {

class ClearanceGrid {
 public:
  static constexpr double kQuantum = 1.0 / 128;  ///< metres per step of the stored bound
  ClearanceGrid() = default;
  /// Covers `region` with at most about `max_voxels` cubic voxels (never smaller than
  /// `min_voxel` m). An empty or non-finite region, or no boxes, gives an empty grid.
  ClearanceGrid(const Aabb& region, const std::vector<Aabb>& boxes,
                std::size_t max_voxels = std::size_t(1) << 16, double min_voxel = 0.02)
      : ClearanceGrid(region, boxes, {}, max_voxels, min_voxel) {}
  /// The same with each obstacle also bounded by an oriented box (`obbs`, one per box, or
  /// empty): a voxel's bound is then the larger of the two distances, which is much tighter
  /// near an obstacle turned away from the axes.
  ClearanceGrid(const Aabb& region, const std::vector<Aabb>& boxes, const std::vector<Obb>& obbs,
                std::size_t max_voxels = std::size_t(1) << 16, double min_voxel = 0.02);

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

  /// Upper bounds: for every voxel, a bound on the distance from any of its points to the
  /// nearest of `boxes` (each exactly an obstacle's shape, and one that every link checked
  /// against the scene must not touch), rounded up to the quantum, kept where it is at most
  /// `cap` (elsewhere unknown). A ball of radius rho inside a link whose centre has an upper
  /// bound of at most rho + padding is then within the padding of an obstacle: a collision.
  /// Stored with the lower bounds, two bytes per voxel (cell()).
  void buildUpper(const std::vector<Obb>& boxes, double cap);
  bool hasCells() const { return !cells_.empty(); }
  /// The upper bound buildUpper(boxes, cap) stores for the voxel of c, in quanta (kUnknown
  /// where it keeps none, outside the grid and for NaN), computed without storing it.
  std::uint8_t upperAt(const Eigen::Vector3d& c, const std::vector<Obb>& boxes, double cap) const;
  /// The bounds of c's voxel in quanta: the lower one in the low byte, the upper one in the
  /// high byte (kUnknown where unknown); kOutside (0 and kUnknown) when c is outside the grid
  /// or NaN. Needs hasCells().
  static constexpr std::uint8_t kUnknown = 255;
  static constexpr std::uint16_t kOutside = std::uint16_t(kUnknown) << 8;
  std::uint16_t cell(const Eigen::Vector3d& c) const {
    return cellAtVoxel((c - below_) * inv_size_);
  }
  /// A pose X composed with the grid's voxel coordinates, for cells of many points of one
  /// frame: cell(f, p) is cell(X p) with one affine map per point.
  struct Frame {
    Eigen::Matrix3d A;
    Eigen::Vector3d b;
  };
  Frame frame(const Eigen::Isometry3d& X) const {
    return {inv_size_ * X.linear(), (X.translation() - below_) * inv_size_};
  }
  std::uint16_t cell(const Frame& f, const Eigen::Vector3d& p) const {
    return cellAtVoxel(f.A * p + f.b);
  }

  /// Candidate lists: for every voxel, the boxes that a ball of radius up to `radius` centred
  /// anywhere in the voxel can touch, one bit per box (index into `boxes`). Built only when
  /// they fit in `max_bytes`; without them candidates() is null.
  /// `obbs`: as for the constructor (a box is then listed only where both its boxes are near).
  void buildCandidates(const std::vector<Aabb>& boxes, double radius, std::size_t max_bytes,
                       const std::vector<Obb>& obbs = {});
  /// The candidate bits of c's voxel (candidateWords() words), or null when c is outside the
  /// grid (or NaN), when no lists were built, or when r exceeds the radius they were built for.
  const std::uint64_t* candidates(const Eigen::Vector3d& c, double r) const {
    if (words_ == 0 || !(r <= candidate_radius_)) return nullptr;
    const std::uint8_t* v = voxel(c);
    return v ? &candidates_[static_cast<std::size_t>(v - bound_.data()) * words_] : nullptr;
  }
  std::size_t candidateWords() const { return words_; }

  /// The lookup's fields, for passes that convert many points at once (slot_spheres.h,
  /// state_batch.h): voxel coordinates u = (c - below) * inv_size, the voxel of index
  /// floor(u) - 1 per axis when that lies in [0, count), its lower bound at
  /// bound[z * stride_z + y * stride_y + x]. When the grid is not empty, kReadPast bytes past
  /// the last voxel are readable (zero), so that a four-byte gather may read any voxel.
  static constexpr std::size_t kReadPast = 3;
  struct Lookup {
    double below[3];
    double inv_size;
    unsigned count[3];
    std::size_t stride_y, stride_z;
    const std::uint8_t* bound;
  };
  Lookup lookup() const {
    return {{below_.x(), below_.y(), below_.z()},
            inv_size_,
            {count_[0], count_[1], count_[2]},
            stride_y_,
            stride_z_,
            bound_.data()};
  }

  bool empty() const { return voxels_ == 0; }
  std::size_t voxels() const { return voxels_; }
  double voxelSize() const { return size_; }
  const Eigen::Vector3d& origin() const { return origin_; }

 private:
  /// f truncated to int; INT_MIN for NaN and for values out of the int range.
  static int toIndex(double f) {
#if defined(__SSE2__)
    return _mm_cvttsd_si32(_mm_set_sd(f));  // the x86 conversion, defined for every input
#else
    return f > -2147483648.0 && f < 2147483647.0 ? static_cast<int>(f)
                                                 : std::numeric_limits<int>::min();
#endif
  }
  /// The voxel holding c, or null outside the grid (and for NaN).
  const std::uint8_t* voxel(const Eigen::Vector3d& c) const {
    const std::ptrdiff_t i = index((c - below_) * inv_size_);
    return i < 0 ? nullptr : &bound_[static_cast<std::size_t>(i)];
  }
  /// The index of the voxel at voxel coordinates u, counted from one voxel below the grid
  /// ((c - below_) / size), or -1 outside. A voxel index i + 1 in [1, n], so that one unsigned
  /// comparison per axis rejects the outside (negative, beyond n, and the INT_MIN that the
  /// conversion gives for NaN and huge values). A point within rounding of a voxel face may
  /// land in the neighbour: the stored bounds keep a margin far above that.
  std::ptrdiff_t index(const Eigen::Vector3d& u) const {
    const unsigned x = static_cast<unsigned>(toIndex(u.x())) - 1u,
                   y = static_cast<unsigned>(toIndex(u.y())) - 1u,
                   z = static_cast<unsigned>(toIndex(u.z())) - 1u;
    if (!((x < count_[0]) & (y < count_[1]) & (z < count_[2]))) return -1;
    return static_cast<std::ptrdiff_t>(z * stride_z_ + y * stride_y_ + x);
  }
  std::uint16_t cellAtVoxel(const Eigen::Vector3d& u) const {
    const std::ptrdiff_t i = index(u);
    return i < 0 ? kOutside : cells_[static_cast<std::size_t>(i)];
  }

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double size_ = 0.0;
  double inv_size_ = 0.0;
  unsigned count_[3] = {0, 0, 0};  // voxel counts per axis (an empty grid: no point is inside)
  Eigen::Vector3d below_ = Eigen::Vector3d::Zero();  // origin_ minus one voxel per axis
  std::size_t stride_y_ = 0, stride_z_ = 0;
  std::size_t voxels_ = 0;
  std::vector<std::uint8_t> bound_;   // voxels_ bounds, then kReadPast zeros (none when empty)
  std::vector<std::uint16_t> cells_;  // empty until buildUpper
  std::size_t words_ = 0;             // candidate words per voxel (0: none built)
  double candidate_radius_ = 0.0;
  std::vector<std::uint64_t> candidates_;
};

}  // namespace dss
