// Conservative approximate convex decomposition of a triangle mesh: a few convex pieces whose
// union contains every triangle and, for a closed mesh, its solid. A piece is the hull of the
// mesh clipped to one cell of recursive plane splits, plus the cell's corners inside the solid
// (the bounding-mesh construction of Gaschler), so no cut section needs capping; each carries a
// concavity certified by a branch-and-bound octree, and cuts go where that concavity is (Lien
// and Amato, "Approximate convex decomposition of polyhedra", CAGD 25 (2008)).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "dss/mesh/mesh.h"

namespace dss::mesh {

struct DecompositionOptions {
  /// Target concavity of every piece, in the mesh's length unit (metres for robot links).
  double tolerance = 0.008;
  /// Most pieces returned. When reached, the pieces report the concavity they have left.
  int max_pieces = 8;
};

struct ConvexPiece {
  /// The piece is conv(points). Every point lies on a triangle, inside the solid, or (a cell
  /// corner too near the surface to classify) within 1e-9 of the mesh's size of the surface, so
  /// conv(points) lies in conv(mesh) up to rounding.
  std::vector<Eigen::Vector3d> points;
  /// Certified upper bound of max over x in conv(points) of the distance from x to the mesh:
  /// to the solid for a closed mesh (0 inside it), to the nearest triangle otherwise. Never
  /// below the true value; the search stops within 10 % of it (or a tenth of the tolerance)
  /// when its box budget allows.
  double concavity = 0.0;
};

struct Decomposition {
  std::vector<ConvexPiece> pieces;
  /// The mesh is closed and edge-manifold (isClosedManifold), so the pieces cover its solid,
  /// not only its triangles.
  bool closed = false;
  /// The concavity bound of the single hull of the whole mesh (what the pieces improve on).
  double hull_concavity = 0.0;
  /// The largest concavity over the pieces.
  double max_concavity = 0.0;
};

/// Cuts `mesh` into at most options.max_pieces convex pieces, each of concavity at most
/// options.tolerance when the search reaches that within the cap. Cuts go to the piece of
/// largest concavity first, along planes through its deepest pocket, its reflex edges and an
/// even sweep, ranked by the concavity of the two sides; pieces whose joint hull meets the
/// tolerance are merged, and at the cap a merge of two better pieces may buy another cut of the
/// worst one. Pieces whose largest concavity is not below 4/5 of the single hull's give way to
/// that hull (one piece): they would cost more checks than they save false alarms.
///
/// Guarantee: every vertex of the mesh lies in some piece (exactly: it is a piece point or
/// inside a piece by a margin far above rounding); every point of every triangle and, when
/// `closed`, every point of the solid lies in some piece, up to the rounding of the computed cut
/// points (a few units in the last place of the coordinates). Every piece lies in the mesh's
/// convex hull up to the same rounding. A vertex that no triangle uses counts as a point of the
/// mesh and is covered too. The output is deterministic.
///
/// Throws std::runtime_error naming `what` when the mesh has no vertex, a non-finite vertex or
/// a triangle with an index out of range, or when the options are unusable (tolerance not
/// positive and finite, max_pieces < 1).
Decomposition decomposeConvex(const TriangleMesh& mesh, const DecompositionOptions& options,
                              const std::string& what);

/// Whether every triangle edge, with vertices identified by their exact coordinates, is shared
/// by exactly two triangles that traverse it in opposite directions (a closed, consistently
/// oriented, edge-manifold surface). Such a mesh bounds a solid: the points of non-zero winding
/// number. False for a mesh without triangles.
bool isClosedManifold(const TriangleMesh& mesh);

/// The generalized winding number of the mesh around p (the sum of the triangles' signed solid
/// angles over 4π): an integer for a closed mesh (±1 inside a simple solid, 0 outside), a
/// smooth value in between for an open one. Points on the surface give an arbitrary value.
/// Throws std::runtime_error for a vertex index out of range (as do the functions below).
double windingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p);

/// |windingNumber(mesh, p)| > 1/2: exact for a closed mesh away from its surface (orientation
/// inward or outward alike), a robust vote for a mesh with small holes.
bool insideSolid(const TriangleMesh& mesh, const Eigen::Vector3d& p);

/// Distance from p to the nearest point of the mesh's triangles (or unused vertices); the
/// nearest point is written to `nearest` when given. Throws std::runtime_error for a mesh
/// without vertices.
double distanceToMesh(const TriangleMesh& mesh, const Eigen::Vector3d& p,
                      Eigen::Vector3d* nearest = nullptr);

}  // namespace dss::mesh
