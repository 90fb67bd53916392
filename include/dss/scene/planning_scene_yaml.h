// MoveIt `moveit_msgs/PlanningScene` in YAML, as MotionBenchMaker and robowflex write it.
//
// Read: `name`, `robot_model_name`, `robot_state.joint_state`, `fixed_frame_transforms`,
// `allowed_collision_matrix` (entry_names/entry_values, default_entry_names/values) and
// `world.collision_objects[]`: `id`, `header.frame_id`, an optional object-level `pose`
// (moveit_msgs >= Noetic: shape poses are relative to it, so X_FO = pose * primitive_pose),
// `primitives[]` with `primitive_poses[]` (box [x, y, z] full edges; sphere [radius];
// cylinder and cone [height, radius], SolidPrimitive order; `type` as a name or the
// SolidPrimitive number), and `meshes[]` with `mesh_poses[]`, each mesh given inline
// (`vertices` as [x, y, z] or {x, y, z}, `triangles` as [a, b, c] or {vertex_indices})
// or by `resource` (a path or package:// URI, optional `dimensions`/`scale` [sx, sy, sz]);
// a mesh becomes the convex hull of its vertices. Positions are [x, y, z] or {x, y, z};
// orientations [x, y, z, w] or {x, y, z, w}, normalised; NaN or zero quaternions refused.
// `planes` (unbounded) and operations other than ADD are refused; attached objects and
// octomaps are listed in Scene::warnings. A top-level document that is itself a `world`
// mapping's content (only `collision_objects`) is also accepted.
#pragma once

#include <string>

#include "dss/scene/scene.h"
#include "dss/scene/scene_load_options.h"

namespace dss {

/// Reads a PlanningScene YAML file. Throws SceneError ("file:line: ...", naming the object).
Scene loadPlanningSceneYaml(const std::string& path, const SceneLoadOptions& options = {});

/// As above from text; `source` names it in messages and is the base of relative mesh paths
/// (its folder).
Scene parsePlanningSceneYaml(const std::string& text, const std::string& source,
                             const SceneLoadOptions& options = {});

}  // namespace dss
