// The ball stage: a pair of which one side is a ball (a sphere obstacle, or a sphere element
// of the robot) and the other a box, sphere, capsule or cylinder is decided by the distance
// from the ball's centre to the other shape, in closed form, without a narrow phase. The
// sweep runs it before the oriented-box stage: a robot among trees (trunks under round crowns)
// or a robot made of spheres in a scene of cylinders meets such pairs all the time.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "dss/checker/inner_shapes.h"
#include "dss/core/any_shape.h"

namespace dss {

/// The signed distance from the point p, given in the frame of `shape`, to `shape` (negative
/// inside it: minus the distance to its boundary), in closed form for a box, sphere, capsule
/// (axis z) or cylinder (axis z); NaN for the other shapes. `size` receives a length of the
/// shape's scale (for rounding margins).
inline double pointDistance(const AnyShape& shape, const Eigen::Vector3d& p, double* size) {
  if (const auto* b = std::get_if<Box>(&shape)) {
    *size = b->half.sum();
    const Eigen::Vector3d q = p.cwiseAbs() - b->half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  }
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    *size = s->radius;
    return p.norm() - s->radius;
  }
  if (const auto* c = std::get_if<Capsule>(&shape)) {
    *size = c->radius + c->half_length;
    const double z = std::max(std::abs(p.z()) - c->half_length, 0.0);
    return std::sqrt(p.x() * p.x() + p.y() * p.y() + z * z) - c->radius;
  }
  if (const auto* c = std::get_if<Cylinder>(&shape)) {
    *size = c->radius + c->half_length;
    const double radial = std::sqrt(p.x() * p.x() + p.y() * p.y()) - c->radius;
    const double axial = std::abs(p.z()) - c->half_length;
    const double out_r = std::max(radial, 0.0), out_a = std::max(axial, 0.0);
    return std::sqrt(out_r * out_r + out_a * out_a) + std::min(std::max(radial, axial), 0.0);
  }
  *size = 0.0;
  return std::numeric_limits<double>::quiet_NaN();
}

/// The pair of `shape` (at X_WS) and the ball of centre c and radius r (world) at padding
/// `pad`: kApart when the signed distance from c to the shape exceeds r + pad, kTouch when it
/// is less, each by more than a relative margin of 1e-9 (1 nm at the scale of a metre) that
/// covers the rounding of the distance; kUnknown within the margin, for the shapes
/// pointDistance does not know, and for NaN anywhere.
inline BoxStage ballStage(const AnyShape& shape, const Eigen::Isometry3d& X_WS,
                          const Eigen::Vector3d& c, double r, double pad) {
  const Eigen::Vector3d t = c - X_WS.translation();
  const Eigen::Vector3d p = X_WS.linear().transpose() * t;
  double size = 0.0;
  const double d = pointDistance(shape, p, &size);
  const double reach = r + pad;
  const double margin = 1e-9 * (1.0 + t.cwiseAbs().sum() + size + std::abs(reach));
  if (d > reach + margin) return BoxStage::kApart;
  if (d < reach - margin) return BoxStage::kTouch;
  return BoxStage::kUnknown;
}

}  // namespace dss
