// Vertices identified by their exact coordinates (internal to dss::mesh): STL files repeat
// every vertex per triangle, and both the parts of a mesh and its closedness are about the
// welded surface.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace dss::mesh::detail {

/// One id per vertex, equal for equal coordinates, numbered in the lexicographic order of the
/// coordinates (0, 1, ... without gaps).
std::vector<int> weldedIds(const std::vector<Eigen::Vector3d>& v);

}  // namespace dss::mesh::detail
