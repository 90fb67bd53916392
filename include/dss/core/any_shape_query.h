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

/// Whether the plane normal to `n` (world, any length) proves a at X_WA (grown by `padding`)
/// and b at X_WB apart: max over a of n.x + padding |n| < min over b of n.y, with a margin of
/// 1e-10 of the pair's size and offset covering the rounding of the supports. Two support
/// evaluations, no search: a separating direction found for a nearby pose (Result::
/// separating_direction) usually still separates. False, never a wrong "apart", for a zero
/// or non-finite n, pose or shape.
bool separatedAlong(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                    const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& n, double padding = 0.0);

}  // namespace dss
