// One convex obstacle of a scene: a shape from the core's closed set, its pose in the world
// and where it came from. A collision object made of several primitives or meshes becomes
// several obstacles sharing an `object_id`, so that each obstacle is one convex set that the
// checker can test, bound and drop on its own.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "dss/core/any_shape.h"

namespace dss {

struct Obstacle {
  /// Unique in its scene: the object id for a one-shape object, "id/k" for shape k of a
  /// several-shape object; when an id holding a '/' already took that name (object "a/1"
  /// against shape 1 of object "a"), the later one gets "#2" appended (or the first free "#n").
  std::string name;
  /// The collision object (MoveIt id, .scene object, URDF link) it belongs to; the allowed
  /// collision matrix names objects by this id.
  std::string object_id;
  AnyShape shape;
  /// Pose of the shape in the world. Valid only when `frame_resolved`.
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  /// Pose of the shape in `frame_id` (object pose composed with the shape's own pose), kept
  /// so that the world pose can be recomputed once the robot's frames are known.
  Eigen::Isometry3d X_FO = Eigen::Isometry3d::Identity();
  /// The frame the file placed the object in; empty for the world (planning) frame.
  std::string frame_id;
  /// False while `frame_id` names a frame that the file itself could not place (a robot
  /// link such as `base_link`); see resolveFrames() in scene.h.
  bool frame_resolved = true;
  /// Human-readable origin, e.g. "box 0.1 x 0.2 x 0.3 (object Cube, primitive 0)".
  std::string description;
};

/// An axis-aligned box in the world.
struct Aabb {
  Eigen::Vector3d lower = Eigen::Vector3d::Zero();
  Eigen::Vector3d upper = Eigen::Vector3d::Zero();
  Eigen::Vector3d center() const { return 0.5 * (lower + upper); }
  /// Half of the diagonal: the radius of a ball about center() that holds the box.
  double radius() const { return 0.5 * (upper - lower).norm(); }
};

namespace detail {
/// Squared distance from p to the box (0 inside).
inline double sqDistPointAabb(const Eigen::Vector3d& p, const Aabb& b) {
  const Eigen::Vector3d d = (b.lower - p).cwiseMax(p - b.upper).cwiseMax(0.0);
  return d.squaredNorm();
}
}  // namespace detail

/// The tight world-space box of an obstacle (from its support function along the six axis
/// directions, so exact for every shape type).
Aabb worldAabb(const Obstacle& obstacle);

/// A short text like "box 0.1 x 0.2 x 0.3" or "convex (8 vertices)".
std::string describeShape(const AnyShape& shape);

}  // namespace dss
