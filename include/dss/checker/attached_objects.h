// Objects the robot holds (scene.h, Scene::attached) made part of the robot: each becomes a link
// of its own, named by the object's id and fixed to the link that holds it, so that every
// stage of the collision model (its slots, self pairs, tables, batches and motion checks) treats
// it as it treats the robot's own links. It collides with the scene and with every link of the
// robot except the one holding it and its touch links, which the allowed collision matrix lets
// it touch (as MoveIt does).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dss/robot/robot_model.h"
#include "dss/scene/scene.h"

namespace dss {

/// `robot` with one fixed link per object of `objects` (joint "<id>/attached"), its parts placed
/// in the holding link: a part given in that link's frame as read; in a world frame, a frame of
/// `fixed_frames` or another link of the robot, through the robot's link poses at `state` (one
/// value per active joint: the scene's saved robot state, where MoveIt attached it). Adds to
/// `acm` the pairs of each object with its holding link and its touch links. The same robot
/// object with the same added links (shapes, placements, names) gives the same robot object
/// while `robot` lives (thread-safe), so that the models of many scenes holding the same object
/// share it and the per-robot caches (self-pair tables, element shapes). Throws
/// std::runtime_error naming the file and line of the object for a link or touch link the robot
/// lacks, an id that names a link of the robot or is attached twice, or a frame found nowhere.
std::shared_ptr<const RobotModel> withAttachedObjects(
    const std::shared_ptr<const RobotModel>& robot, const std::vector<AttachedObject>& objects,
    const std::vector<double>& state, const FrameMap& fixed_frames, AllowedCollisionMatrix& acm);

}  // namespace dss
