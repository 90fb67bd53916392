// A robot as the collision checker sees it: a kinematic tree of links and joints, each link
// carrying zero or more convex collision elements (primitives kept exact, meshes as hulls).
//
// Indices are dense and stable: links and joints are numbered in a depth-first order from the
// root, children in document order, so a parent always comes before its children. The joint
// values of a state are indexed by *active* joint index: the revolute, continuous and
// prismatic joints that are not mimic joints, in that same depth-first order. Mimic joints
// follow their leader (value = multiplier * leader + offset).
#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "dss/core/any_shape.h"

namespace dss {

enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic };

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

  bool isMoving() const { return type != JointType::kFixed; }
};

struct CollisionElement {
  AnyShape shape;
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();  ///< shape frame in the link frame
  std::string description;  ///< e.g. "link panda_link1 collision[0] mesh meshes/link1.stl"
  /// For a mesh: the file it was read from (resolved path) and the scale applied to its
  /// vertices; the shape is the hull of the scaled vertices. Empty for primitives.
  std::string mesh_path;
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
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
  std::vector<int> active_joints;  ///< joint index of each active joint, by active index
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

  std::size_t numActiveJoints() const { return active_joints.size(); }
  std::vector<std::string> activeJointNames() const;
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
