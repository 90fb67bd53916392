// A planning scene as the checker needs it: convex obstacles posed in the world, the pairs
// the scene allows to touch, and the robot joint values the scene was saved with.
//
// The readers (planning_scene_yaml.h, scene_text.h, urdf_world.h; scene_loader.h picks one by
// extension) fill it. Obstacles placed in a robot frame (e.g. `header.frame_id: base_link`)
// keep their pose in that frame and are flagged unresolved until resolveFrames() is given
// the robot's frames.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "dss/scene/allowed_collision_matrix.h"
#include "dss/scene/attached_object.h"
#include "dss/scene/obstacle.h"

namespace dss {

/// Poses of named frames in the world (e.g. the robot's links that never move).
using FrameMap = std::map<std::string, Eigen::Isometry3d>;

struct Scene {
  std::string name;
  /// The file it was read from (used in messages).
  std::string source;
  /// `robot_model_name` of a MoveIt scene; empty otherwise.
  std::string robot_model_name;
  std::vector<Obstacle> obstacles;
  AllowedCollisionMatrix allowed_collisions;
  /// Joint values saved with the scene (`robot_state.joint_state`), by joint name.
  std::map<std::string, double> robot_state;
  /// Multi-DOF joint transforms saved with the scene (`robot_state.multi_dof_joint_state`),
  /// in file order: the values of a robot's planar or floating joints (multi_dof.h).
  std::vector<std::pair<std::string, Eigen::Isometry3d>> robot_multi_dof;
  /// Frames the file itself places (MoveIt `fixed_frame_transforms`), world poses.
  FrameMap fixed_frames;
  /// Objects the robot holds (`robot_state.attached_collision_objects`): setupModel
  /// (checker_setup.h) makes each one a link of the robot, fixed to the link that holds it.
  std::vector<AttachedObject> attached;
  /// Things read but not modelled (an octomap, non-fixed URDF joints set to a value): never
  /// dropped silently, always listed here.
  std::vector<std::string> warnings;

  /// Distinct object ids, in file order.
  std::vector<std::string> objectIds() const;
  /// Frame ids that no obstacle could resolve yet (sorted, unique).
  std::vector<std::string> unresolvedFrames() const;
};

/// True for the names that mean the world/planning frame itself: "", "world", "/world".
bool isWorldFrame(const std::string& frame_id);

/// Recomputes X_WO = X_WF * X_FO for every obstacle whose frame is world, in `frames`, or in
/// the scene's `fixed_frames` (a leading '/' is ignored). With `require_all`, an obstacle
/// whose frame is found nowhere is an error naming the file, the object and the frame;
/// otherwise it stays unresolved.
void resolveFrames(Scene& scene, const FrameMap& frames, bool require_all = true);

}  // namespace dss
