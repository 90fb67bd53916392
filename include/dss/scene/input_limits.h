// Input budgets of the scene and request readers (PlanningScene YAML, MoveIt .scene text,
// URDF worlds, MotionPlanRequest YAML), in one place.
//
// Users load scenes they did not write. YAML aliases let a small file stand for a huge one (a
// 156 KB scene can list a million obstacles, a 43 KB allowed-collision matrix millions of
// pairs), counts in a .scene file are arbitrary numbers and XML nests without bound; these
// limits turn such files into a clear error instead of exhausted memory, a stack overflow or
// minutes of work. The counts are taken after alias expansion. Each default sits far above
// every real file we know (the largest value seen in the scenes, requests and mesh files this
// project is tested on is given for each), and every error names the field that raises it:
// SceneLoadOptions::limits for the scene readers, PlanRequestOptions::limits for requests.
#pragma once

#include <cstddef>

namespace dss {

struct SceneInputLimits {
  /// Obstacles of one scene, i.e. primitives and meshes of all objects (largest seen: 21).
  static constexpr std::size_t kDefaultMaxObstacles = 100'000;
  /// Primitives plus meshes of one collision object or .scene object (largest seen: 8).
  static constexpr std::size_t kDefaultMaxShapesPerObject = 10'000;
  /// Names of an allowed collision matrix (entry_names, and default_entry_names); the matrix
  /// has this many squared values (largest seen: 20 names).
  static constexpr std::size_t kDefaultMaxAcmEntries = 1'000;
  /// Vertices of one mesh: inline, in a .scene file or read from a mesh file (largest seen:
  /// 130 419 in a robot mesh file, 432 in a scene).
  static constexpr std::size_t kDefaultMaxMeshVertices = 5'000'000;
  /// Triangles of one inline or .scene mesh (largest seen in a mesh file: 43 473).
  static constexpr std::size_t kDefaultMaxMeshTriangles = 10'000'000;
  /// Vertices of all meshes of one scene together (largest seen: 1 260, the kitchen world).
  static constexpr std::size_t kDefaultMaxSceneMeshVertices = 20'000'000;
  /// Element nesting of a URDF world, the root element being 1 (largest seen: 5). tinyxml and
  /// urdfdom parse recursively, so the text is scanned for this before parsing.
  static constexpr std::size_t kDefaultMaxXmlDepth = 256;
  /// Joint values of one MotionPlanRequest: start state joints plus goal joint constraints
  /// over all goals (largest seen: 18).
  static constexpr std::size_t kDefaultMaxRequestJointValues = 100'000;

  std::size_t max_obstacles = kDefaultMaxObstacles;
  std::size_t max_shapes_per_object = kDefaultMaxShapesPerObject;
  std::size_t max_acm_entries = kDefaultMaxAcmEntries;
  std::size_t max_mesh_vertices = kDefaultMaxMeshVertices;
  std::size_t max_mesh_triangles = kDefaultMaxMeshTriangles;
  std::size_t max_scene_mesh_vertices = kDefaultMaxSceneMeshVertices;
  std::size_t max_xml_depth = kDefaultMaxXmlDepth;
  std::size_t max_request_joint_values = kDefaultMaxRequestJointValues;
};

}  // namespace dss
