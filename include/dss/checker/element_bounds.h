// Cheap bounds of a collision element that the sweep tests before the narrow phase: a
// bounding sphere in the link frame and a box, axis-aligned in the shape's own frame, that
// holds the shape. Both are grown by a small relative margin so that rounding never cuts a
// point of the shape off: they may only make a test say "maybe", never "apart" wrongly.
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"

namespace dss {

/// Bounding sphere of `shape` placed at X_LS in its link: centre (link frame) and radius.
void elementSphere(const AnyShape& shape, const Eigen::Isometry3d& X_LS, Eigen::Vector3d* center_L,
                   double* radius);

/// A box holding `shape`, axis-aligned in the shape frame: centre and half extents, grown by a
/// relative 1e-9.
void localBox(const AnyShape& shape, Eigen::Vector3d* center_S, Eigen::Vector3d* half);

}  // namespace dss
