// Input budgets of the robot readers (URDF, SRDF, the mesh files they name), in one place.
//
// Users load descriptions they did not write; these bounds turn a hostile or broken file into
// a clear error instead of a stack overflow, an endless expansion or exhausted memory. Each
// default sits far above every real description we know (the largest value seen in the robots
// and scenes this project is tested on is given for each), and every error names the field
// that raises it: LoadOptions::limits for loadUrdf, the `limits` argument of loadSrdf,
// parseSrdf and loadRobot.
#pragma once

#include <cstddef>

namespace dss {

struct RobotInputLimits {
  /// Element nesting of a URDF or SRDF document, the root element being 1 (largest seen: 5).
  /// tinyxml and urdfdom parse recursively, so the text is scanned for this before parsing.
  static constexpr std::size_t kDefaultMaxXmlDepth = 256;
  /// Subgroup nesting of an SRDF planning group, a group without subgroups being 1 (largest
  /// seen: 2).
  static constexpr std::size_t kDefaultMaxGroupDepth = 64;
  /// Vertices of one collision mesh after the mesh file's node instancing (largest seen:
  /// 130 419, robotiq_fts300.stl).
  static constexpr std::size_t kDefaultMaxMeshVertices = 5'000'000;

  std::size_t max_xml_depth = kDefaultMaxXmlDepth;
  std::size_t max_group_depth = kDefaultMaxGroupDepth;
  std::size_t max_mesh_vertices = kDefaultMaxMeshVertices;
};

}  // namespace dss
