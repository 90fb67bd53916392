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
// a mesh becomes the convex hulls of its connected parts (mesh/mesh_parts.h; the hull of
// its vertices when it has no triangles), one obstacle each. Positions are [x, y, z] or {x, y, z};
// orientations [x, y, z, w] or {x, y, z, w}, normalised; NaN or zero quaternions refused.
// `robot_state.attached_collision_objects[]`: `link_name`, `object` (read as a world
// object; its id must differ from every other object's) and `touch_links`, into
// Scene::attached (`detach_posture` and `weight` accepted, not read).
// `planes` (unbounded) and operations other than ADD are refused; octomaps are listed in
// Scene::warnings. A top-level document that is itself a `world` mapping's content (only
// `collision_objects`) is also accepted.
//
// Keys: every mapping read may hold only the fields of its ROS message (PlanningScene,
// PlanningSceneWorld, RobotState, JointState, MultiDOFJointState, TransformStamped,
// AllowedCollisionMatrix and its entries, CollisionObject, AttachedCollisionObject, Header,
// SolidPrimitive, Pose, Point, Quaternion, Mesh, MeshTriangle) plus the extensions above. A key
// the message lacks (e.g. `Pose`, `primitve_poses`) is an error naming the key, the line and
// the fields the message has, because deserializing the ROS message from such YAML fails too
// (rostopic pub, ros2 topic pub); SceneLoadOptions::unknown_keys_are_warnings turns it into a
// line in Scene::warnings instead. A key given twice in one mapping is always an error (YAML
// requires unique keys; yaml-cpp would keep one value silently). Fields we do not use
// (object_colors, is_diff, subframes, octomap content, ...) are accepted and not read. A
// collision object id given twice (world or attached) is an error naming both lines: MoveIt's
// ADD would replace the first object by the second, silently.
// Budgets: obstacles, shapes per object, allowed-collision-matrix names, mesh vertices and
// triangles are counted after alias expansion and bounded by SceneLoadOptions::limits
// (dss/scene/input_limits.h) before they are read; an error names the limit.
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
