// The core shapes of a pair file, as the library's model shapes (AnyShape) with a pose: each
// pair is decided by the instantiations compiled once in the core library (DSS) and in the
// comparisons library (GJK, Hybrid).
//
// Primitives keep their pose (identity when none is given). A convex shape with a pose is
// posed once, vertex by vertex (fl(R v + p)), and kept as a hull of world points at the
// identity pose: the exact mode is then exact for the posed floating-point inputs. Shape A
// may be padded by a radius, which turns the decision into "distance <= r".
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "dss/core/any_shape.h"
#include "dss/core/result.h"
#include "pairs_input.h"

namespace dss {
namespace pairs {

struct CorePair {
  AnyShape a;
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  AnyShape b;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};

/// The shape of a spec and its pose. Throws std::invalid_argument (from the core constructors).
CorePair makeCorePair(const ShapeSpec& a, const ShapeSpec& b);

enum class CoreAlgo { kDss, kGjk, kHybrid };

/// Decides every pair (the loop is inside, so that timing measures the decisions and the
/// per-pair dispatch only); `padding` grows shape A.
void decideAll(CoreAlgo algo, const std::vector<CorePair>& pairs, const Options& opt,
               double padding, std::vector<Result>& out);

}  // namespace pairs
}  // namespace dss
