// Checked inputs and mesh URIs for the scene readers.
#include "scene_util.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "../common/nesting_scan.h"
#include "dss/mesh/mesh.h"
#include "dss/mesh/mesh_parts.h"
#include "dss/mesh/mesh_paths.h"
#include "dss/scene/scene_error.h"

namespace fs = std::filesystem;

namespace dss {
namespace scene_detail {

Eigen::Quaterniond checkedQuaternion(double x, double y, double z, double w,
                                     const std::string& where) {
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  std::ostringstream q;
  q << "[" << x << ", " << y << ", " << z << ", " << w << "]";
  if (!std::isfinite(n)) throw SceneError(where + ": non-finite quaternion " + q.str());
  // A zero quaternion is no rotation at all (MoveIt warns and substitutes identity; we refuse
  // since the file is wrong). Anything else is normalised, as MoveIt does.
  if (n < 1e-9) throw SceneError(where + ": zero quaternion " + q.str());
  return Eigen::Quaterniond(w / n, x / n, y / n, z / n);
}

void checkSize(double v, const std::string& what, const std::string& where) {
  if (!std::isfinite(v)) throw SceneError(where + ": non-finite " + what);
  if (v < 0) {
    std::ostringstream s;
    s << where << ": negative " << what << " (" << v << ")";
    throw SceneError(s.str());
  }
}

void checkMeshScale(const Eigen::Vector3d& scale, const std::string& where) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(scale[i]) || scale[i] == 0) {
      std::ostringstream s;
      s << where << ": mesh scale component "
        << "xyz"[i] << " is " << scale[i] << " (scale \"" << scale.x() << " " << scale.y() << " "
        << scale.z() << "\"): it must be finite and non-zero, or the mesh collapses";
      throw SceneError(s.str());
    }
}

void makeObstacleNamesUnique(Scene& scene) {
  // Every name as read is reserved first, so that a renamed obstacle never takes the name an
  // obstacle further on was given.
  std::unordered_set<std::string> taken;
  for (const Obstacle& o : scene.obstacles) taken.insert(o.name);
  std::unordered_set<std::string> kept;
  for (Obstacle& o : scene.obstacles) {
    if (kept.insert(o.name).second) continue;
    for (std::size_t n = 2;; ++n) {
      std::string candidate = o.name + "#" + std::to_string(n);
      if (taken.insert(candidate).second) {
        o.name = std::move(candidate);
        kept.insert(o.name);
        break;
      }
    }
  }
}

