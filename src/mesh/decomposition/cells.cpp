// Cells and their clipped polygons (see cells.h).
#include "cells.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace dss::mesh::decomposition {

void clipPolygon(const Vec3* first, const Vec3* last, const Plane& plane, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t k = static_cast<std::size_t>(last - first);
  double s_prev = plane.n.dot(first[k - 1]) - plane.o;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = first[(i + k - 1) % k];
    const Vec3& b = first[i];
    const double s = plane.n.dot(b) - plane.o;
    if ((s_prev <= 0.0) != (s <= 0.0)) out.push_back(a + (s_prev / (s_prev - s)) * (b - a));
    if (s <= 0.0) out.push_back(b);
    s_prev = s;
  }
}

Cell rootCell(const MeshData& m) {
  Box box;
  for (const Vec3& p : m.v) box.add(p);
  // The box must hold the mesh strictly inside: its corners are then outside the solid.
  const Vec3 grow = Vec3::Constant(1e-3 * m.size + 1e3 * m.near_eps + 1e-300);
  box.lo -= grow;
  box.hi += grow;
  Cell cell;
  for (int i = 0; i < 8; ++i) {
    Corner c;
    c.p = Vec3((i & 1) ? box.hi.x() : box.lo.x(), (i & 2) ? box.hi.y() : box.lo.y(),
               (i & 4) ? box.hi.z() : box.lo.z());
    c.planes = {(i & 1) ? 0 : 1, (i & 2) ? 2 : 3, (i & 4) ? 4 : 5};
    cell.corners.push_back(std::move(c));
  }
  std::vector<Vec3> tri(3);
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    for (int k = 0; k < 3; ++k) tri[k] = m.v[m.elements[e][k]];
    cell.polys.add(static_cast<int>(e), tri);
  }
  return cell;
}

Cell clipCell(const Cell& cell, const Plane& plane, int plane_id, const MeshData& m,
              bool polys_out) {
  Cell out;
  std::vector<Vec3> poly;
  for (std::size_t i = 0; i < cell.polys.size(); ++i) {
    const Vec3* first = cell.polys.pts.data() + cell.polys.start[i];
    const Vec3* last = cell.polys.pts.data() + cell.polys.start[i + 1];
    clipPolygon(first, last, plane, poly);
    if (poly.empty()) continue;
    if (polys_out)
      out.polys.add(cell.polys.element[i], poly);
    else
      out.polys.pts.insert(out.polys.pts.end(), poly.begin(), poly.end());
  }
  // Corners: those on the kept side, and where an edge of the cell (two corners sharing two
  // planes) crosses the plane. Labels are combinatorial, never re-derived from coordinates.
  std::vector<double> s(cell.corners.size());
  for (std::size_t i = 0; i < cell.corners.size(); ++i)
    s[i] = plane.n.dot(cell.corners[i].p) - plane.o;
  std::vector<int> common;
  for (std::size_t i = 0; i < cell.corners.size(); ++i) {
    if (s[i] > 0.0) continue;
    out.corners.push_back(cell.corners[i]);
    for (std::size_t j = 0; j < cell.corners.size(); ++j) {
      if (s[j] <= 0.0) continue;
      const Corner& a = cell.corners[i];
      const Corner& b = cell.corners[j];
      common.clear();
      std::set_intersection(a.planes.begin(), a.planes.end(), b.planes.begin(), b.planes.end(),
                            std::back_inserter(common));
      if (common.size() < 2) continue;
      Corner c;
      c.p = a.p + (s[i] / (s[i] - s[j])) * (b.p - a.p);
      c.planes = common;
      c.planes.push_back(plane_id);
      std::sort(c.planes.begin(), c.planes.end());
      if (m.closed) {
        // Any doubt keeps the corner: an extra point only enlarges the piece.
        c.keep = m.tree.nearest(c.p) <= m.near_eps || m.inside(c.p);
      }
      out.corners.push_back(std::move(c));
    }
  }
  return out;
}

std::vector<Vec3> cellPoints(const Cell& cell) {
  std::vector<Vec3> pts = cell.polys.pts;
  for (const Corner& c : cell.corners)
    if (c.keep) pts.push_back(c.p);
  return pts;
}

Polygons mergePolygons(const Polygons& a, const Polygons& b) {
  Polygons out;
  std::size_t i = 0, j = 0;
  std::vector<Vec3> poly;
  auto take = [&](const Polygons& p, std::size_t k) {
    poly.assign(p.pts.begin() + p.start[k], p.pts.begin() + p.start[k + 1]);
    out.add(p.element[k], poly);
  };
  while (i < a.size() || j < b.size()) {
    if (j >= b.size() || (i < a.size() && a.element[i] <= b.element[j]))
      take(a, i++);
    else
      take(b, j++);
  }
  return out;
}

}  // namespace dss::mesh::decomposition
