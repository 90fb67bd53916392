// Picks a scene reader by file extension.
#include "dss/scene/scene_loader.h"

#include <algorithm>
#include <filesystem>

#include "dss/scene/planning_scene_yaml.h"
#include "dss/scene/scene_error.h"
#include "dss/scene/scene_text.h"
#include "dss/scene/urdf_world.h"

namespace dss {

Scene loadScene(const std::string& path, const SceneLoadOptions& options) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".yaml" || ext == ".yml") return loadPlanningSceneYaml(path, options);
  if (ext == ".scene") return loadSceneText(path, options);
  if (ext == ".urdf" || ext == ".xml") return loadUrdfWorld(path, options);
  throw SceneError(path + ": unknown scene format '" + ext +
                   "' (expected .yaml, .yml, .scene or .urdf)");
}

}  // namespace dss
