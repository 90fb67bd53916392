// Multi-DOF joints: planar and floating joints (URDF joints or SRDF virtual joints) as chains
// of one-variable joints (see robot_model.h for the names), the bounds of their translation
// variables, and their values from a transform (MoveIt's multi_dof_joint_state).
//
// Conventions follow MoveIt: a planar joint moves in the x-y plane of its joint frame (x, y,
// then theta about z; a URDF planar joint's <axis> is not used), a floating joint translates
// along x, y, z of its joint frame and then turns by a quaternion. Their translation variables
// have no bounds until a workspace gives them (MoveIt's workspace_parameters); the state space
// of a group that moves such a variable is refused while it is unbounded. The theta of a
// planar joint is continuous; quaternion variables range over [-1, 1] and the kinematics
// normalises them (a quaternion of norm below kMinQuaternionNorm is an invalid state).
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dss/robot/robot_model.h"

namespace dss {

/// A state whose quaternion has a smaller norm is invalid (its rotation is undefined).
inline constexpr double kMinQuaternionNorm = 1e-6;

/// Whether the quaternion (x, y, z, w) has a norm of at least kMinQuaternionNorm and a finite
/// squared norm (tested on the squared norm, without a square root).
inline bool quaternionNormValid(double x, double y, double z, double w) {
  const double n2 = x * x + y * y + z * z + w * w;
  return n2 >= kMinQuaternionNorm * kMinQuaternionNorm && n2 <= 1.7976931348623157e308;
}

/// Replaces each listed joint (given by index; a placeholder of type kFixed without variables)
/// by the chain of one-variable joints of its type, renumbering links, joints and active
/// indices (mimic joints keep their leaders). `source` names the file for errors (a name
/// clash with an existing link or joint). `from_srdf` is recorded in the MultiDofJoint.
void expandMultiDofJoints(RobotModel& model,
                          const std::vector<std::pair<int, MultiDofType>>& placeholders,
                          bool from_srdf, const std::string& source);

/// Connects the robot's root link to a new root link named `parent_frame` by a planar or
/// floating joint `name` (an SRDF virtual joint); `child_link` must be the root link. Throws
/// std::runtime_error naming `source` otherwise, or for an unknown `type` ("fixed" is
/// accepted and changes nothing).
void applyVirtualJoint(RobotModel& model, const std::string& name, const std::string& type,
                       const std::string& parent_frame, const std::string& child_link,
                       const std::string& source);

/// Bounds of the translation variables of every multi-DOF joint: planar x, y take [lo.x, hi.x]
/// and [lo.y, hi.y], floating trans_x/y/z all three. Throws std::invalid_argument when a
/// bound is not finite or lo > hi.
void setMultiDofTranslationBounds(RobotModel& model, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi);

/// True when some translation variable of a multi-DOF joint has no bounds.
bool hasUnboundedMultiDofJoint(const RobotModel& model);

/// The variable values (activeJointNames order within the joint) of multi-DOF joint `index`
/// for the transform X from its parent's joint frame: planar x, y, yaw of X (X's other
/// components are dropped); floating translation and quaternion (w >= 0).
std::vector<std::pair<std::string, double>> multiDofValues(const RobotModel& model, int index,
                                                           const Eigen::Isometry3d& X);

/// The values of the model's multi-DOF joints from named transforms (a scene's or a request's
/// multi_dof_joint_state), by variable name. A name that is not a planar or floating joint of
/// the model is skipped: silently when its transform is the identity (MoveIt saves the fixed
/// virtual joint's), else with a line in `notes`.
std::map<std::string, double> multiDofStateValues(
    const RobotModel& model, const std::vector<std::pair<std::string, Eigen::Isometry3d>>& named,
    std::vector<std::string>* notes = nullptr);

}  // namespace dss
