// Reading a robot from a URDF file into a RobotModel.
//
// urdfdom parses the kinematic tree; a separate XML scan counts every <collision> element of
// every link, because urdfdom silently drops collision elements after an unknown geometry
// tag (e.g. <capsule>). Every <collision> that did not become a shape is an error by default
// (`LoadOptions::allow_dropped_collisions` turns it into a loud warning, recorded in
// RobotModel::warnings and printed to stderr). Primitives stay exact (box, sphere, cylinder
// of URDF radius and length along z); meshes become convex hulls, or the convex pieces of a
// decomposition that covers them (LoadOptions::meshes). Planar and floating joints become
// chains of one-variable joints (multi_dof.h). Every error is a std::runtime_error whose
// message names the file and the element (link, joint, collision index, line).
// The joints must form a tree: a link that is the child of two joints (a closed chain or a
// cycle) and links that cannot be reached from the root (a detached cycle), both of which
// urdfdom accepts, are errors naming the links and joints. A mesh `scale` component of zero is
// an error; a negative one mirrors the mesh (the hull is that of the mirrored vertices, as in
// the URDF-world reader). Input budgets (XML nesting, vertices per mesh) are
// LoadOptions::limits (dss/robot/input_limits.h). Elements and attributes that URDF does not
// define (e.g. <gazebo>, <transmission>, vendor extensions) are ignored, as urdfdom and so
// MoveIt ignore them; inside <collision><geometry>, an unknown tag is a dropped collision
// (above), never skipped silently.
// Not thread safe: urdfdom reports through the process-wide console_bridge handler, which is
// swapped for the duration of a load to capture its messages.
#pragma once

#include <map>
#include <string>

#include "dss/mesh/decomposition_cache.h"
#include "dss/mesh/mesh_paths.h"
#include "dss/robot/input_limits.h"
#include "dss/robot/robot_model.h"

namespace dss {

/// How a mesh <collision> becomes convex elements.
enum class MeshGeometry {
  kHull,       ///< one element: the mesh's convex hull
  kDecompose,  ///< the convex pieces of mesh::decomposeConvex (one, the hull, when the hull's
               ///< concavity already meets the tolerance); pieces cover the mesh and its solid
};

struct MeshGeometryOptions {
  MeshGeometry geometry = MeshGeometry::kHull;  ///< every link's meshes...
  std::map<std::string, MeshGeometry> links;    ///< ...unless its link is named here
  mesh::DecompositionOptions decomposition;     ///< tolerance (m) and piece cap
  /// Where decompositions are cached (decomposition_cache.h); empty: no cache.
  std::string cache_dir = mesh::defaultDecompositionCacheDir();
};

struct LoadOptions {
  MeshPathOptions mesh_paths;
  MeshGeometryOptions meshes;
  /// false (default): a <collision> that did not become a shape is an error.
  bool allow_dropped_collisions = false;
  /// Load collision geometry at all (false: kinematics only).
  bool load_collisions = true;
  /// Counts and depths beyond which a file is refused.
  RobotInputLimits limits;
};

RobotModel loadUrdf(const std::string& path, const LoadOptions& options = {});

/// As loadUrdf, from text; `source` names it in messages and `base_dir` anchors relative
/// mesh paths.
RobotModel loadUrdfString(const std::string& xml, const std::string& source,
                          const std::string& base_dir, const LoadOptions& options = {});

}  // namespace dss
