// The connected parts of a triangle mesh, as the point sets whose convex hulls stand for it.
//
// A mesh that holds several separate solids (the boards of a shelf exported as one file, a door
// and its handle) is covered far more tightly by one hull per part than by the hull of the
// whole: the space between the parts stays free. Triangles belong to one part when they are
// linked through shared vertices, with vertices identified by their exact coordinates (STL
// files repeat every vertex per triangle). Every vertex lies in the point set of its part, so
// the hulls of the parts cover every triangle and, for a closed mesh, its solid: each part of a
// closed edge-manifold mesh is itself closed, and a point inside the solid has a non-zero
// winding number about some part, hence lies in that part's hull.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "dss/mesh/mesh.h"

namespace dss::mesh {

/// The point sets of the connected parts of `mesh` (each point once), in the order of each
/// part's first triangle, then the vertices no triangle uses as one more set. With more than
/// `max_parts` sets, neighbouring sets are joined into `max_parts` groups: ordered by their
/// centroid along the longest side of the mesh's bounding box and cut into runs of nearly equal
/// count (a joined group's hull still covers its sets). Deterministic.
/// Throws std::runtime_error naming `what` for a mesh without vertices, a triangle index out of
/// range, or max_parts == 0.
std::vector<std::vector<Eigen::Vector3d>> meshParts(const TriangleMesh& mesh, std::size_t max_parts,
                                                    const std::string& what);

/// A lower bound on how far `hull` (one part's hull, or any hull containing triangles of `mesh`)
/// reaches beyond the mesh: the largest distance from a point of the hull's surface to the
/// mesh's triangles, over the centroids and edge midpoints of the hull's facet triangles (every
/// k-th of them when their count times the mesh's size exceeds `max_work`). Points on the hull's
/// surface are never inside a closed mesh's solid, so the bound holds for open and closed meshes
/// alike. 0 for a mesh without triangles, and without measuring when the mesh's vertices and
/// triangles exceed `max_work`. A concave or open part (a cupboard's carcass open at the front)
/// reaches far; a convex solid's hull reaches nowhere (rounding aside).
double hullExcess(const TriangleMesh& mesh, const dss::ConvexHull& hull,
                  std::size_t max_work = std::size_t(1) << 22);

}  // namespace dss::mesh
