// Helpers shared by the scene readers (internal): checked quaternions and sizes, and mesh
// URIs turned into files and convex hulls.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "dss/core/convex_hull.h"
#include "dss/scene/scene_load_options.h"

namespace dss {
namespace scene_detail {

/// A unit quaternion from x, y, z, w; `where` prefixes the message of the SceneError thrown
/// for a non-finite or zero quaternion.
Eigen::Quaterniond checkedQuaternion(double x, double y, double z, double w,
                                     const std::string& where);

/// Throws unless v is finite and >= 0.
void checkSize(double v, const std::string& what, const std::string& where);

/// The file a mesh URI points to: package:// through options.package_dirs,
/// ROS_PACKAGE_PATH, AMENT_PREFIX_PATH (share/<pkg>) and then `base_dir` (some files use
/// package://meshes/... for their own folder); file:// and relative paths against base_dir.
std::string resolveMeshUri(const std::string& uri, const std::string& base_dir,
                           const SceneLoadOptions& options, const std::string& where);

/// The convex hull of a mesh file, scaled.
ConvexHull meshFileHull(const std::string& file, const Eigen::Vector3d& scale,
                        const std::string& where);

/// The convex hull of inline vertices.
ConvexHull pointsHull(const std::vector<Eigen::Vector3d>& points, const std::string& where);

/// Folder of a path ("" -> ".").
std::string parentDir(const std::string& path);

/// Whole file as text; SceneError naming the file when it cannot be read.
std::string readTextFile(const std::string& path);

}  // namespace scene_detail
}  // namespace dss
