// A MoveIt `moveit_msgs/MotionPlanRequest` in YAML, reduced to what a joint-space planning
// problem needs: the group, the start joint state and the joint goal constraints.
//
// Cartesian goal constraints (position, orientation, visibility) are refused: the planners
// here take joint goals only. Missing tolerances are 0, as in the message's defaults
// (MotionBenchMaker gives none).
//
// Keys: every mapping read (the request, start_state and its joint states, each goal's
// Constraints and JointConstraint) may hold only the fields of its moveit_msgs message. An
// unknown key (e.g. `goal_constraint`, `Position`) is an error naming the key and the line, as
// a ROS message would fail to deserialize with it; PlanRequestOptions::unknown_keys_are_warnings
// turns it into a line in PlanRequest::warnings. A key given twice in one mapping is always an
// error (yaml-cpp would keep one value silently). Fields of the message that a joint-space
// problem does not use (path_constraints, the scaling factors, ...) are accepted and not read.
// The start state's multi-DOF joint transforms are kept by joint name (a planar or floating
// joint's values, multi_dof.h), and workspace_parameters' corners bound such joints. The start
// joints plus all goal joint constraints are bounded by
// PlanRequestOptions::limits.max_request_joint_values, counted after YAML alias expansion.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "dss/scene/attached_object.h"
#include "dss/scene/input_limits.h"

namespace dss {

struct PlanRequestOptions {
  /// max_request_joint_values, and for the start state's attached objects those of a scene.
  SceneInputLimits limits;
  /// An unknown key becomes a line in PlanRequest::warnings instead of an error.
  bool unknown_keys_are_warnings = false;
};

struct JointConstraint {
  std::string joint_name;
  double position = 0.0;
  double tolerance_above = 0.0;
  double tolerance_below = 0.0;
  double weight = 1.0;
};

/// One `goal_constraints[]` entry: all its joint constraints hold together.
struct GoalConstraint {
  std::string name;
  std::vector<JointConstraint> joint_constraints;
};

struct PlanRequest {
  std::string source;
  std::string group_name;
  std::string planner_id;
  std::vector<std::string> start_names;
  std::vector<double> start_positions;
  /// start_state.multi_dof_joint_state: one transform per joint name, in file order.
  std::vector<std::pair<std::string, Eigen::Isometry3d>> start_multi_dof;
  /// start_state.attached_collision_objects, read as a PlanningScene's (at_request_start set).
  /// MoveIt plans with them held: append them to the scene's Scene::attached before
  /// setupModel / makeProblem (dss_plan does).
  std::vector<AttachedObject> start_attached;
  /// workspace_parameters' min_corner and max_corner, when given.
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> workspace;
  /// Any one of these goals satisfies the request (MoveIt semantics).
  std::vector<GoalConstraint> goals;
  double allowed_planning_time = 0.0;
  int num_planning_attempts = 0;
  std::vector<std::string> warnings;

  /// Start state by joint name.
  std::map<std::string, double> startState() const;
};

/// Checks a request's joints against a robot: every goal joint must be in `movable`; a start
/// joint must be in `movable` or in `held` (joints the robot has but does not move, e.g. the
/// UR5 gripper joints that are fixed in its URDF: ignored). Throws SceneError naming the file
/// and the joint otherwise; returns the start joints that were ignored.
std::vector<std::string> checkRequestJoints(const PlanRequest& request,
                                            const std::set<std::string>& movable,
                                            const std::set<std::string>& held);

/// Throws SceneError ("file:line: ...") on malformed YAML, a missing group_name, mismatched
/// name/position lengths, non-finite values, non-joint goal constraints, an unknown or
/// repeated key, or more joint values than the limit.
PlanRequest loadPlanRequestYaml(const std::string& path);
PlanRequest loadPlanRequestYaml(const std::string& path, const PlanRequestOptions& options);
PlanRequest parsePlanRequestYaml(const std::string& text, const std::string& source);
PlanRequest parsePlanRequestYaml(const std::string& text, const std::string& source,
                                 const PlanRequestOptions& options);

}  // namespace dss
