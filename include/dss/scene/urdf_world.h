// A URDF used as a world (e.g. MotionBenchMaker's kitchen): every link's collision geometry,
// placed at the link's pose with all joints held still.
//
// Decision on movable joints: a revolute, prismatic or continuous joint is held at the value
// given in SceneLoadOptions::joint_values, else at 0 (within its limits, else at the nearest
// limit), and a line is added to Scene::warnings naming the joint and the value used;
// with `urdf_require_fixed_joints` such a joint is an error instead. Floating and planar
// joints are refused. Primitives stay exact (box, sphere, cylinder); meshes (with their
// `scale`) become the convex hulls of their connected parts (mesh/mesh_parts.h).
// Mesh URIs: package:// through SceneLoadOptions::package_dirs,
// then <dir>/pkg for each ROS_PACKAGE_PATH entry (or the entry itself when it is named pkg),
// then AMENT_PREFIX_PATH/share/pkg, then the URDF's folder; file:// and relative paths.
// The URDF's root link is the world frame. A link's shapes (a collision element, or each part
// of a mesh) are obstacles named "link" (one shape) or "link/k"; their object_id is the link
// name. A `<collision>` element
// that urdfdom did not turn into geometry (e.g. after an unknown tag) is an error.
// urdfdom's own messages are captured (console_bridge's global output handler is swapped for
// the duration of the parse) and put in the exception or in Scene::warnings; do not load
// URDFs from several threads at once.
// The joints must form a tree: a link that is the child of two joints (a closed chain or a
// cycle) and links that cannot be reached from the root (a detached cycle), which urdfdom
// accepts, are errors naming the links and joints with their lines; the poses are computed
// without recursion. A mesh scale component of zero (or not finite) is an error; a negative
// one mirrors the mesh, as in the robot loader. Input budgets (XML nesting checked on the raw
// text before parsing, obstacles, mesh vertices) are SceneLoadOptions::limits. Elements that
// URDF does not define are ignored, as urdfdom ignores them.
#pragma once

#include <string>

#include "dss/scene/scene.h"
#include "dss/scene/scene_load_options.h"

namespace dss {

Scene loadUrdfWorld(const std::string& path, const SceneLoadOptions& options = {});

}  // namespace dss
