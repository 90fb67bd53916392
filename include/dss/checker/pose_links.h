// Pose links: a link is rigid to the nearest link above it whose parent joint moves with the
// group (or to the root) as long as the joints in between -- fixed, or held outside the group
// -- keep their held values. The sweep then needs only the poses of those pose links: a
// gripper's hand and fingers ride on the last arm link (the Panda arm group computes 7 poses
// instead of 10).
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "dss/robot/kinematics.h"
#include "dss/robot/robot_model.h"

namespace dss {

struct PoseLinks {
  std::vector<int> pose_of;             ///< per link: its pose link
  std::vector<Eigen::Isometry3d> X_PL;  ///< per link: its frame in its pose link's frame
};

/// Pose links of every link for a group (`in_group`: per active joint) with the other joints at
/// `held` (`kin` gives joint values, mimic joints included). A held value that places nothing
/// (NaN, Inf) keeps its link a pose link of its own.
PoseLinks poseLinks(const RobotModel& robot, const Kinematics& kin, const std::vector<double>& held,
                    const std::vector<char>& in_group);

}  // namespace dss
