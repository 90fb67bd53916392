// Triangulated convex hulls through qhull (reentrant C API), for the benchmark's FCL convex
// shapes, hull adjacency and the exact separating-axis reference.
#pragma once

#include <array>
#include <vector>

#include "dss/core/types.h"

namespace dss {
namespace bench {

/// Outward-oriented (counter-clockwise seen from outside) triangles of the convex hull of
/// `points` (indices into `points`), triangulated with qhull's Qt. Throws std::runtime_error
/// when qhull fails (fewer than 4 points, flat sets).
std::vector<std::array<int, 3>> hullTriangles(const std::vector<Vec3d>& points);

/// Outward orientation of triangles given in any order: flips each triangle whose normal
/// points towards `interior`.
void orientOutward(const std::vector<Vec3d>& points, const Vec3d& interior,
                   std::vector<std::array<int, 3>>& triangles);

}  // namespace bench
}  // namespace dss
