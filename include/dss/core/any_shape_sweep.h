// Swept decisions on model shapes, compiled once in the core library: a shape moving from one
// pose to another is bounded by the convex hull of its two poses (SweptHull) grown by a
// padding that covers the bulge of the motion between them; the other shape is posed, or
// swept too. The conservative motion validator of the planning layer is built on these. As in
// any_shape_query.h, a NaN or an infinity in any shape parameter, pose or padding answers
// "intersect" with status invalid_input.
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"
#include "dss/core/result.h"

namespace dss {

/// Does conv(X_WA0(a) U X_WA1(a)) grown by `padding` meet b at X_WB?
Result intersectSwept(const AnyShape& a, const Eigen::Isometry3d& X_WA0,
                      const Eigen::Isometry3d& X_WA1, double padding, const AnyShape& b,
                      const Eigen::Isometry3d& X_WB, const Options& opt = {});

/// Does conv(X_WA0(a) U X_WA1(a)) grown by `padding` meet conv(X_WB0(b) U X_WB1(b))?
Result intersectSwept(const AnyShape& a, const Eigen::Isometry3d& X_WA0,
                      const Eigen::Isometry3d& X_WA1, double padding, const AnyShape& b,
                      const Eigen::Isometry3d& X_WB0, const Eigen::Isometry3d& X_WB1,
                      const Options& opt = {});

}  // namespace dss
