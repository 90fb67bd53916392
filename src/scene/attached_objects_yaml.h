// The attached collision objects of a moveit_msgs/RobotState in YAML (internal): the
// PlanningScene reader's own, for the start state of a MotionPlanRequest.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "dss/scene/attached_object.h"
#include "dss/scene/scene_load_options.h"

namespace dss {
namespace scene_detail {

/// Reads `list` (a robot state's attached_collision_objects, in the YAML text of `source`;
/// `where` names it in messages) as the PlanningScene reader reads a scene's: each object's
/// parts, link_name and touch_links, ids unique within the list. Meshes resolve against the
/// source's folder. Appends the reader's warnings to `warnings`; throws as that reader does.
std::vector<AttachedObject> readAttachedObjectsYaml(const YAML::Node& list,
                                                    const std::string& source,
                                                    const std::string& where,
                                                    const SceneLoadOptions& options,
                                                    std::vector<std::string>& warnings);

}  // namespace scene_detail
}  // namespace dss
