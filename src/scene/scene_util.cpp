// Checked inputs and mesh URIs for the scene readers.
#include "scene_util.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dss/mesh/mesh.h"
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

ConvexHull meshFileHull(const std::string& file, const Eigen::Vector3d& scale,
                        const std::string& where) {
  mesh::TriangleMesh m;
  try {
    m = mesh::loadMesh(file, scale);
  } catch (const std::exception& e) {
    throw SceneError(where + ": " + e.what());
  }
  if (m.vertices.empty()) throw SceneError(where + ": mesh '" + file + "' has no vertices");
  return pointsHull(m.vertices, where + " (mesh " + file + ")");
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
