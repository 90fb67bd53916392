// Resolution of package://, file:// and relative mesh URIs (see dss/mesh/mesh_paths.h).
#include "dss/mesh/mesh_paths.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace dss {
namespace {

namespace fs = std::filesystem;

bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::vector<std::string> splitPath(const char* env) {
  std::vector<std::string> out;
  if (!env) return out;
  std::stringstream ss(env);
  std::string item;
  while (std::getline(ss, item, ':'))
    if (!item.empty()) out.push_back(item);
  return out;
}

// A directory named `pkg` at depth <= max_depth below `dir` (rospack crawls ROS_PACKAGE_PATH).
std::optional<fs::path> findPackageDir(const fs::path& dir, const std::string& pkg, int max_depth) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return std::nullopt;
  if (dir.filename() == pkg) return dir;
  if (fs::is_directory(dir / pkg, ec)) return dir / pkg;
  if (max_depth <= 0) return std::nullopt;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_directory(ec))
      if (auto found = findPackageDir(it->path(), pkg, max_depth - 1)) return found;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> resolveMeshUri(const std::string& uri, const std::string& urdf_dir,
                                          const MeshPathOptions& options,
                                          std::vector<std::string>* tried) {
  auto attempt = [&](const fs::path& p) -> std::optional<std::string> {
    if (tried) tried->push_back(p.string());
    if (isFile(p)) return p.lexically_normal().string();
    return std::nullopt;
  };
  const std::string kPackage = "package://", kFile = "file://";
  if (uri.rfind(kPackage, 0) == 0) {
    const std::string rest = uri.substr(kPackage.size());
    const auto slash = rest.find('/');
    const std::string pkg = rest.substr(0, slash);
    const std::string inner = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (const auto it = options.package_dirs.find(pkg); it != options.package_dirs.end())
      if (auto p = attempt(fs::path(it->second) / inner)) return p;
    if (options.use_ros_package_path)
      for (const auto& dir : splitPath(std::getenv("ROS_PACKAGE_PATH")))
        if (auto root = findPackageDir(dir, pkg, 3))
          if (auto p = attempt(*root / inner)) return p;
    if (options.use_ament_prefix_path)
      for (const auto& prefix : splitPath(std::getenv("AMENT_PREFIX_PATH")))
        if (auto p = attempt(fs::path(prefix) / "share" / pkg / inner)) return p;
    if (options.relative_to_urdf) {
      // package://meshes/x means <urdf dir>/meshes/x in some real URDFs (VAMP).
      if (auto p = attempt(fs::path(urdf_dir) / rest)) return p;
      if (auto p = attempt(fs::path(urdf_dir) / inner)) return p;
    }
    return std::nullopt;
  }
  std::string path = uri;
  if (uri.rfind(kFile, 0) == 0) path = uri.substr(kFile.size());
  fs::path p(path);
  if (p.is_relative()) p = fs::path(urdf_dir) / p;
  return attempt(p);
}

}  // namespace dss