std::string parentDir(const std::string& path) {
  const fs::path p = fs::path(path).parent_path();
  return p.empty() ? std::string(".") : p.string();
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string resolveMeshUri(const std::string& uri, const std::string& base_dir,
                           const SceneLoadOptions& options, const std::string& where) {
  // One search order for robots and scenes: dss::resolveMeshUri (dss/mesh/mesh_paths.h).
  static const std::string kPackage = "package://";
  if (uri.compare(0, kPackage.size(), kPackage) == 0) {
    const std::string rest = uri.substr(kPackage.size());
    const auto slash = rest.find('/');
    if (slash == std::string::npos || slash == 0)
      throw SceneError(where + ": malformed package URI '" + uri + "'");
  }
  MeshPathOptions mp;
  mp.package_dirs = options.package_dirs;
  std::vector<std::string> tried;
  if (auto file = dss::resolveMeshUri(uri, base_dir, mp, &tried)) return *file;
  std::string msg = where + ": cannot resolve mesh '" + uri + "' (tried";
  for (const auto& p : tried) msg += " " + p;
  throw SceneError(msg + ")");
}

std::string overLimit(const std::string& what, std::size_t limit, const std::string& field,
                      const std::string& options) {
  return what + " exceeds the limit of " + std::to_string(limit) + " (SceneInputLimits::" + field +
         "; raise it with " + options + "::limits." + field + ")";
}

void MeshBudget::take(std::size_t count, const std::string& where, bool more) {
  const std::string size = (more ? "more than " : "") + std::to_string(count) + " vertices";
  if (count > limits_.max_mesh_vertices || (more && count == limits_.max_mesh_vertices))
    throw SceneError(
        where + ": " +
        overLimit("a mesh of " + size, limits_.max_mesh_vertices, "max_mesh_vertices"));
  const std::size_t left = remaining();
  if (count > left || (more && count == left))
    throw SceneError(where + ": " +
                     overLimit("the scene's mesh vertices (" + std::to_string(used_) +
                                   " before this mesh of " + size + ")",
                               limits_.max_scene_mesh_vertices, "max_scene_mesh_vertices"));
  used_ += count;
}

std::size_t MeshBudget::remaining() const {
  const std::size_t scene_left =
      limits_.max_scene_mesh_vertices - std::min(used_, limits_.max_scene_mesh_vertices);
  return std::min(limits_.max_mesh_vertices, scene_left);
}

std::string partName(const std::string& what, std::size_t k, std::size_t n) {
  return n == 1 ? what : what + " part " + std::to_string(k) + " of " + std::to_string(n);
}

std::string obstacleRoom(const std::string& what, std::size_t count, std::size_t before,
                         const SceneInputLimits& limits) {
  if (before <= limits.max_obstacles && count <= limits.max_obstacles - before) return {};
  return overLimit(what + ": " + std::to_string(count) + " shapes and mesh parts after " +
                       std::to_string(before) + " obstacles",
                   limits.max_obstacles, "max_obstacles");
}

std::vector<ConvexHull> meshHulls(const mesh::TriangleMesh& m, std::size_t max_parts,
                                  const std::string& where, std::vector<std::string>& warnings) {
  std::vector<std::vector<Eigen::Vector3d>> parts;
  try {
    parts = mesh::meshParts(m, max_parts, where);
  } catch (const std::exception& e) {
    throw SceneError(e.what());
  }
  std::vector<ConvexHull> hulls;
  hulls.reserve(parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::string part = partName(where, k, parts.size());
    hulls.push_back(pointsHull(parts[k], part));
    // The measure's budget is shared by the parts: a large mesh loads without a long wait.
    const double excess = mesh::hullExcess(m, hulls.back(), (std::size_t(1) << 24) / parts.size());
    if (excess > kHullExcessWarning) {
      std::ostringstream w;
      w.precision(3);
      w << part << ": its convex hull reaches at least " << excess
        << " m beyond the mesh (a concave or open part): states in that space count as "
           "colliding";
      warnings.push_back(w.str());
    }
  }
  return hulls;
}

std::vector<ConvexHull> meshFileHulls(const std::string& file, const Eigen::Vector3d& scale,
                                      const std::string& where, MeshBudget& budget,
                                      std::size_t max_parts, std::vector<std::string>& warnings) {
  const std::string what = where + " (mesh " + file + ")";
  mesh::TriangleMesh m;
  const std::size_t cap = budget.remaining();
  try {
    m = mesh::loadMesh(file, scale, cap);
  } catch (const std::length_error&) {
    budget.take(cap, what, /*more=*/true);  // throws, naming the limit
  } catch (const std::exception& e) {
    throw SceneError(where + ": " + e.what());
  }
  if (m.vertices.empty()) throw SceneError(where + ": mesh '" + file + "' has no vertices");
  budget.take(m.vertices.size(), what);
  return meshHulls(m, max_parts, what, warnings);
}

void checkXmlDepth(const std::string& text, const std::string& file,
                   const SceneInputLimits& limits) {
  const input_scan::NestingExcess e = input_scan::xmlNesting(text, limits.max_xml_depth);
  if (e.exceeded)
    throw SceneError(file + ":" + std::to_string(e.line) + ":" + std::to_string(e.column) + ": " +
                     overLimit("XML element nesting", limits.max_xml_depth, "max_xml_depth"));
}

ConvexHull pointsHull(const std::vector<Eigen::Vector3d>& points, const std::string& where) {
  if (points.empty()) throw SceneError(where + ": mesh has no vertices");
  try {
    return mesh::convexHull(points, where);
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(where + ": " + e.what());
  }
}

}  // namespace scene_detail
}  // namespace dss
