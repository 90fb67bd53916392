// Inner balls: up to four balls inside an element's shape. A ball that comes within the
// padding of an obstacle box proves the pair colliding without a narrow phase (the sweep's
// inner-ball stage, for narrow phases that see the elements' own shapes).
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"

namespace dss {

/// Up to `max_out` balls inside `shape` (centre in the shape frame, radius), along the longest
/// axis of its local box (box_c, box_h; element_bounds.h). The radius of a ball at c is the
/// distance from c to the shape's boundary (for a hull: to its facet planes), reduced by a
/// relative 1e-7 of the shape's size, far above the rounding of the planes; every ball kept is
/// checked against the support function in the facet normals and 26 fixed directions. Cones
/// and flat hulls get none. Returns the number written.
int innerBalls(const AnyShape& shape, const Eigen::Vector3d& box_c, const Eigen::Vector3d& box_h,
               Eigen::Vector4d* out, int max_out);

/// True when the ball (c, r) comes within `pad` of the box (rotation, centre, half extents),
/// with a relative margin against rounding: a safe "colliding". NaN anywhere gives false.
inline bool ballTouchesBox(const Eigen::Vector3d& c, double r, const Eigen::Matrix3d& R,
                           const Eigen::Vector3d& bc, const Eigen::Vector3d& h, double pad) {
  const Eigen::Vector3d t = c - bc;
  const Eigen::Vector3d p(R.col(0).dot(t), R.col(1).dot(t), R.col(2).dot(t));
  const double reach = r + pad - 1e-9 * (1.0 + t.cwiseAbs().sum() + h.sum() + r);
  if (!(reach > 0.0) || !(h.x() >= 0.0)) return false;
  const Eigen::Vector3d d = (p.cwiseAbs() - h).cwiseMax(0.0);
  return d.squaredNorm() < reach * reach;
}

}  // namespace dss
