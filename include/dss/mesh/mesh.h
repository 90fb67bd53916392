// Triangle meshes from files, their convex hulls, and triangle tessellations of primitives.
//
// A mesh enters the collision model only as its convex hull ("a mesh is its convex hull"),
// so loading keeps vertices and triangles and nothing else. Files are read with assimp: STL
// (binary and ASCII), OBJ and Collada (DAE). For Collada the <unit> scale is applied and the
// up-axis is ignored, as RViz and MoveIt do, so that a DAE written Z-up is not rotated.
// Hulls are built with qhull (reentrant API) and carry their vertex adjacency so that the
// core's support function can hill-climb; flat, collinear and single-point sets, where qhull
// has no 3-D hull, fall back to the distinct input points (support by linear scan), which is
// exact because the support of conv(V) is the maximum over V.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "dss/core/any_shape.h"
#include "dss/core/convex_hull.h"

namespace dss::mesh {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// Reads a mesh file (STL binary/ASCII, COLLADA .dae or OBJ, through assimp, after the checks of
/// src/mesh/mesh_file_check.h: other formats, Collada counts larger than the file and stray
/// characters in its number lists are errors), applies the node transforms of the file
/// (Collada units included, up-axis ignored) and then `scale` per axis.
/// A negative scale component mirrors the mesh (triangles are flipped to stay outward when
/// the mirroring is odd). Throws std::runtime_error naming the path: missing file, unreadable
/// file, no vertices, a non-finite vertex or a non-finite scale; std::length_error (also
/// naming the path) when the file's meshes, counted once per node that instances them, have
/// more than `max_vertices` vertices.
TriangleMesh loadMesh(const std::string& path,
                      const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                      std::size_t max_vertices = std::numeric_limits<std::size_t>::max());

/// The convex hull of `points`, with vertex adjacency when the set is full-dimensional.
/// Flat (coplanar), collinear, single-point and tiny sets return the distinct points without
/// adjacency. `what` names the source in error messages, e.g.
/// "link panda_link1 collision[0] (…/link1.stl)". Throws std::runtime_error on empty or
/// non-finite input.
dss::ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points, const std::string& what);

/// Statistics of the last hull built (for reports): whether qhull produced a 3-D hull.
struct HullInfo {
  std::size_t input_points = 0;
  std::size_t hull_vertices = 0;
  bool full_dimensional = false;
};
dss::ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points, const std::string& what,
                           HullInfo* info);

/// A closed triangle surface approximating `shape` with its vertices on the surface (so the
/// hull of the tessellation is inside the shape, within r·(1 - cos(pi/resolution)) of it):
/// box (8 vertices), sphere and ellipsoid (latitude-longitude grid, `resolution` segments
/// around, resolution/2 bands), cylinder, cone and capsule (`resolution` segments around),
/// convex hull (its qhull facets; a flat hull gives its points and no triangles).
/// Throws std::invalid_argument for resolution < 3.
TriangleMesh tessellate(const dss::AnyShape& shape, int resolution = 16);

}  // namespace dss::mesh
