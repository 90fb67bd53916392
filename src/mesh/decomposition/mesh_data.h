// The mesh as the decomposition sees it: its elements with outward normals, its rounding
// scales, its reflex edges and an element tree, after checks that name what is wrong.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "dss/mesh/mesh.h"
#include "element_tree.h"
#include "geometry.h"

namespace dss::mesh::decomposition {

struct MeshData {
  std::vector<Vec3> v;
  // Triangles, then every vertex no triangle uses as a repeated-index element, so that it is
  // clipped, covered and measured like the rest.
  std::vector<std::array<int, 3>> elements;
  std::vector<Vec3> normal;  // unit, oriented out of the solid; zero for degenerate elements
  bool closed = false;
  // Closed, and every connected shell turns the same way as the whole: the winding number is
  // then >= 0 everywhere after orientation, which the face rule of the certificate relies on.
  bool face_rule = false;
  double size = 0.0;   // bounding-box diagonal
  double reach = 0.0;  // largest coordinate magnitude
  // Scales of rounding and of the tests built on it (setScales in mesh_data.cpp).
  double overlap = 0.0;   // sibling cells overlap by this much
  double near_eps = 0.0;  // a corner this close to the surface is kept without a verdict
  double on_eps = 0.0;    // a triangle this close to a facet plane lies on it
  double margin = 0.0;    // plane tests for points and boxes
  ElementTree tree;
  // Reflex (concave) edges, as endpoint pairs, and the ones each element holds (CSR): cut
  // planes through them separate convex parts where they meet.
  std::vector<std::array<Vec3, 2>> reflex;
  std::vector<int> reflex_start, reflex_ids;

  /// The winding number of the elements about p (solid angles).
  double winding(const Vec3& p) const;
  bool inside(const Vec3& p) const { return std::abs(crossings(p)) > 0.5; }
  /// The winding number of a closed mesh as the signed count of surface crossings along a ray.
  double crossings(const Vec3& p) const;
};

/// Directed welded edges; closed and edge-manifold when each appears once and its reverse once.
bool closedManifold(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris);

/// The mesh checked (finite vertices, indices in range; `what` names it in the error) and
/// prepared.
MeshData prepare(const TriangleMesh& mesh, const std::string& what);

}  // namespace dss::mesh::decomposition
