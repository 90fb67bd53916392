// Decision GJK and the paper's Hybrid on model shapes (AnyShape) with poses: the algorithms
// DSS is compared with (dss_pairs, benchmarks), compiled once in their own library so that
// the product's core does not carry them. Same contract as dss::intersect on AnyShape
// (any_shape_query.h), padding and world-vertex hulls included.
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"
#include "dss/core/result.h"

namespace dss {

/// Decision GJK (plain floating-point signs; Mode::kFloat runs it in float, else double).
Result intersectGjk(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                    const Eigen::Isometry3d& X_WB, const Options& opt = {}, double padding = 0.0);

/// Hybrid: four GJK-directed steps, then DSS on the polygon they built (in every mode).
Result intersectHybrid(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                       const Eigen::Isometry3d& X_WB, const Options& opt = {},
                       double padding = 0.0);

}  // namespace dss
