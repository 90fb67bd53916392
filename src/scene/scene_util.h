// Helpers shared by the scene readers (internal): checked quaternions and sizes, and mesh
// URIs turned into files and convex hulls.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "dss/core/convex_hull.h"
#include "dss/mesh/mesh.h"
#include "dss/scene/scene.h"
#include "dss/scene/scene_load_options.h"

namespace dss {
namespace scene_detail {

/// A unit quaternion from x, y, z, w; `where` prefixes the message of the SceneError thrown
/// for a non-finite or zero quaternion.
Eigen::Quaterniond checkedQuaternion(double x, double y, double z, double w,
                                     const std::string& where);

/// Throws unless v is finite and >= 0.
void checkSize(double v, const std::string& what, const std::string& where);

/// A URDF mesh scale: every component finite and non-zero (zero would flatten the mesh to a
/// plane, a line or a point). A negative component mirrors the mesh and is accepted, as URDF
/// allows it; the hull is that of the mirrored vertices.
void checkMeshScale(const Eigen::Vector3d& scale, const std::string& where);

/// The file a mesh URI points to: package:// through options.package_dirs,
/// ROS_PACKAGE_PATH, AMENT_PREFIX_PATH (share/<pkg>) and then `base_dir` (some files use
/// package://meshes/... for their own folder); file:// and relative paths against base_dir.
std::string resolveMeshUri(const std::string& uri, const std::string& base_dir,
                           const SceneLoadOptions& options, const std::string& where);

/// What to say when an input exceeds one of the SceneInputLimits: "<what> exceeds the limit
/// of <limit> (SceneInputLimits::<field>; raise it with <options>::limits.<field>)".
std::string overLimit(const std::string& what, std::size_t limit, const std::string& field,
                      const std::string& options = "SceneLoadOptions");

/// Counts the mesh vertices of one scene against the per-mesh and per-scene limits; throws
/// SceneError prefixed by `where`.
class MeshBudget {
 public:
  explicit MeshBudget(const SceneInputLimits& limits) : limits_(limits) {}
  /// Before using a mesh of `count` vertices (`more`: of more than `count`); checks the
  /// per-mesh and the per-scene limit.
  void take(std::size_t count, const std::string& where, bool more = false);
  /// What a mesh may still have: the smaller of the two limits.
  std::size_t remaining() const;
  const SceneInputLimits& limits() const { return limits_; }

 private:
  const SceneInputLimits& limits_;
  std::size_t used_ = 0;
};

/// `what` for the only part of a mesh, else "<what> part k of n".
std::string partName(const std::string& what, std::size_t k, std::size_t n);

/// Empty when an object's `count` shapes and mesh parts fit after the scene's `before`
/// obstacles (limits.max_obstacles), else the message naming `what` and the limit.
std::string obstacleRoom(const std::string& what, std::size_t count, std::size_t before,
                         const SceneInputLimits& limits);

/// A part's hull reaching farther than this beyond its mesh gets a line in Scene::warnings.
inline constexpr double kHullExcessWarning = 0.01;

/// The convex hulls of a mesh's connected parts (mesh/mesh_parts.h), at most `max_parts`
/// (SceneLoadOptions::max_mesh_parts); a line in `warnings` for each hull that reaches more
/// than kHullExcessWarning beyond the mesh (mesh::hullExcess). SceneError prefixed by `where`
/// for a bad mesh.
std::vector<ConvexHull> meshHulls(const mesh::TriangleMesh& m, std::size_t max_parts,
                                  const std::string& where, std::vector<std::string>& warnings);

/// The hulls of a mesh file's parts, scaled, as meshHulls; its vertices are taken from
/// `budget`.
std::vector<ConvexHull> meshFileHulls(const std::string& file, const Eigen::Vector3d& scale,
                                      const std::string& where, MeshBudget& budget,
                                      std::size_t max_parts, std::vector<std::string>& warnings);

/// The convex hull of inline vertices.
ConvexHull pointsHull(const std::vector<Eigen::Vector3d>& points, const std::string& where);

/// Throws SceneError ("file:line:column: ...") when the element nesting of XML `text` exceeds
/// limits.max_xml_depth, before a recursive parser sees it.
void checkXmlDepth(const std::string& text, const std::string& file,
                   const SceneInputLimits& limits);

/// Obstacle names are the object id, or "id/k" for shape k of a several-shape object, and an
/// id may itself hold a '/': object "a/1" and shape 1 of object "a" would share a name. The
/// later of two equal names gets "#2" appended (or the first free "#n"), so that every name
/// is unique in the scene, as Obstacle::name promises.
void makeObstacleNamesUnique(Scene& scene);

/// Folder of a path ("" -> ".").
std::string parentDir(const std::string& path);

/// Whole file as text; SceneError naming the file when it cannot be read.
std::string readTextFile(const std::string& path);

}  // namespace scene_detail
}  // namespace dss
