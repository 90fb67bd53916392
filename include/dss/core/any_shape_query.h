// The decision on model shapes (AnyShape) with poses, compiled once in the core library: every
// pair of shape types, plain and padded, in the three modes. The type dispatch happens once
// per pair; the search then runs on concrete types (Posed<Ref<S>>: the shapes are not
// copied), with no virtual call and no allocation.
//
// Two convex hulls that both sit at the exact identity pose are taken as given by their world
// vertices: the exact mode then decides them exactly (result.h). Every other pair is posed,
// and its "disjoint" answers are certified. Every number of a query (shape parameters, poses,
// padding) is checked first: a NaN or an infinity anywhere answers "intersect" with status
// invalid_input, whatever the mode and the iteration cap.
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"
#include "dss/core/result.h"

namespace dss {

/// Do shape a at pose X_WA and shape b at pose X_WB intersect (touching counts)? `padding` > 0
/// grows a by a ball: the answer is then "distance <= padding".
Result intersect(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                 const Eigen::Isometry3d& X_WB, const Options& opt = {}, double padding = 0.0);

}  // namespace dss
