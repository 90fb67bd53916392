// Options shared by the scene readers: where `package://` mesh URIs live, which values the
// movable joints of a URDF world take, the input budgets and how strictly YAML keys are read.
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include "dss/scene/input_limits.h"

namespace dss {

struct SceneLoadOptions {
  /// Package name -> directory, tried first for `package://name/...` mesh URIs; then
  /// ROS_PACKAGE_PATH and AMENT_PREFIX_PATH (share/name), then the scene file's own folder.
  std::map<std::string, std::string> package_dirs;
  /// URDF world: values of its non-fixed joints (others are set to 0; see urdf_world.h).
  std::map<std::string, double> joint_values;
  /// URDF world: refuse a URDF with non-fixed joints instead of posing them.
  bool urdf_require_fixed_joints = false;
  /// A mesh obstacle becomes the convex hulls of its connected parts (mesh/mesh_parts.h), each
  /// an obstacle of its object, at most this many per mesh (neighbouring parts are joined
  /// beyond it); 1 takes every mesh as one hull.
  std::size_t max_mesh_parts = 16;
  /// Counts and depths beyond which a file is refused (see input_limits.h).
  SceneInputLimits limits;
  /// PlanningScene YAML: a key that the message at that place does not have (e.g. `Pose` or
  /// `primitve_poses`) is an error by default, as when deserializing the ROS message; true
  /// makes it a line in Scene::warnings instead (the key is then ignored).
  bool unknown_keys_are_warnings = false;
};

}  // namespace dss
