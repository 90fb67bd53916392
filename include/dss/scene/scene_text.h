// MoveIt's `.scene` text format (PlanningScene::loadGeometryFromStream), both versions.
//
//   scene name line
//   * object id
//   [x y z                      new format only: the object pose
//    qx qy qz qw]
//   shape count
//   per shape: type line (box | sphere | cylinder | cone | mesh), dimensions (box: x y z;
//              sphere: r; cylinder and cone: radius length; mesh: "v t", v vertex lines,
//              t triangle lines), position line, quaternion x y z w line, RGBA line
//   [subframe count, per subframe: name, position, quaternion]      new format only
//   .
//
// As MoveIt does, the line after `* id` decides the version: with spaces it is the object
// position (new format), without it is the shape count (old format). Shape poses are
// relative to the object pose. Poses are in the world frame. A mesh becomes the convex hulls
// of its connected parts (mesh/mesh_parts.h), one obstacle each. Errors name the file and line.
// An object id given twice is an error naming both lines (MoveIt would add the second
// object's shapes to the first and move them all to the second pose).
// Counts are digits only and bounded before use by SceneLoadOptions::limits (shapes per
// object, obstacles, vertices and triangles per mesh, mesh vertices per scene); a count over
// its limit is an error naming the line and the limit. Only `limits` of the options applies.
#pragma once

#include <string>

#include "dss/scene/scene.h"
#include "dss/scene/scene_load_options.h"

namespace dss {

Scene loadSceneText(const std::string& path, const SceneLoadOptions& options = {});
Scene parseSceneText(const std::string& text, const std::string& source,
                     const SceneLoadOptions& options = {});

}  // namespace dss
