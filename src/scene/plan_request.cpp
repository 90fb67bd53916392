// Reader of moveit_msgs/MotionPlanRequest YAML (joint-space requests).
#include "dss/scene/plan_request.h"

#include <initializer_list>
#include <set>

#include "attached_objects_yaml.h"
#include "dss/scene/scene_error.h"
#include "scene_util.h"
#include "yaml_util.h"

namespace dss {

using scene_detail::YamlReader;

std::map<std::string, double> PlanRequest::startState() const {
  std::map<std::string, double> m;
  for (std::size_t i = 0; i < start_names.size() && i < start_positions.size(); ++i)
    m[start_names[i]] = start_positions[i];
  return m;
}

namespace {

// Fields of the messages read (moveit_msgs as of ROS Noetic and ROS 2).
constexpr std::initializer_list<const char*> kMotionPlanRequestKeys = {
    "workspace_parameters",
    "start_state",
    "goal_constraints",
    "path_constraints",
    "trajectory_constraints",
    "reference_trajectories",
    "pipeline_id",
    "planner_id",
    "group_name",
    "num_planning_attempts",
    "allowed_planning_time",
    "max_velocity_scaling_factor",
    "max_acceleration_scaling_factor",
    "cartesian_speed_end_effector_link",
    "cartesian_speed_limited_link",
    "max_cartesian_speed"};
constexpr std::initializer_list<const char*> kRobotStateKeys = {
    "joint_state", "multi_dof_joint_state", "attached_collision_objects", "is_diff"};
constexpr std::initializer_list<const char*> kConstraintsKeys = {
    "name", "joint_constraints", "position_constraints", "orientation_constraints",
    "visibility_constraints"};
constexpr std::initializer_list<const char*> kJointConstraintKeys = {
    "joint_name", "position", "tolerance_above", "tolerance_below", "weight"};

}  // namespace

PlanRequest parsePlanRequestYaml(const std::string& text, const std::string& source) {
  return parsePlanRequestYaml(text, source, PlanRequestOptions{});
}

PlanRequest parsePlanRequestYaml(const std::string& text, const std::string& source,
                                 const PlanRequestOptions& options) {
  PlanRequest r;
  r.source = source;
  YamlReader y(source);
  y.setUnknownKeyPolicy(options.unknown_keys_are_warnings, &r.warnings,
                        "PlanRequestOptions::unknown_keys_are_warnings");
  const YAML::Node root = y.load(text);
  if (!root.IsMap()) y.fail(root, "expected a MotionPlanRequest mapping at the top level");
  y.checkKeys(root, "request", "moveit_msgs/MotionPlanRequest", kMotionPlanRequestKeys);
  const std::size_t max_values = options.limits.max_request_joint_values;
  auto overLimit = [&](const YAML::Node& n, const std::string& what) {
    y.fail(n, scene_detail::overLimit(what, max_values, "max_request_joint_values",
                                      "PlanRequestOptions"));
  };
  r.group_name = y.string(y.require(root, "group_name", "request"), "group_name");
  if (r.group_name.empty()) y.fail(root["group_name"], "request: empty group_name");
  if (YamlReader::has(root, "planner_id"))
    r.planner_id = y.string(root["planner_id"], "planner_id");
  if (YamlReader::has(root, "allowed_planning_time"))
    r.allowed_planning_time = y.number(root["allowed_planning_time"], "allowed_planning_time");
  if (YamlReader::has(root, "num_planning_attempts"))
    r.num_planning_attempts = y.integer(root["num_planning_attempts"], "num_planning_attempts");

  if (YamlReader::has(root, "workspace_parameters")) {
    const YAML::Node ws = root["workspace_parameters"];
    y.checkKeys(ws, "workspace_parameters", "moveit_msgs/WorkspaceParameters",
                {"header", "min_corner", "max_corner"});
    const Eigen::Vector3d lo =
        y.vector3(y.require(ws, "min_corner", "workspace_parameters"), "min_corner");
    const Eigen::Vector3d hi =
        y.vector3(y.require(ws, "max_corner", "workspace_parameters"), "max_corner");
    for (int k = 0; k < 3; ++k)
      if (!(lo[k] <= hi[k]))
        y.fail(ws, std::string("workspace_parameters: min_corner.") + "xyz"[k] +
                       " is above max_corner." + "xyz"[k]);
    r.workspace.emplace(lo, hi);
  }

  // Constraints along the path are not something a collision checker enforces: said, not
  // dropped silently.
  auto nonEmptyList = [](const YAML::Node& n, const char* key) {
    if (!n.IsMap()) return false;
    const YAML::Node l = YamlReader::optional(n, key);
    return l.IsDefined() && l.IsSequence() && l.size() > 0;
  };
  if (YamlReader::has(root, "path_constraints")) {
    const YAML::Node pc = root["path_constraints"];
    bool any = false;
    for (const char* k : {"joint_constraints", "position_constraints", "orientation_constraints",
                          "visibility_constraints"})
      any = any || nonEmptyList(pc, k);
    if (any) r.warnings.push_back(y.at(pc) + ": path_constraints not enforced (ignored)");
  }
  if (YamlReader::has(root, "trajectory_constraints") &&
      nonEmptyList(root["trajectory_constraints"], "constraints"))
    r.warnings.push_back(y.at(root["trajectory_constraints"]) +
                         ": trajectory_constraints not enforced (ignored)");

  const YAML::Node start = y.require(root, "start_state", "request");
  y.checkKeys(start, "start_state", "moveit_msgs/RobotState", kRobotStateKeys);
  if (YamlReader::has(start, "joint_state")) {
    const YAML::Node js = start["joint_state"];
    y.checkKeys(js, "start_state.joint_state", "sensor_msgs/JointState",
                {"header", "name", "position", "velocity", "effort"});
    const YAML::Node names =
        y.sequence(y.require(js, "name", "start_state.joint_state"), "start_state name");
    const YAML::Node pos =
        y.sequence(y.require(js, "position", "start_state.joint_state"), "start_state position");
    if (names.size() != pos.size())
      y.fail(js, "start_state.joint_state: " + std::to_string(names.size()) + " names but " +
                     std::to_string(pos.size()) + " positions");
    if (names.size() > max_values)
      overLimit(names, "start_state: " + std::to_string(names.size()) + " joints");
    for (std::size_t i = 0; i < names.size(); ++i) {
      r.start_names.push_back(y.string(names[i], "start_state name"));
      r.start_positions.push_back(
          y.number(pos[i], "start_state position of '" + r.start_names.back() + "'"));
    }
  }
  if (YamlReader::has(start, "multi_dof_joint_state"))
    r.start_multi_dof =
        y.multiDofJointState(start["multi_dof_joint_state"], "start_state.multi_dof_joint_state",
                             max_values - r.start_names.size(), [&](std::size_t n) {
                               return scene_detail::overLimit(
                                   "start_state: " + std::to_string(n) + " multi-DOF joints (and " +
                                       std::to_string(r.start_names.size()) + " joints)",
                                   max_values, "max_request_joint_values", "PlanRequestOptions");
                             });
  if (YamlReader::has(start, "attached_collision_objects")) {
    SceneLoadOptions scene_options;
    scene_options.limits = options.limits;
    scene_options.unknown_keys_are_warnings = options.unknown_keys_are_warnings;
    r.start_attached = scene_detail::readAttachedObjectsYaml(
        start["attached_collision_objects"], source, "start_state.attached_collision_objects",
        scene_options, r.warnings);
    for (AttachedObject& a : r.start_attached) a.at_request_start = true;
  }

  const YAML::Node goals =
      y.sequence(y.require(root, "goal_constraints", "request"), "goal_constraints");
  if (goals.size() == 0) y.fail(goals, "request: goal_constraints is empty");
  // Start joints and goal joint constraints together, counted before any goal is read:
  // aliases let a short text repeat long lists.
  std::size_t constraints = 0;
  for (std::size_t g = 0; g < goals.size(); ++g) {
    const YAML::Node jcs = YamlReader::optional(goals[g], "joint_constraints");
    if (jcs.IsDefined() && jcs.IsSequence()) constraints += jcs.size();
  }
  if (constraints > max_values - r.start_names.size())
    overLimit(goals, "goal_constraints: " + std::to_string(constraints) + " joint constraints in " +
                         std::to_string(goals.size()) + " goals (and " +
                         std::to_string(r.start_names.size()) + " start joints)");
  for (std::size_t g = 0; g < goals.size(); ++g) {
    const std::string ge = "goal_constraints[" + std::to_string(g) + "]";
    const YAML::Node gc = goals[g];
    if (!gc.IsMap()) y.fail(gc, ge + ": expected a mapping");
    y.checkKeys(gc, ge, "moveit_msgs/Constraints", kConstraintsKeys);
    for (const char* other :
         {"position_constraints", "orientation_constraints", "visibility_constraints"}) {
      const YAML::Node o = YamlReader::optional(gc, other);
      if (o.IsDefined() && o.IsSequence() && o.size() > 0)
        y.fail(o, ge + ": " + other + " not supported (joint goals only)");
    }
    GoalConstraint goal;
    if (YamlReader::has(gc, "name")) goal.name = y.string(gc["name"], ge + " name");
    const YAML::Node jcs =
        y.sequence(y.require(gc, "joint_constraints", ge), ge + " joint_constraints");
    if (jcs.size() == 0) y.fail(jcs, ge + ": no joint constraints");
    for (const auto& jc : jcs) {
      y.checkKeys(jc, ge + " joint constraint", "moveit_msgs/JointConstraint",
                  kJointConstraintKeys);
      JointConstraint c;
      c.joint_name = y.string(y.require(jc, "joint_name", ge + " joint constraint"), "joint_name");
      const std::string ce = ge + " joint '" + c.joint_name + "'";
      c.position = y.number(y.require(jc, "position", ce), ce + " position");
      if (YamlReader::has(jc, "tolerance_above"))
        c.tolerance_above = y.number(jc["tolerance_above"], ce + " tolerance_above");
      if (YamlReader::has(jc, "tolerance_below"))
        c.tolerance_below = y.number(jc["tolerance_below"], ce + " tolerance_below");
      if (c.tolerance_above < 0 || c.tolerance_below < 0) y.fail(jc, ce + ": negative tolerance");
      if (YamlReader::has(jc, "weight")) c.weight = y.number(jc["weight"], ce + " weight");
      goal.joint_constraints.push_back(c);
    }
    r.goals.push_back(std::move(goal));
  }
  return r;
}

std::vector<std::string> checkRequestJoints(const PlanRequest& request,
                                            const std::set<std::string>& movable,
                                            const std::set<std::string>& held) {
  std::vector<std::string> ignored;
  for (const auto& n : request.start_names) {
    if (movable.count(n)) continue;
    if (!held.count(n))
      throw SceneError(request.source + ": start state names joint '" + n +
                       "', which the robot lacks");
    ignored.push_back(n);
  }
  for (std::size_t g = 0; g < request.goals.size(); ++g)
    for (const auto& c : request.goals[g].joint_constraints)
      if (!movable.count(c.joint_name))
        throw SceneError(request.source + ": goal_constraints[" + std::to_string(g) +
                         "] names joint '" + c.joint_name +
                         "', which is not a movable joint of "
                         "the robot");
  return ignored;
}

PlanRequest loadPlanRequestYaml(const std::string& path) {
  return parsePlanRequestYaml(scene_detail::readTextFile(path), path, PlanRequestOptions{});
}

PlanRequest loadPlanRequestYaml(const std::string& path, const PlanRequestOptions& options) {
  return parsePlanRequestYaml(scene_detail::readTextFile(path), path, options);
}

}  // namespace dss
