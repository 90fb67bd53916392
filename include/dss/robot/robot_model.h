// A robot as the collision checker sees it: a kinematic tree of links and joints, each link
// carrying zero or more convex collision elements (primitives kept exact, meshes as hulls).
//
// Indices are dense and stable: links and joints are numbered in a depth-first order from the
// root, children in document order, so a parent always comes before its children. The values
// of a state are indexed by *active* index: one per variable of the revolute, continuous,
// prismatic and ball joints that are not mimic joints, in that same depth-first order (a ball
// joint has four, every other moving joint one). Mimic joints follow their leader (value =
// multiplier * leader + offset).
//
// Multi-DOF joints (URDF planar and floating joints, SRDF planar and floating virtual joints)
// are expanded into chains of one-variable joints named as MoveIt names their variables,
// joined by links without geometry (see multi_dof.h): a planar joint J becomes J/x, J/y
// (prismatic along x and y of the joint frame) and J/theta (continuous about z); a floating
// joint J becomes J/trans_x, J/trans_y, J/trans_z and the ball joint J/rot, whose variables are
// J/rot_x, J/rot_y, J/rot_z, J/rot_w (a quaternion, normalised by the kinematics). Every other
// part of the library sees ordinary joints.
#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "dss/core/any_shape.h"

namespace dss {

/// kBall: free rotation about the joint origin, four variables (quaternion x, y, z, w); only
/// made by the expansion of a floating joint.
enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic, kBall };

const char* toString(JointType t);

struct JointLimits {
  bool has_position_limits = false;  ///< false for continuous joints
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  double velocity = 0.0;
  double effort = 0.0;
};

struct JointMimic {
  std::string leader;  ///< empty: not a mimic joint
  double multiplier = 1.0;
  double offset = 0.0;
};

struct RobotJoint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;
  int child_link = -1;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();  ///< joint frame in the parent link
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();         ///< unit, in the joint frame
  JointLimits limits;
  JointMimic mimic;
  int active_index = -1;  ///< index in a state vector; -1 for fixed and mimic joints
  /// For a mimic joint: the active joint it follows and the composed multiplier/offset
  /// (chains of mimic joints are resolved). -1 otherwise.
  int mimic_active = -1;
  double mimic_multiplier = 1.0;
  double mimic_offset = 0.0;

  /// The multi-DOF joint this joint is a part of (index into RobotModel::multi_dof_joints),
  /// -1 for a joint of the robot description itself.
  int multi_dof = -1;

  bool isMoving() const { return type != JointType::kFixed; }
  /// Number of state values the joint owns (0 for fixed and mimic joints).
  int numVariables() const { return active_index < 0 ? 0 : (type == JointType::kBall ? 4 : 1); }
};

/// The motion of a joint (in its joint frame) at its value: `value` points to the joint's one
/// value, or to a ball joint's four (a quaternion x, y, z, w, normalised here). Identity for a
/// fixed joint.
Eigen::Isometry3d jointMotion(const RobotJoint& joint, const double* value);

enum class MultiDofType { kPlanar, kFloating };

/// A planar or floating joint as the robot description names it, and the one-variable joints
/// it was expanded into (planar: x, y, theta; floating: trans_x, trans_y, trans_z, rot).
struct MultiDofJoint {
  std::string name;
  MultiDofType type = MultiDofType::kPlanar;
  std::vector<int> joints;  ///< model joint indices, from the parent side
  bool from_srdf = false;   ///< an SRDF virtual joint (else a URDF joint)
};

struct CollisionElement {
  AnyShape shape;
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();  ///< shape frame in the link frame
  std::string description;  ///< e.g. "link panda_link1 collision[0] mesh meshes/link1.stl"
  /// For a mesh: the file it was read from (resolved path) and the scale applied to its
  /// vertices; the shape is the hull of the scaled vertices. Empty for primitives.
  std::string mesh_path;
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
  /// A piece of a decomposed mesh (MeshGeometry::kDecompose): its index among `pieces` and its
  /// certified concavity (m; mesh::ConvexPiece); piece -1 for a plain hull or a primitive.
  int piece = -1;
  int pieces = 1;
  double concavity = 0.0;
};

struct RobotLink {
  std::string name;
  int parent_joint = -1;  ///< -1 for the root
  int parent_link = -1;
  std::vector<int> child_joints;
  std::vector<CollisionElement> collisions;

  bool hasGeometry() const { return !collisions.empty(); }
};

struct RobotModel {
  std::string name;
  std::string source;  ///< the file it was read from (for messages)
  std::vector<RobotLink> links;
  std::vector<RobotJoint> joints;
  /// The joint that owns each state value, by active index (a ball joint appears four times).
  std::vector<int> active_joints;
  std::vector<MultiDofJoint> multi_dof_joints;
  int root_link = 0;
  /// Non-fatal findings of the loader (dropped collision elements in warning mode, mimic
  /// tags on fixed joints, ...), one line each.
  std::vector<std::string> warnings;

  /// -1 when absent.
  int linkIndex(const std::string& name) const;
  int jointIndex(const std::string& name) const;
  /// Throws std::out_of_range naming the model and the missing name.
  int linkIndexOrThrow(const std::string& name) const;
  int jointIndexOrThrow(const std::string& name) const;

  /// The number of values in a state (the variables of the active joints).
  std::size_t numActiveJoints() const { return active_joints.size(); }
  /// The name of each state value, by active index: the joint's name, or for a ball joint
  /// J/rot the variable names J/rot_x, J/rot_y, J/rot_z, J/rot_w.
  std::vector<std::string> activeJointNames() const;
  /// The active index of a state value by its name (as activeJointNames gives it); -1 when
  /// absent (fixed and mimic joints have none).
  int variableIndex(const std::string& name) const;
  /// -1 when absent.
  int multiDofIndex(const std::string& name) const;
  std::size_t numCollisionElements() const;
  /// The nearest ancestor-or-self whose parent joint moves (the root when none): links with
  /// the same rigid ancestor never move relative to each other.
  int rigidAncestor(int link) const;
  /// The default state as MoveIt defines it: 0 for each active joint when 0 is within its
  /// limits, otherwise the middle of the limits.
  std::vector<double> defaultState() const;

  /// Rebuild the name maps (the loader calls it; needed after editing names by hand).
  void rebuildIndex();

 private:
  std::unordered_map<std::string, int> link_index_;
  std::unordered_map<std::string, int> joint_index_;
};

}  // namespace dss
