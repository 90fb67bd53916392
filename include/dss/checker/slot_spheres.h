// The slots' bounding spheres of one state in one pass: each sphere's world centre from its
// link's pose, and which spheres the clearance grid proves clear of the scene.
//
// The sweep (sweep.h) needs every centre (the self pairs test the spheres pairwise) and, for
// each slot checked against the scene, the grid's verdict first; most slots of a free state
// stop there. One pass over all of them keeps the poses' columns in vector registers and has
// no branch per slot. It runs on the run-time instruction set (simd_path.h): every path
// computes each coordinate as ((R_0 x + R_1 y) + R_2 z) + t with the same roundings, so the
// centres and the bits are the same on every path.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dss/checker/clearance_grid.h"
#include "dss/core/simd_path.h"

namespace dss {

class SlotSpheres {
 public:
  /// A sphere fixed to a link: its centre in the link's frame.
  struct Sphere {
    int link = -1;
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    double radius = 0.0;
    bool scene = false;  ///< checked against the scene
  };
  SlotSpheres() = default;
  /// `own[k]`, `folded[k]`: slot k's sphere on its own link and on its pose link (pose_links.h);
  /// the radius and the scene flag are own[k]'s.
  SlotSpheres(const std::vector<Sphere>& own, const std::vector<Sphere>& folded);

  std::size_t size() const { return size_; }
  /// Centres place() writes: size() and up to four more (it pads the spheres).
  std::size_t centersWritten() const { return radius_.size() + 1; }
  /// Words of the bit sets place() writes.
  std::size_t words() const { return (size() + 63) / 64; }
  /// The spheres checked against the scene, bit k for sphere k (words() words).
  const std::uint64_t* scene() const { return scene_.data(); }

  /// Places the spheres with the link poses X_WL (own links, or pose links when `pose_links`):
  /// writes the world centres to `centers` (centersWritten() of them: the first size() are the
  /// spheres') and sets bit k of `clear` (words()
  /// words, overwritten) where the grid proves sphere k grown by `padding` farther than that
  /// from every obstacle box (ClearanceGrid::clear; never for a centre outside the grid or NaN).
  void place(bool pose_links, const Eigen::Isometry3d* X_WL, const ClearanceGrid& grid,
             double padding, Eigen::Vector3d* centers, std::uint64_t* clear) const {
    placeOn(path_, pose_links, X_WL, grid, padding, centers, clear);
  }
  /// The same on a given path (tests; a path the CPU lacks falls back to the best one).
  void place(SimdPath path, bool pose_links, const Eigen::Isometry3d* X_WL,
             const ClearanceGrid& grid, double padding, Eigen::Vector3d* centers,
             std::uint64_t* clear) const;

 private:
  void placeOn(SimdPath path, bool pose_links, const Eigen::Isometry3d* X_WL,
               const ClearanceGrid& grid, double padding, Eigen::Vector3d* centers,
               std::uint64_t* clear) const;

  SimdPath path_ = SimdPath::kScalar;
  std::size_t size_ = 0;
  std::vector<int> link_[2];       ///< per slot: own link, pose link
  std::vector<double> center_[2];  ///< per slot four values: x, y, z, 0
  std::vector<double> radius_;     ///< padded to a multiple of four with infinity
  std::vector<std::uint64_t> scene_;
};

}  // namespace dss
