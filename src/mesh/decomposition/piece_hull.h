// The convex hull of a piece's points as the search and the report need it: its points, the
// half-spaces that hold them, its volume and its box: from the facets of the points' hull
// (tessellate), or, for flat and tiny sets, from their box, their plane and their 2-D hull.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry.h"
#include "mesh_data.h"

namespace dss::mesh::decomposition {

struct Hull {
  std::vector<Vec3> points;   // the piece is conv(points)
  std::vector<Plane> planes;  // conv(points) lies in every half-space
  bool full = false;          // 3-D: the planes are the facets
  double volume = 0.0;
  Box box;
};

enum class HullMode {
  kRough,     // for ranking cuts: from a subset of the points when they are many
  kVertices,  // qhull's vertices: within qhull's rounding of the points' hull
  kExact,     // qhull's vertices and every point not proved inside them
};

/// The principal axes of `pts` (at least one point): the eigenvectors of their scatter matrix
/// about their mean, as columns by increasing eigenvalue (the last: the direction of largest
/// spread; the first: the normal of a best-fit plane).
Eigen::Matrix3d principalAxes(const std::vector<Vec3>& pts);

/// The hull of `pts` (see HullMode).
Hull buildHull(std::vector<Vec3> pts, const MeshData& m, HullMode mode);

}  // namespace dss::mesh::decomposition
