// A MoveIt `moveit_msgs/MotionPlanRequest` in YAML, reduced to what a joint-space planning
// problem needs: the group, the start joint state and the joint goal constraints.
//
// Cartesian goal constraints (position, orientation, visibility) are refused: the planners
// here take joint goals only. Missing tolerances are 0, as in the message's defaults
// (MotionBenchMaker gives none).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace dss {

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
/// name/position lengths, non-finite values or non-joint goal constraints.
PlanRequest loadPlanRequestYaml(const std::string& path);
PlanRequest parsePlanRequestYaml(const std::string& text, const std::string& source);

}  // namespace dss
