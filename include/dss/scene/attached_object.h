// An object the robot holds: MoveIt's `moveit_msgs/AttachedCollisionObject` as a PlanningScene's
// robot state lists it. It moves with its link and collides like a part of the robot, except
// with the links it may touch (a gripper's fingers around it).
#pragma once

#include <string>
#include <vector>

#include "dss/scene/obstacle.h"

namespace dss {

struct AttachedObject {
  /// The collision object's id: the name the allowed collision matrix and messages use.
  std::string id;
  /// `link_name`: the robot link it moves with.
  std::string link;
  /// `touch_links`: robot links it may touch (the link it moves with always may).
  std::vector<std::string> touch_links;
  /// Its convex parts as the reader placed them: each part's pose X_FO in its `frame_id` (the
  /// object's `header.frame_id`: usually `link`; a world frame or another robot link is taken
  /// at the scene's saved robot state, as MoveIt attaches it). X_WO and frame_resolved unused.
  std::vector<Obstacle> parts;
  /// Where it was read ("file:line"), for messages.
  std::string at;
  /// Read from a MotionPlanRequest's start state: parts given in another frame than `link`
  /// are placed at the request's start state (else at the scene's saved robot state).
  bool at_request_start = false;
};

}  // namespace dss
