// One entry point for every scene format: picks the reader by the file's extension
// (.yaml/.yml: PlanningScene YAML; .scene: MoveIt text; .urdf/.xml: URDF world).
#pragma once

#include <string>

#include "dss/scene/scene.h"
#include "dss/scene/scene_load_options.h"

namespace dss {

/// Throws SceneError for an unknown extension or anything the chosen reader refuses.
Scene loadScene(const std::string& path, const SceneLoadOptions& options = {});

}  // namespace dss
