// Options shared by the scene readers: where `package://` mesh URIs live and which values
// the movable joints of a URDF world take.
#pragma once

#include <map>
#include <string>

namespace dss {

struct SceneLoadOptions {
  /// Package name -> directory, tried first for `package://name/...` mesh URIs; then
  /// ROS_PACKAGE_PATH and AMENT_PREFIX_PATH (share/name), then the scene file's own folder.
  std::map<std::string, std::string> package_dirs;
  /// URDF world: values of its non-fixed joints (others are set to 0; see urdf_world.h).
  std::map<std::string, double> joint_values;
  /// URDF world: refuse a URDF with non-fixed joints instead of posing them.
  bool urdf_require_fixed_joints = false;
};

}  // namespace dss
