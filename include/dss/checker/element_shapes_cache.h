// The bounds of a robot's collision elements that depend on the element alone -- its bounding
// sphere in the link frame, its local box, its inner balls and inner box -- computed once per
// robot for every collision model built from it (a folder of MotionBenchMaker problems, a
// planning scene that changes between requests). Finding the inner shapes of a convex hull
// is most of that work, and a model's setup would otherwise repeat it for every scene.
//
// Process-wide and thread-safe (built outside the lock); it keeps the 16 robots asked for
// last. Only models built from the same RobotModel object (the same shared_ptr, still alive)
// share an entry, so an entry is exactly what computing the bounds again would give.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "dss/checker/sphere_chain.h"
#include "dss/robot/robot_model.h"

namespace dss {

struct ElementShapes {
  Eigen::Vector3d center_L = Eigen::Vector3d::Zero();  ///< bounding sphere in the link frame
  double radius = 0.0;
  /// The local box (element_bounds.h): the oriented-box stage of the sweep.
  Eigen::Vector3d box_center_S = Eigen::Vector3d::Zero();
  Eigen::Vector3d box_half = Eigen::Vector3d::Zero();
  /// Inner balls (inner_shapes.h): centre in the shape frame, radius.
  static constexpr int kMaxInner = 4;
  int num_inner = 0;
  Eigen::Vector4d inner_S[kMaxInner];
  /// Inner box (inner_shapes.h), axis-aligned in the shape frame: centre (the local box's: the
  /// sweep tests both boxes in one pass, boxStages), half extents. Kept only where it holds
  /// more than the balls (flat and boxy elements).
  bool has_inner_box = false;
  Eigen::Vector3d inner_box_c = Eigen::Vector3d::Zero();
  Eigen::Vector3d inner_box_h = Eigen::Vector3d::Zero();
};

/// What the cache keeps of an element: the bounds the sweep reads (each model's elements carry
/// them) and the balls along it (sphere_chain.h, in the shape frame), which a model copies into
/// its chain points where they pay.
struct CachedElementShapes : ElementShapes {
  SphereChain chain;
};

/// The bounds of one element (not cached).
CachedElementShapes computeElementShapes(const CollisionElement& element);

/// One entry per collision element of the robot: links in model order, each link's elements
/// in order.
std::shared_ptr<const std::vector<CachedElementShapes>> cachedElementShapes(
    const std::shared_ptr<const RobotModel>& robot);

}  // namespace dss
