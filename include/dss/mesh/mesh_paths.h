// Where a URDF mesh URI points on disk.
//
// `package://pkg/rest` is looked up, in order, in the explicit package directories given
// (pkg -> root, the root holding `rest` directly), then in every directory of
// ROS_PACKAGE_PATH (a folder named pkg at any depth up to 3 below it, as rospack does with its
// crawl, and <dir>/pkg), then AMENT_PREFIX_PATH (<prefix>/share/pkg), and last relative to
// the URDF's own folder (some real URDFs write `package://meshes/...` to mean the folder of
// the URDF). `file:///abs` and absolute paths are used as they are; relative paths are
// relative to the URDF's folder.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dss {

struct MeshPathOptions {
  /// package name -> root directory of that package.
  std::map<std::string, std::string> package_dirs;
  bool use_ros_package_path = true;   ///< read ROS_PACKAGE_PATH
  bool use_ament_prefix_path = true;  ///< read AMENT_PREFIX_PATH
  bool relative_to_urdf = true;       ///< last resort for package:// URIs
};

/// The existing file a URI refers to, or nullopt. `tried` (optional) receives every candidate
/// path that was checked, for error messages.
std::optional<std::string> resolveMeshUri(const std::string& uri, const std::string& urdf_dir,
                                          const MeshPathOptions& options,
                                          std::vector<std::string>* tried = nullptr);

}  // namespace dss
