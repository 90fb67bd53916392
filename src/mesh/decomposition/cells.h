// Cells of the plane splits: the triangles clipped to a cell, as flat polygons, and its corners
// with the ids of the planes through them (labels are combinatorial, never re-derived from
// coordinates).
#pragma once

#include <vector>

#include "geometry.h"
#include "mesh_data.h"

namespace dss::mesh::decomposition {

// Clipped polygons, stored flat and in increasing element order.
struct Polygons {
  std::vector<int> element;
  std::vector<int> start{0};
  std::vector<Vec3> pts;
  std::size_t size() const { return element.size(); }
  void add(int e, const std::vector<Vec3>& poly) {
    element.push_back(e);
    pts.insert(pts.end(), poly.begin(), poly.end());
    start.push_back(static_cast<int>(pts.size()));
  }
};

// Keeps the part of polygon [first, last) where n·x <= o (Sutherland–Hodgman, one plane).
void clipPolygon(const Vec3* first, const Vec3* last, const Plane& plane, std::vector<Vec3>& out);

struct Corner {
  Vec3 p;
  std::vector<int> planes;  // ids of the cell planes through it, sorted
  bool keep = false;        // inside the solid, or too near its surface to tell
};

struct Cell {
  std::vector<Corner> corners;
  Polygons polys;
};

/// The root cell: the mesh's bounding box, grown so that the mesh lies strictly inside, with
/// every element as its polygon.
Cell rootCell(const MeshData& m);

/// The part of `cell` with n·x <= o. Without `polys_out` only the points of the clipped
/// polygons are kept (in out.polys.pts), which is all a piece's hull needs.
Cell clipCell(const Cell& cell, const Plane& plane, int plane_id, const MeshData& m,
              bool polys_out = true);

/// The piece points of a cell, with repeats (a vertex appears once per triangle using it).
std::vector<Vec3> cellPoints(const Cell& cell);

/// The polygons of two cells in one list, in increasing element order.
Polygons mergePolygons(const Polygons& a, const Polygons& b);

}  // namespace dss::mesh::decomposition
